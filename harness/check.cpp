#include "check.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "config.h"
#include "runner.h"
#include "structures/error.h"
#include "writers.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// The value of a top-level string field of context.json (written by runner.cpp's contextJson).
std::string jsonField(const std::string& json, const std::string& key) {
    const std::string marker = "\"" + key + "\": \"";
    const std::size_t start = json.find(marker);
    if (start == std::string::npos) throw Error("context.json: no \"" + key + "\"");
    std::string value;
    for (std::size_t i = start + marker.size(); i < json.size(); ++i) {
        const char c = json[i];
        if (c == '"') return value;
        if (c != '\\') {
            value += c;
            continue;
        }
        const char e = json[++i];
        switch (e) {
            case 'n': value += '\n'; break;
            case 't': value += '\t'; break;
            case 'r': value += '\r'; break;
            case 'u': value += static_cast<char>(std::stoi(json.substr(i + 1, 4), nullptr, 16)), i += 4; break;
            default: value += e;
        }
    }
    throw Error("context.json: unterminated \"" + key + "\"");
}

// Columns that describe where and when, not what: a difference is reported, never a failure.
bool isContextColumn(const std::string& column) {
    return column == "git_commit" || column == "experiment_output" || column == "device" || column == "driver" ||
           column == "embree_threads" || column == "embree_isa";
}

}  // namespace

bool isTimingColumn(const std::string& column) {
    return column.find("_ms") != std::string::npos || column.find("mrays_s") != std::string::npos ||
           column == "speed_ratio_vs_embree1" || column == "wall_s";
}

CheckResult checkResults(const std::string& folder, double timingTolerance, std::ostream& out) {
    const fs::path contextPath = fs::path(folder) / "context.json";
    std::ifstream in(contextPath);
    if (!in) throw Error(contextPath.string() + ": cannot open (is this a results folder?)");
    std::stringstream text;
    text << in.rdbuf();
    const std::string json = text.str();
    const std::string configPath = jsonField(json, "config_path");
    // Relative scene paths resolve against the recorded config's folder: where it was when run if
    // that still exists, else where the path points from here.
    std::string configDir = fs::absolute(configPath).parent_path().string();
    if (json.find("\"config_dir\"") != std::string::npos && fs::is_directory(jsonField(json, "config_dir")))
        configDir = jsonField(json, "config_dir");
    const ExperimentPlan plan = loadExperimentText(jsonField(json, "config_text"), configPath, configDir);
    const std::vector<Row> recorded = readCsv((fs::path(folder) / "runs.csv").string());

    const fs::path scratch = fs::temp_directory_path() / ("rtbench-check-" + std::to_string(::getpid()));
    fs::remove_all(scratch);
    RunnerOptions options;
    options.quiet = true;
    options.force = true;
    options.outputOverride = scratch.string();
    ExperimentResult now;
    try {
        now = runExperiment(plan, options);
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
                      const std::string& again, const char* kind) {
        table << std::left << std::setw(6) << run << std::setw(30) << column << std::setw(22) << then << std::setw(22)
              << again << kind << "\n";
    };
    for (const Row& old : recorded) {
        ++result.runs;
        const auto found = byRun.find(old.at("run"));
        if (found == byRun.end()) {
            report(old.at("run"), "(run)", "present", "missing", "count");
            ++result.deterministicDifferences;
            continue;
        }
        const Row& fresh = *found->second;
        for (const auto& [column, value] : old) {
            const auto it = fresh.find(column);
            const std::string again = it == fresh.end() ? "" : it->second;
            if (again == value || column == "git_commit" || column == "experiment_output") continue;
            if (isContextColumn(column)) {
                report(old.at("run"), column, value, again, "context");
            } else if (isTimingColumn(column)) {
                const double a = std::atof(value.c_str()), b = std::atof(again.c_str());
                if (std::abs(b - a) <= timingTolerance * std::max(std::abs(a), 1e-9)) continue;
                report(old.at("run"), column, value, again, "timing");
                ++result.timingDifferences;
            } else {
                report(old.at("run"), column, value, again, "count");
                ++result.deterministicDifferences;
            }
        }
    }
    if (now.rows.size() > recorded.size()) {
        report("-", "(runs)", std::to_string(recorded.size()), std::to_string(now.rows.size()), "count");
        ++result.deterministicDifferences;
    }
    out << "rtbench check " << folder << ": " << result.runs << " runs re-run; " << result.deterministicDifferences
        << " deterministic difference(s), " << result.timingDifferences << " timing(s) outside " << timingTolerance * 100
        << "%\n";
    if (!table.str().empty()) {
        out << std::left << std::setw(6) << "run" << std::setw(30) << "column" << std::setw(22) << "recorded" << std::setw(22)
            << "now" << "kind\n"
            << table.str();
    }
    return result;
}

}  // namespace rtbench
