#include "resume.h"

#include <filesystem>
#include <iostream>
#include <set>

#include "core/error.h"
#include "core/input_file.h"
#include "device/vulkan_context.h"
#include "harness/columns.h"
#include "harness/output_folder.h"
#include "harness/run_columns.h"
#include "harness/samples_check.h"
#include "harness/timing_rounds.h"
#include "harness/version.h"
#include "harness/writers.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// A run's identity beyond its parameters (config_hash): the commit of the binary, the device it
// ran on and the contents of the files its scene was made from. A row of an earlier invocation
// stands for a run of this plan only when all of them are equal.
std::string identity(const Row& row) {
    std::string key;
    for (const char* column : {"run", "config_hash", "git_commit", "device", "driver", "cpu", "inputs_hash"})
        key += (key.empty() ? "" : "|") + cellText(row, column);
    return key;
}

// Sets aside rows of an earlier invocation that a resume does not keep: the rows, their timing
// samples (and samples of runs whose row was never written), the context they were recorded under
// (the old context.json, before this invocation replaces it), and each row's per-run files
// (run-NNN.hits, -shaded.png, -diff.png), which would else sit beside a new row of the same run
// number. Returns the prefix of their names.
std::string setAside(const std::string& folder, const std::string& csvName, const std::string& contextPath,
                     const std::vector<std::string>& columns, const std::vector<Row>& rows,
                     const std::string& samplesName, const std::vector<Row>& samples) {
    const std::string prefix = supersededPrefix(folder);
    if (!rows.empty()) writeCsv(prefix + csvName, columns, rows);
    if (!samples.empty()) writeCsv(prefix + samplesName, sampleColumns(), samples);
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(contextPath, ec)))
        writeFileAtomically(prefix + fs::path(contextPath).filename().string(),
                            readInputFile(contextPath, kMaxResultsFileBytes, "JSON file"));
    for (const Row& row : rows)
        for (const char* suffix : {".hits", "-shaded.png", "-diff.png"}) {
            const fs::path file = fs::path(folder) / ("run-" + row.at("run") + suffix);
            if (fs::is_regular_file(fs::symlink_status(file, ec)))
                fs::rename(file, prefix + file.filename().string(), ec);
        }
    return prefix;
}

// The text of a CSV this invocation resumes from. A last row without its line end was cut while
// written (a crash, power lost): it is set aside as it is, and the rows before it stand.
std::string readResumable(const std::string& folder, const std::string& path, const std::string& name) {
    std::string text = readInputFile(path, kMaxResultsFileBytes, "CSV file");
    if (text.empty() || text.back() == '\n') return text;
    const std::size_t end = text.rfind('\n');
    const std::string prefix = supersededPrefix(folder);
    writeFileAtomically(prefix + name + ".cut-row", end == std::string::npos ? text : text.substr(end + 1));
    text.resize(end == std::string::npos ? 0 : end + 1);
    std::cerr << "[rtbench] " << path << ": its last row was cut while written; set aside in " << prefix << name
              << ".cut-row, and run again\n";
    return text;
}

// An earlier runs CSV (or its samples): read to resume from, or, unreadable with --force, moved
// aside whole.
template <typename Parse>
std::vector<Row> readEarlier(const SweepFiles& files, const std::string& path, const std::string& name, bool force, Parse parse) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(path, ec))) return {};
    try {
        return parse(readResumable(files.folder, path, name), path);
    } catch (const Error& e) {
        if (!force) throw Error(std::string(e.what()) + "; cannot resume from it (--force re-runs every run and replaces it)");
        const std::string aside = supersededPrefix(files.folder) + name;  // --force replaces it; the file is kept aside
        fs::rename(path, aside, ec);
        if (ec) throw Error(path + ": cannot move the unreadable file aside: " + ec.message());
        std::cerr << "[rtbench] " << path << " could not be read (" << e.what() << "); kept as " << aside << "\n";
        return {};
    }
}

// The earlier rows and samples, and what is known of them as the sweep starts.
struct Earlier {
    std::vector<Row> rows, samples;
    std::map<std::string, const Row*> okByIdentity;  // ok rows by identity()
    std::set<std::string> okRuns;                    // "run|config_hash" of those
    std::set<const Row*> keptRows;                   // the rows that stand
    std::map<std::string, std::string> inputsNow;    // run -> inputs_hash, of runs with an earlier ok row
    std::set<const Row*> samplesNotItsOwn;           // ok rows whose samples are missing or another's
};

// Each run's row as it will be written: its parameters and identity, or its earlier row where that
// stands (the scene's inputs are hashed as loaded, so only runs with an earlier row to match load
// their scene here).
void matchEarlier(const ExperimentPlan& plan, const std::vector<const RunConfig*>& mine, Caches& caches, Earlier& earlier,
                  Resumed& resumed) {
    resumed.rows.resize(mine.size());
    resumed.kept.assign(mine.size(), false);
    const auto earlierByRun = samplesByRun(earlier.samples);
    for (std::size_t k = 0; k < mine.size(); ++k) {
        const RunConfig& run = *mine[k];
        const VulkanContext& vk = deviceFor(run, caches);
        Row& row = resumed.rows[k] = identityRow(run, gitCommit(), vk.info().name, vk.info().driver, cpuModel());
        if (!earlier.okRuns.count(runKey(row))) continue;
        Row withInputs = row;
        try {
            writeInputColumns(*fullScene(plan, run, caches), withInputs);
        } catch (const std::exception&) {
            continue;  // the scene no longer loads: the run is run again, and says why
        }
        earlier.inputsNow[row["run"]] = withInputs["inputs_hash"];
        const auto previous = earlier.okByIdentity.find(identity(withInputs));
        if (previous == earlier.okByIdentity.end()) continue;
        if (!samplesProblem(*previous->second, earlierByRun).empty()) {  // a row is kept with its evidence only
            earlier.samplesNotItsOwn.insert(previous->second);
            continue;
        }
        row = *previous->second;
        put(row, runColumnsDeclared().label, run.label());  // the label names the swept keys of this plan
        resumed.kept[k] = true;
        earlier.keptRows.insert(previous->second);
    }
}

// Why an earlier row does not stand, first reason first. `now`: this invocation's row of its run (null: none).
const char* whyNotKept(const Row& row, const Row* now, const std::set<std::string>& planned, const Earlier& earlier, bool force) {
    auto differs = [&](const char* column) { return now->at(column) != (row.count(column) ? row.at(column) : ""); };
    return !planned.count(runKey(row)) ? "no longer in the plan"
           : row.at("status") != "ok"                                   ? "failed"
           : force                                                      ? "--force"
           : now == nullptr                                             ? "another shard's"
           : differs("git_commit")                                      ? "another commit"
           : differs("device") || differs("driver")                     ? "another device or driver"
           : differs("cpu")                                             ? "another CPU"
           : !earlier.inputsNow.count(row.at("run"))                    ? "a scene that no longer loads"
           : earlier.samplesNotItsOwn.count(&row)                       ? "samples missing or not its own"
                                                                        : "other input files";
}

// The samples of kept rows stand with them; the finished rounds of an interleaved run to time again
// (a killed sweep's, with no row) go on; the rest (superseded rows', and those of a run interrupted
// before its row was written) are returned to be set aside.
std::vector<Row> sortSamples(const ExperimentPlan& plan, const RunnerOptions& options, Earlier& earlier, Resumed& resumed) {
    std::set<std::string> keptRuns, rowRuns, toRun;
    for (const Row* row : earlier.keptRows) keptRuns.insert(runKey(*row));
    for (const Row& row : earlier.rows) rowRuns.insert(runKey(row));
    const bool interleaved = plan.runs.front().getString("experiment.order") == "interleaved";
    for (std::size_t k = 0; k < resumed.rows.size(); ++k)
        if (!resumed.kept[k] && interleaved && !options.force)
            toRun.insert(runKey(resumed.rows[k]));
    std::vector<Row> aside;
    for (Row& sample : earlier.samples) {
        const std::string key = runKey(sample);
        if (keptRuns.count(key)) resumed.samples.push_back(std::move(sample));
        else if (toRun.count(key) && !rowRuns.count(key)) resumed.rounds[key].push_back(std::move(sample));
        else aside.push_back(std::move(sample));
    }
    for (const auto& [key, rounds] : resumed.rounds) resumed.samples.insert(resumed.samples.end(), rounds.begin(), rounds.end());
    return aside;
}

// Earlier rows that do not stand, and samples that belong to no row that stands, set aside in a
// file of their own; the reasons said on stderr.
void setAsideEarlier(const ExperimentPlan& plan, const SweepFiles& files, const RunnerOptions& options, Earlier& earlier,
                     Resumed& resumed) {
    std::set<std::string> planned;
    for (const RunConfig& run : plan.runs) planned.insert(runNumber(run) + "|" + run.hash());
    std::map<std::string, const Row*> planRow;  // run -> this invocation's row of it
    for (const Row& row : resumed.rows) planRow[row.at("run")] = &row;
    if (!options.filters.empty())  // --filter: the earlier rows of the runs it leaves out stand as they are
        for (const Row& row : earlier.rows)
            if (planned.count(runKey(row)) && !planRow.count(row.at("run"))) {
                resumed.carried.push_back(row);
                earlier.keptRows.insert(&row);
            }
    std::vector<Row> superseded;
    std::map<std::string, std::size_t> why;
    std::string notInPlan;
    for (const Row& row : earlier.rows) {
        if (earlier.keptRows.count(&row)) continue;
        superseded.push_back(row);
        const auto now = planRow.find(row.at("run"));
        const std::string reason = whyNotKept(row, now == planRow.end() ? nullptr : now->second, planned, earlier, options.force);
        ++why[reason];
        if (reason == "no longer in the plan") notInPlan += (notInPlan.empty() ? "" : ", ") + row.at("run") + " (" + row.at("label") + ")";
    }
    const std::vector<Row> samples = sortSamples(plan, options, earlier, resumed);
    resumed.setAside = superseded.size();
    if (superseded.empty() && samples.empty()) return;
    const std::string aside = setAside(files.folder, files.csvName, files.contextPath, files.columns, superseded, files.samplesName, samples);
    if (superseded.empty()) {
        std::cerr << "[rtbench] " << samples.size() << " timing sample(s) of " << files.samplesPath
                  << " belong to no row (a run interrupted before its row was written); they are saved in " << aside
                  << files.samplesName << "\n";
        return;
    }
    std::string reasons;
    for (const auto& [reason, count] : why) reasons += (reasons.empty() ? "" : ", ") + std::to_string(count) + " " + reason;
    std::cerr << "[rtbench] " << superseded.size() << " row(s) of " << files.csvPath << " are not kept (" << reasons << ")"
              << (notInPlan.empty() ? "" : "; no longer in the plan: " + notInPlan) << "; they are saved in " << aside
              << files.csvName << "\n";
}

}  // namespace

Resumed resumeSweep(const ExperimentPlan& plan, const std::vector<const RunConfig*>& mine, const SweepFiles& files,
                    const RunnerOptions& options, Caches& caches) {
    Earlier earlier;
    earlier.rows = readEarlier(files, files.csvPath, files.csvName, options.force,
                               [](const std::string& text, const std::string& path) { return parseRunsCsv(text, path); });
    earlier.samples = readEarlier(files, files.samplesPath, files.samplesName, options.force, parseSamplesCsv);
    if (!options.force)
        for (const Row& row : earlier.rows)
            if (row.at("status") == "ok") {
                earlier.okByIdentity[identity(row)] = &row;
                earlier.okRuns.insert(runKey(row));
            }
    Resumed resumed;
    matchEarlier(plan, mine, caches, earlier, resumed);
    setAsideEarlier(plan, files, options, earlier, resumed);
    resumed.earlierRows = std::move(earlier.rows);
    return resumed;
}

}  // namespace rtbench
