#include "check.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "columns.h"
#include "output_folder.h"
#include "config.h"
#include "runner.h"
#include "samples_check.h"
#include "timing_rounds.h"
#include "core/error.h"
#include "writers.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

std::string contextString(const Json& context, const std::string& path, const char* key) {
    const auto it = context.find(key);
    if (it == context.end() || !it->is_string())
        throw Error(path + ": no string field \"" + std::string(key) + "\"");
    return it->get<std::string>();
}

// The rows must be the recorded plan's runs: each row a run of the plan with its config hash, and,
// when context.json says the sweep completed, every run of the plan a row. The recorded plan must
// be the plan its config text gives. A lost, extra or edited row is an error naming the run.
// A folder of an older results schema hashed its runs without the keys added since (`newerKeys`).
void checkRowsAgainstPlan(const Json& context, const std::string& contextPath, const ExperimentPlan& plan,
                          const std::vector<Row>& rows, const std::string& csvPath, const std::set<std::string>& newerKeys) {
    std::map<std::string, std::string> derived, planned;
    for (const RunConfig& run : plan.runs) derived[runNumber(run)] = newerKeys.empty() ? run.hash() : run.hashWithout(newerKeys);
    try {
        for (const Json& run : context.at("plan"))
            planned[run.at("run").get<std::string>()] = run.at("config_hash").get<std::string>();
    } catch (const Json::exception& e) {
        throw Error(contextPath + ": no valid \"plan\" list: " + e.what());
    }
    for (const auto& [run, hash] : derived)
        if (!planned.count(run) || planned[run] != hash)
            throw Error(contextPath + ": its plan lacks run " + run + " (config_hash " + hash + ") that its config text gives (" +
                        std::to_string(planned.size()) + " runs recorded, " + std::to_string(derived.size()) +
                        " in the config): the plan was cut down or edited");
    if (planned.size() != derived.size())
        throw Error(contextPath + ": its plan lists " + std::to_string(planned.size()) + " runs, its config text gives " +
                    std::to_string(derived.size()) + ": the plan was edited");
    std::set<std::string> present;
    for (const Row& row : rows) {
        const std::string& run = row.at("run");
        const auto it = derived.find(run);
        if (it == derived.end()) throw Error(csvPath + ": run " + run + " (" + row.at("label") + ") is not in the recorded plan");
        if (it->second != row.at("config_hash"))
            throw Error(csvPath + ": run " + run + " has config_hash " + row.at("config_hash") + ", the plan's is " + it->second +
                        " (a row of another config?)");
        present.insert(run);
    }
    const auto completeField = context.find("complete");
    if (completeField == context.end() || !completeField->is_boolean())
        throw Error(contextPath + ": no boolean \"complete\" field");
    const bool complete = completeField->get<bool>();
    if (!complete) return;  // an interrupted sweep: the runs it finished are checked
    for (const RunConfig& run : plan.runs)
        if (!present.count(runNumber(run)))
            throw Error(csvPath + ": run " + runNumber(run) + " (" + run.label() + ") of the plan has no row, and " + contextPath +
                        " says the sweep completed: rows were lost");
}

// What differs between the recorded rows and the re-run, by class: a line per deterministic,
// reference (within tolerance) and context difference, and one line per run for its timings.
struct Differences {
    CheckResult counts;
    std::vector<std::string> deterministic, within, timings, context;
};

std::string differenceLine(const std::string& run, const std::string& column, const std::string& then,
                           const std::string& again, const std::string& kind) {
    std::ostringstream line;
    line << std::left << std::setw(5) << run << " " << std::setw(29) << column << " " << std::setw(23) << then << " "
         << std::setw(23) << again << "  " << kind;  // a long value pushes the next along, never into it
    return line.str();
}

// A run's timings in one line, where one of them moved beyond the tolerance: the kernel's and
// Embree rtcIntersect1's medians and their ratio, recorded -> now.
std::string timingLine(const Row& old, const Row& fresh) {
    auto cell = [](const Row& row, const char* column) {
        const std::string text = cellText(row, column);
        return text.empty() ? std::string("-") : text;
    };
    auto change = [&](const char* column) {
        const double a = cellNumber(cell(old, column)), b = cellNumber(cell(fresh, column));
        std::string text = std::string(column) + " " + cell(old, column) + " -> " + cell(fresh, column);
        if (std::isfinite(a) && std::isfinite(b) && a > 0) {
            std::ostringstream percent;
            percent << std::showpos << std::fixed << std::setprecision(1) << 100.0 * (b / a - 1.0) << "%";
            text += " (" + percent.str() + ")";
        }
        return text;
    };
    return old.at("run") + "  " + change("kernel_ms_median") + ", " + change("embree1_ms_median") + ", " +
           change("speed_ratio_vs_embree1");
}

// One recorded row against its re-run, column by column, each by its kind.
void compareRow(const Row& old, const Row& fresh, const CheckOptions& options, bool olderSchema, Differences& d) {
    const double rays = cellNumber(old.at("rays"));
    bool timingMoved = false;
    for (const auto& [column, value] : old) {
        const std::string again = fresh.count(column) ? fresh.at(column) : "";
        if (again == value) continue;
        const ColumnSpec& spec = columnSpec(column);
        if (!options.embreeConfigOverride.empty() && (column == "baseline_embree_config" || column == "config_hash"))
            continue;  // changed on purpose by the override
        if (column == "config_hash" && olderSchema) continue;  // an older schema's hash, checked against the plan
        switch (spec.kind) {
            case ColumnKind::Parameter:
            case ColumnKind::Exact:
                d.deterministic.push_back(differenceLine(old.at("run"), column, value, again, columnKindName(spec.kind)));
                break;
            case ColumnKind::Reference: {
                const double tolerance = spec.perRay ? spec.tolerance * rays : spec.tolerance;
                std::ostringstream kind;
                kind << "reference (tolerance " << tolerance << ")";
                const bool within = std::abs(cellNumber(value) - cellNumber(again)) <= tolerance;
                (within ? d.within : d.deterministic)
                    .push_back(differenceLine(old.at("run"), column, value, again, kind.str() + (within ? ": within" : ": BEYOND")));
                break;
            }
            case ColumnKind::Timing: {
                // Judged on the medians and their ratio, by the tolerance (the spread, intervals and
                // rates move with them or with the repetitions: not reported one by one).
                if (column != "kernel_ms_median" && column != "embree1_ms_median" && column != "speed_ratio_vs_embree1")
                    break;
                const double a = cellNumber(value), b = cellNumber(again);
                const bool numeric = !std::isnan(a) && !std::isnan(b);
                timingMoved |= !numeric || std::abs(b - a) > options.timingTolerance * std::max(std::abs(a), 1e-9);
                break;
            }
            case ColumnKind::Context:
            case ColumnKind::Scheduled:
                if (column == "git_commit") break;  // differs by design
                d.context.push_back(differenceLine(old.at("run"), column, value, again, columnKindName(spec.kind)));
                break;
        }
    }
    if (timingMoved) d.timings.push_back(timingLine(old, fresh));
}

Differences compareRuns(const std::vector<Row>& recorded, const std::vector<Row>& rerun, const CheckOptions& options,
                        bool olderSchema) {
    std::map<std::string, const Row*> byRun;
    for (const Row& row : rerun) byRun[row.at("run")] = &row;
    Differences d;
    for (const Row& old : recorded) {
        ++d.counts.runs;
        const auto found = byRun.find(old.at("run"));
        if (found == byRun.end())
            d.deterministic.push_back(differenceLine(old.at("run"), "(run)", "present", "not in the plan", "parameter"));
        else
            compareRow(old, *found->second, options, olderSchema, d);
    }
    d.counts.deterministicDifferences = int(d.deterministic.size());
    d.counts.referenceDifferences = int(d.within.size());
    d.counts.timingDifferences = int(d.timings.size());
    d.counts.contextDifferences = int(d.context.size());
    return d;
}

// The recorded rows' samples (samples_check.h), one line per row whose samples are not its own: the
// timings of record are only as good as the samples behind them.
std::vector<std::string> samplesProblems(const std::string& folder, const std::vector<Row>& recorded, int schema) {
    const std::string path = (fs::path(folder) / "samples.csv").string();
    std::error_code ec;
    if (schema < 5) return {};
    if (!fs::exists(fs::symlink_status(path, ec)))
        return {differenceLine("-", "(samples.csv)", "missing", "", "evidence of the timings")};
    const std::vector<Row> samples = readSamplesCsv(path);
    const auto byRun = samplesByRun(samples);
    std::vector<std::string> problems;
    for (const Row& row : recorded)
        if (const std::string problem = samplesProblem(row, byRun); !problem.empty())
            problems.push_back(differenceLine(row.at("run"), "(samples.csv)", problem, "", "evidence of the timings"));
    return problems;
}

// The folder's columns.csv, where it has one (the early schemas wrote none), must describe its
// runs.csv: a readable CSV naming every column of the recorded rows with its kind (a reader types
// the cells from it). "" when it does.
std::string columnsProblem(const std::string& folder, const std::vector<Row>& recorded) {
    const std::string path = (fs::path(folder) / "columns.csv").string();
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(path, ec))) return "";
    std::set<std::string> described;
    try {
        for (const Row& row : readCsv(path)) {
            if (!row.count("column") || !row.count("kind")) return "no column and kind columns";
            described.insert(row.at("column"));
        }
    } catch (const Error& e) {
        return e.what();
    }
    for (const auto& [column, value] : recorded.front())
        if (!described.count(column)) return "does not describe runs.csv's column " + column;
    return "";
}

// Deterministic differences first (what fails), then reference values within tolerance, the runs
// whose timings moved (one line each), and the context.
void printDifferences(const Differences& d, const CheckOptions& options, std::ostream& out) {
    const std::string header = differenceLine("run", "column", "recorded", "now", "kind");
    if (!d.deterministic.empty()) {
        out << "\ndeterministic differences (a failure):\n" << header << "\n";
        for (const std::string& line : d.deterministic) out << line << "\n";
    }
    if (!d.within.empty()) {
        out << "\nreference-dependent values within their tolerance:\n" << header << "\n";
        for (const std::string& line : d.within) out << line << "\n";
    }
    if (!d.timings.empty()) {
        out << "\ntimings outside " << options.timingTolerance * 100 << "% (reported, never a failure; recorded -> now):\n";
        for (const std::string& line : d.timings) out << line << "\n";
    }
    if (!d.context.empty()) {
        out << "\ncontext and scheduling (reported, never a failure):\n" << header << "\n";
        for (const std::string& line : d.context) out << line << "\n";
    }
}

}  // namespace

std::vector<std::string> deterministicDifferences(const Row& recorded, const Row& rerun) {
    Differences d;
    compareRow(recorded, rerun, CheckOptions{}, false, d);
    return d.deterministic;
}

ExperimentPlan recordedPlan(const Json& context, const std::string& contextPath) {
    const std::string configPath = contextString(context, contextPath, "config_path");
    // Relative scene paths resolve against the recorded config's folder: where it was when run if
    // that still exists, else where the path points from here.
    std::string configDir = fs::absolute(configPath).parent_path().string();
    if (context.contains("config_dir") &&
        fs::is_directory(contextString(context, contextPath, "config_dir")))
        configDir = contextString(context, contextPath, "config_dir");
    // The command line's --set of the recorded run, applied over its config text as then.
    std::vector<std::string> settings;
    if (context.contains("settings")) {
        if (!context["settings"].is_array()) throw Error(contextPath + ": \"settings\" is not a list of strings");
        for (const Json& s : context["settings"]) {
            if (!s.is_string()) throw Error(contextPath + ": \"settings\" is not a list of strings");
            settings.push_back(s.get<std::string>());
        }
    }
    ExperimentPlan plan = loadExperimentText(contextString(context, contextPath, "config_text"),
                                             configPath, configDir, settings);
    // The command line's overrides of the recorded run (-d, --validation, --embree-config).
    if (context.contains("overrides")) {
        std::map<std::string, std::string> overrides;
        for (const auto& [key, value] : context["overrides"].items())
            if (value.is_string()) overrides[key] = value.get<std::string>();
        applyRecordedOverrides(plan, overrides);
    }
    return plan;
}

CheckResult checkResults(const std::string& folder, const CheckOptions& options,
                         std::ostream& out) {
    if (!(options.timingTolerance >= 0.0) || !std::isfinite(options.timingTolerance))
        throw Error("--tolerance " + formatNumber(options.timingTolerance) + ": expected a finite number >= 0 (0.5 = 50%)");
    if (!options.embreeConfigOverride.empty()) {
        ExperimentPlan none;
        overrideEmbreeConfig(none, options.embreeConfigOverride);  // refused before any work
    }
    const std::string contextPath = (fs::path(folder) / "context.json").string();
    if (!fs::exists(contextPath))
        throw Error(contextPath + ": not found (is this a results folder?)");
    refuseFolderBeingWritten(folder, "check");
    const Json context = readJson(contextPath);
    ExperimentPlan plan = recordedPlan(context, contextPath);
    const std::string csvPath = (fs::path(folder) / "runs.csv").string();
    int schema = kSchemaVersion;
    const std::vector<Row> recorded = readRunsCsv(csvPath, &schema);
    std::set<std::string> newerKeys;  // keys the folder's schema did not have
    for (const KeySpec& k : configSchema())
        if (columnSpec(keyColumns(k).front()).since > schema) newerKeys.insert(k.name);
    checkRowsAgainstPlan(context, contextPath, plan, recorded, csvPath, newerKeys);
    if (!options.embreeConfigOverride.empty()) overrideEmbreeConfig(plan, options.embreeConfigOverride);

    CheckResult result;
    if (recorded.empty()) {  // an interrupted sweep that finished no run: nothing to re-run
        out << "rtbench check " << folder << ": 0 runs recorded (the sweep was interrupted before its first run "
            << "finished); nothing re-run\n";
        return result;
    }
    RunnerOptions runner;
    runner.quiet = true;
    runner.force = true;
    for (const Row& row : recorded) runner.onlyRuns.insert(row.at("run"));
    ExperimentResult now;
    {
        const ScratchFolder scratch("rtbench-check");
        runner.outputOverride = scratch.path();
        now = runExperiment(plan, runner);
    }

    Differences found = compareRuns(recorded, now.rows, options, !newerKeys.empty());
    for (const std::string& problem : samplesProblems(folder, recorded, schema)) found.deterministic.push_back(problem);
    if (const std::string problem = columnsProblem(folder, recorded); !problem.empty())
        found.deterministic.push_back(differenceLine("-", "(columns.csv)", problem, "", "the columns' description"));
    found.counts.deterministicDifferences = int(found.deterministic.size());
    result = found.counts;
    out << "rtbench check " << folder << ": " << result.runs << " runs re-run"
        << (options.embreeConfigOverride.empty()
                ? ""
                : " with baseline.embree_config = \"" + options.embreeConfigOverride + "\"")
        << "; " << result.deterministicDifferences << " deterministic difference(s), "
        << result.referenceDifferences << " reference-dependent within tolerance, "
        << result.timingDifferences << " run(s) with a timing outside " << options.timingTolerance * 100
        << "%, " << result.contextDifferences << " context\n";
    // A folder of an older results schema lacks the later columns: they are not compared.
    std::string newer;
    for (const std::string& column : runColumns())
        if (!recorded.front().count(column) && std::any_of(now.rows.begin(), now.rows.end(), [&](const Row& r) {
                const auto it = r.find(column);
                return it != r.end() && !it->second.empty();
            }))
            newer += (newer.empty() ? "" : ", ") + column;
    if (!newer.empty())
        out << "(recorded under results schema " << schema << "; columns of schema " << kSchemaVersion
            << " not compared: " << newer << ")\n";
    if (!now.rows.empty() && cellText(recorded.front(), "git_commit") != cellText(now.rows.front(), "git_commit"))
        out << "(recorded by commit " << cellText(recorded.front(), "git_commit") << ", re-run by commit "
            << cellText(now.rows.front(), "git_commit") << ": a timing may also move with the code)\n";
    if (context.contains("complete") && context["complete"] == false)
        out << "(the recorded sweep was interrupted: " << recorded.size() << " of "
            << plan.runs.size() << " runs were recorded and checked)\n";
    printDifferences(found, options, out);
    return result;
}

}  // namespace rtbench
