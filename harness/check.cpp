#include "check.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "columns.h"
#include "config.h"
#include "runner.h"
#include "structures/error.h"
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

double number(const std::string& s) {
    return s.empty() ? std::nan("") : std::strtod(s.c_str(), nullptr);
}

}  // namespace

CheckResult checkResults(const std::string& folder, const CheckOptions& options,
                         std::ostream& out) {
    const std::string contextPath = (fs::path(folder) / "context.json").string();
    if (!fs::exists(contextPath))
        throw Error(contextPath + ": not found (is this a results folder?)");
    const Json context = readJson(contextPath);
    const std::string configPath = contextString(context, contextPath, "config_path");
    // Relative scene paths resolve against the recorded config's folder: where it was when run if
    // that still exists, else where the path points from here.
    std::string configDir = fs::absolute(configPath).parent_path().string();
    if (context.contains("config_dir") &&
        fs::is_directory(contextString(context, contextPath, "config_dir")))
        configDir = contextString(context, contextPath, "config_dir");
    ExperimentPlan plan = loadExperimentText(contextString(context, contextPath, "config_text"),
                                             configPath, configDir);
    const std::vector<Row> recorded = readRunsCsv((fs::path(folder) / "runs.csv").string());
    if (!options.embreeConfigOverride.empty()) overrideEmbreeConfig(plan, options.embreeConfigOverride);

    RunnerOptions runner;
    runner.quiet = true;
    runner.force = true;
    for (const Row& row : recorded) runner.onlyRuns.insert(row.at("run"));
    const fs::path scratch =
        fs::temp_directory_path() / ("rtbench-check-" + std::to_string(::getpid()));
    fs::remove_all(scratch);
    runner.outputOverride = scratch.string();
    ExperimentResult now;
    try {
        now = runExperiment(plan, runner);
    } catch (...) {
        fs::remove_all(scratch);
        throw;
    }
    fs::remove_all(scratch);

    CheckResult result;
    std::map<std::string, const Row*> byRun;
    for (const Row& row : now.rows) byRun[row.at("run")] = &row;
    std::ostringstream table;
    auto report = [&](const std::string& run, const std::string& column, const std::string& then,
                      const std::string& again, const std::string& kind) {
        table << std::left << std::setw(6) << run << std::setw(30) << column << std::setw(24)
              << then << std::setw(24) << again << kind << "\n";
    };
    for (const Row& old : recorded) {
        ++result.runs;
        const auto found = byRun.find(old.at("run"));
        if (found == byRun.end()) {
            report(old.at("run"), "(run)", "present", "not in the plan", "parameter");
            ++result.deterministicDifferences;
            continue;
        }
        const Row& fresh = *found->second;
        const double rays = number(old.at("rays"));
        for (const auto& [column, value] : old) {
            const std::string again = fresh.count(column) ? fresh.at(column) : "";
            if (again == value) continue;
            const ColumnSpec& spec = columnSpec(column);
            if (!options.embreeConfigOverride.empty() &&
                (column == "baseline_embree_config" || column == "config_hash"))
                continue;  // changed on purpose by the override
            switch (spec.kind) {
                case ColumnKind::Parameter:
                case ColumnKind::Count:
                    report(old.at("run"), column, value, again, columnKindName(spec.kind));
                    ++result.deterministicDifferences;
                    break;
                case ColumnKind::Reference: {
                    const double a = number(value), b = number(again);
                    const double tolerance = spec.perRay ? spec.tolerance * rays : spec.tolerance;
                    std::ostringstream kind;
                    kind << "reference (tolerance " << tolerance << ")";
                    if (std::abs(a - b) <= tolerance) {
                        ++result.referenceDifferences;
                        report(old.at("run"), column, value, again, kind.str() + ": within");
                    } else {
                        ++result.deterministicDifferences;
                        report(old.at("run"), column, value, again, kind.str() + ": BEYOND");
                    }
                    break;
                }
                case ColumnKind::Timing: {
                    const double a = number(value), b = number(again);
                    if (std::abs(b - a) <= options.timingTolerance * std::max(std::abs(a), 1e-9))
                        break;
                    report(old.at("run"), column, value, again, "timing");
                    ++result.timingDifferences;
                    break;
                }
                case ColumnKind::Context:
                    if (column == "git_commit") break;  // differs by design
                    report(old.at("run"), column, value, again, "context");
                    ++result.contextDifferences;
                    break;
            }
        }
    }
    out << "rtbench check " << folder << ": " << result.runs << " runs re-run"
        << (options.embreeConfigOverride.empty()
                ? ""
                : " with baseline.embree_config = \"" + options.embreeConfigOverride + "\"")
        << "; " << result.deterministicDifferences << " deterministic difference(s), "
        << result.referenceDifferences << " reference-dependent within tolerance, "
        << result.timingDifferences << " timing(s) outside " << options.timingTolerance * 100
        << "%, " << result.contextDifferences << " context\n";
    if (context.contains("complete") && context["complete"] == false)
        out << "(the recorded sweep was interrupted: " << recorded.size() << " of "
            << plan.runs.size() << " runs were recorded and checked)\n";
    if (!table.str().empty()) {
        out << std::left << std::setw(6) << "run" << std::setw(30) << "column" << std::setw(24)
            << "recorded" << std::setw(24) << "now"
            << "kind\n"
            << table.str();
    }
    return result;
}

}  // namespace rtbench
