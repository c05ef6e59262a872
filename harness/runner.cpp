// An experiment: the plan's runs of this invocation selected, the results folder made and held,
// what an earlier invocation left resumed (harness/resume.h), the sweep run (harness/sweep.h: each
// run the pipeline of harness/run_pipeline.h), and the folder's files completed. `rtbench merge`
// is harness/shard_merge.cpp.
#include "runner.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "device/vulkan_context.h"
#include "harness/columns.h"
#include "harness/embree_reference.h"
#include "harness/images.h"
#include "harness/interrupt_note.h"
#include "harness/output_folder.h"
#include "harness/plan_view.h"
#include "harness/resume.h"
#include "harness/run_columns.h"
#include "harness/run_inputs.h"
#include "harness/sweep.h"
#include "harness/timing_rounds.h"
#include "harness/version.h"
#include "scene/scene_description.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// What is needed to re-run and to judge the experiment: written when the sweep starts, with every
// device it uses already opened (complete: false), and once more at its end (complete: true). The
// runs done are runs.csv's rows, so `rtbench check` works on an interrupted sweep, and a run's
// bookkeeping does not grow with the plan.
Json contextJson(const ExperimentPlan& plan, const RunnerOptions& options, const Caches& caches,
                 const std::string& startedUtc, bool complete) {
    Json j;
    j["command"] = options.commandLine;
    j["config_path"] = plan.configPath;
    j["config_text"] = plan.configText;
    j["config_dir"] = plan.configDir;
    j["overrides"] = Json::object();  // the command line's -d, --validation, --embree-config
    for (const auto& [key, value] : plan.overrides) j["overrides"][key] = value;
    if (!plan.settings.empty()) j["settings"] = plan.settings;  // the command line's --set, applied over config_text
    j["shard"] = options.shardCount > 1 ? std::to_string(options.shardIndex) + "/" + std::to_string(options.shardCount) : "";
    j["schema_version"] = kSchemaVersion;
    j["git_commit"] = gitCommit();
    j["date_utc"] = startedUtc;
    j["complete"] = complete;
    j["host"] = hostName();
    j["cpu"] = cpuModel();
    j["cpu_threads"] = std::thread::hardware_concurrency();
    j["embree_version"] = EmbreeReference::version();
    j["images"] = imagesSupported() ? "OpenImageIO" : "hit records only";
    j["devices"] = Json::array();
    for (const auto& [key, vk] : caches.devices) {
        const DeviceInfo& d = vk->info();
        j["devices"].push_back({{"name", d.name}, {"driver", d.driver}, {"api", d.apiVersion}, {"type", d.type},
                                {"subgroup_size", d.subgroupSize}, {"lock_step_subgroups", d.lockStepSubgroups},
                                {"max_storage_buffer_range", d.maxStorageBufferRange},
                                {"timestamp_period_ns", d.timestampPeriodNs}, {"ray_query", d.rayQuery}});
    }
    j["plan"] = Json::array();
    for (const RunConfig& run : plan.runs)
        j["plan"].push_back({{"run", runNumber(run)}, {"config_hash", run.hash()}, {"label", run.label()}});
    return j;
}

// "file:line" of the first line of the config text that gives `value` as a quoted string, else
// the file alone (a value from --set, or written another way).
std::string whereInConfig(const ExperimentPlan& plan, const std::string& value) {
    std::istringstream lines(plan.configText);
    std::string line;
    for (int n = 1; std::getline(lines, line); ++n)
        if (line.find("\"" + value + "\"") != std::string::npos || line.find("'" + value + "'") != std::string::npos)
            return plan.configPath + ":" + std::to_string(n);
    return plan.configPath;
}

// Every scene.source the runs name exists (scene/scene_description.h checkSceneSource);
// else an error naming the config's line, the key, the source and its runs.
void checkSceneSources(const ExperimentPlan& plan, const std::vector<const RunConfig*>& runs) {
    std::map<std::string, std::vector<std::string>> bySource;
    for (const RunConfig* run : runs) bySource[run->getString("scene.source")].push_back(runNumber(*run));
    for (const auto& [source, numbers] : bySource) {
        try {
            checkSceneSource(source, plan.configDir);
        } catch (const Error& e) {
            std::string which;
            for (std::size_t i = 0; i < numbers.size() && i < 6; ++i) which += (i ? ", " : "") + numbers[i];
            if (numbers.size() > 6) which += ", ... (" + std::to_string(numbers.size()) + " runs)";
            throw Error(whereInConfig(plan, source) + ": key 'scene.source' = \"" + source + "\" (run " + which + "): " + e.what() +
                        "; nothing was run");
        }
    }
}

}  // namespace

std::string runNumber(const RunConfig& run) {
    char index[16];
    std::snprintf(index, sizeof index, "%03zu", run.index);
    return index;
}

std::string consoleNumber(const std::string& cell) {
    char* end = nullptr;
    const double value = std::strtod(cell.c_str(), &end);
    if (cell.empty() || *end != '\0' || !std::isfinite(value)) return cell;
    char text[32];
    std::snprintf(text, sizeof text, std::fabs(value) >= 100.0 ? "%.0f" : "%.3g", value);
    return text;
}

std::string summaryTable(const std::vector<Row>& rows) {
    // Speed (with the ratio's 95% interval) and the exact accuracy; the swept parameters last, whole.
    std::ostringstream out;
    auto get = [](const Row& r, const char* key) {
        auto it = r.find(key);
        return it == r.end() || it->second.empty() ? std::string("-") : it->second;
    };
    auto number = [&](const Row& r, const char* key) { return consoleNumber(get(r, key)); };
    out << std::left << std::setw(5) << "run" << std::right << std::setw(13) << "kernel Mr/s" << std::setw(14)
        << "Embree1 Mr/s" << std::setw(10) << "ratio" << std::setw(22) << "ratio 95% interval" << std::setw(12)
        << "wrong ppm" << std::setw(9) << "status" << "  " << std::left << "parameters (wrong ppm: against the exact reference)\n";
    for (const Row& r : rows) {
        const std::string interval = get(r, "speed_ratio_ci_low") == "-" ? "-"
                                     : "[" + number(r, "speed_ratio_ci_low") + ", " + number(r, "speed_ratio_ci_high") + "]";
        out << std::left << std::setw(5) << get(r, "run") << std::right << std::setw(13) << number(r, "kernel_mrays_s")
            << std::setw(14) << number(r, "embree1_mrays_s") << std::setw(10) << number(r, "speed_ratio_vs_embree1") << std::setw(22)
            << interval << std::setw(12) << number(r, "exact_wrong_ppm") << std::setw(9) << get(r, "status") << "  " << std::left
            << get(r, "label") << (get(r, "timing_warning") == "-" ? "" : " [timing_warning]")
            << (get(r, "warnings") == "-" ? "" : " [warning]") << "\n";
    }
    for (const Row& r : rows)
        if (get(r, "status") == "failed") out << "run " << get(r, "run") << " failed: " << get(r, "error") << "\n";
    return out.str();
}

namespace {
// Rows of two lists by run number (this invocation's and those --filter carried over).
std::vector<Row> inRunOrder(std::vector<Row> rows, const std::vector<Row>& more) {
    rows.insert(rows.end(), more.begin(), more.end());
    std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.at("run") < b.at("run"); });
    return rows;
}

std::string shardSuffix(const RunnerOptions& options) {
    if (options.shardCount <= 1) return "";
    return ".shard-" + std::to_string(options.shardIndex) + "-of-" + std::to_string(options.shardCount);
}
}  // namespace

std::string runsFileName(const RunnerOptions& options) { return "runs" + shardSuffix(options) + ".csv"; }
std::string contextFileName(const RunnerOptions& options) { return "context" + shardSuffix(options) + ".json"; }
std::string samplesFileName(const RunnerOptions& options) { return "samples" + shardSuffix(options) + ".csv"; }

namespace {

// The plan's runs this invocation runs: its shard's, --only's and --filter's.
std::vector<const RunConfig*> selectRuns(const ExperimentPlan& plan, const RunnerOptions& options) {
    if (options.shardCount == 0 || options.shardIndex >= options.shardCount)
        throw Error("--shard " + std::to_string(options.shardIndex) + "/" + std::to_string(options.shardCount) +
                    ": expected i/N with 0 <= i < N");
    if (plan.runs.empty()) throw Error(plan.configPath + ": the plan has no runs");
    std::set<const RunConfig*> selected;  // --filter's
    for (const RunConfig* run : filterRuns(plan, options.filters)) selected.insert(run);
    std::vector<const RunConfig*> mine;
    for (const RunConfig& run : plan.runs)
        if (run.index % options.shardCount == options.shardIndex &&
            (options.onlyRuns.empty() || options.onlyRuns.count(runNumber(run))) && selected.count(&run))
            mine.push_back(&run);
    if (mine.empty() && !options.filters.empty())
        throw Error(plan.configPath + ": no run matches --filter (rtbench plan --filter shows what each selects)");
    return mine;
}

// The results folder made (never through a link) and its files named and checked writable.
SweepFiles makeFolder(const std::string& folder, const RunnerOptions& options) {
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(folder, ec))) refuseSymlinks(folder);
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder))
        throw Error(folder + ": cannot create the results folder" + (ec ? ": " + ec.message() : std::string()));
    SweepFiles files;
    files.folder = folder;
    files.csvName = runsFileName(options);
    files.csvPath = (fs::path(folder) / files.csvName).string();
    files.contextPath = (fs::path(folder) / contextFileName(options)).string();
    files.samplesName = samplesFileName(options);
    files.samplesPath = (fs::path(folder) / files.samplesName).string();
    files.columns = runColumns();
    return files;
}

// The bookkeeping before the first run: context.json (complete: false), columns.csv, runs.csv with
// the kept rows and samples.csv with their samples (and the rounds a killed sweep finished).
void startFiles(const ExperimentPlan& plan, const RunnerOptions& options, const Caches& caches, const SweepFiles& files,
                const Resumed& resumed, const std::string& started) {
    writeJson(files.contextPath, contextJson(plan, options, caches, started, false));
    writeFileAtomically((fs::path(files.folder) / "columns.csv").string(), columnsCsv());
    std::vector<Row> keptRows;
    for (std::size_t k = 0; k < resumed.rows.size(); ++k)
        if (resumed.kept[k]) keptRows.push_back(resumed.rows[k]);
    writeCsv(files.csvPath, files.columns, inRunOrder(keptRows, resumed.carried));
    writeCsv(files.samplesPath, sampleColumns(), resumed.samples);
}

// What the console says as the sweep starts: what a resume kept, and what runs where.
void sayStart(const ExperimentPlan& plan, const RunnerOptions& options, const SweepFiles& files, const Resumed& resumed) {
    if (options.quiet) return;
    const std::size_t runs = resumed.rows.size();
    if (!resumed.earlierRows.empty()) {
        const std::size_t keptCount = std::size_t(std::count(resumed.kept.begin(), resumed.kept.end(), true));
        std::cout << "[rtbench] resuming " << files.csvPath << ": " << keptCount << " row(s) kept, " << runs - keptCount
                  << " run(s) to run, " << resumed.setAside << " earlier row(s) set aside\n";
    }
    std::cout << "[rtbench] " << plan.configPath << ": " << runs << " run" << (runs == 1 ? "" : "s")
              << (options.shardCount > 1 ? " (shard " + std::to_string(options.shardIndex) + "/" +
                                               std::to_string(options.shardCount) + " of " + std::to_string(plan.runs.size()) + ")"
                                         : std::string())
              << " -> " << files.folder << "/" << files.csvName << "\n";
}

}  // namespace

ExperimentResult runExperiment(const ExperimentPlan& plan, const RunnerOptions& options) {
    const std::vector<const RunConfig*> mine = selectRuns(plan, options);
    const RunConfig& first = plan.runs.front();
    const std::string output = options.outputOverride.empty() ? first.getString("experiment.output") : options.outputOverride;
    ExperimentResult result;
    result.folder = experimentFolder(output, first.getString("experiment.name"));
    // What would fail every run fails the command before any folder is made: a device that is not
    // there (its name and driver are part of each run's identity) or a scene source that is not.
    Caches caches;
    for (const RunConfig* run : mine) deviceFor(*run, caches);
    checkSceneSources(plan, mine);
    const SweepFiles files = makeFolder(result.folder, options);
    // Everything below writes the folder: one writer of each file, checked before any run.
    const std::unique_ptr<OutputFolderLock> lock =
        options.shardCount > 1 ? std::make_unique<OutputFolderLock>(result.folder, shardSuffix(options).substr(1))
                               : std::make_unique<OutputFolderLock>(result.folder);
    refuseSymlinks(result.folder);
    const FolderIdentity folder(result.folder);  // checked again before every write below
    for (const std::string& path : {files.csvPath, files.contextPath, files.samplesPath}) checkWritableFile(path);
    const std::string started = utcNow();
    Resumed resumed = resumeSweep(plan, mine, files, options, caches);
    startFiles(plan, options, caches, files, resumed, started);
    sayStart(plan, options, files, resumed);
    Sweep sweep{plan, mine, files, folder, options, caches, resumed, result};
    runSweep(sweep);
    result.rows = resumed.rows;
    const std::vector<Row> written = inRunOrder(resumed.rows, resumed.carried);
    folder.check();
    writeCsv(files.csvPath, files.columns, written);  // in plan order
    // Complete when every planned run of this file has its row (--filter may leave some without).
    const std::size_t plannedHere = std::size_t(std::count_if(plan.runs.begin(), plan.runs.end(), [&](const RunConfig& run) {
        return run.index % options.shardCount == options.shardIndex;
    }));
    const bool complete = options.filters.empty() || written.size() == plannedHere;
    writeJson(files.contextPath, contextJson(plan, options, caches, started, complete));
    if (!options.commandLine.empty()) setInterruptNote("");
    return result;
}

Row identityRow(const RunConfig& run, const std::string& commit, const std::string& device, const std::string& driver,
                const std::string& cpu) {
    Row row;
    for (const auto& [key, value] : run.values)
        for (const auto& [column, cell] : keyCells(keySpec(key), value)) row[column] = cell;
    const RunColumns& c = runColumnsDeclared();
    put(row, c.run, runNumber(run));
    put(row, c.label, run.label());
    put(row, c.sweep, run.sweep);
    put(row, c.configHash, run.hash());
    put(row, c.gitCommit, commit);
    put(row, c.device, device);
    put(row, c.driver, driver);
    put(row, c.cpu, cpu);
    return row;
}

}  // namespace rtbench
