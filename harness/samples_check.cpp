#include "samples_check.h"

#include <cmath>
#include <set>
#include <tuple>

#include "statistics.h"
#include "writers.h"

namespace rtbench {

std::string runKey(const Row& row) { return cellText(row, "run") + "|" + cellText(row, "config_hash"); }

std::map<std::string, std::vector<const Row*>> samplesByRun(const std::vector<Row>& samples) {
    std::map<std::string, std::vector<const Row*>> byRun;
    for (const Row& s : samples) byRun[runKey(s)].push_back(&s);
    return byRun;
}

namespace {

// One method's samples against the row's median and their count, the row's `countColumn`; ""
// when they agree.
std::string methodProblem(const Row& row, const std::string& method, const std::vector<const Row*>& samples,
                          const std::string& countColumn) {
    const double repetitions = cellNumber(cellText(row, countColumn));
    std::vector<double> ms;
    std::set<std::tuple<std::string, std::string>> seen;
    for (const Row* s : samples) {
        if (s->at("method") != method) continue;
        const double value = cellNumber(s->at("ms"));
        if (!(value > 0) || !std::isfinite(value))
            return method + " sample '" + s->at("ms") + "' is not a positive number of ms";
        if (!seen.insert({s->at("round"), s->at("repetition")}).second)
            return method + " round " + s->at("round") + " repetition " + s->at("repetition") + " twice";
        ms.push_back(value);
    }
    if (ms.empty()) return "no " + method + " samples";
    if (double(ms.size()) != repetitions)
        return std::to_string(ms.size()) + " " + method + " samples, " + countColumn + " says " + cellText(row, countColumn);
    const double recorded = cellNumber(cellText(row, method + "_ms_median")), again = median(ms);
    if (!(std::abs(again - recorded) <= 1e-5 * std::abs(recorded)))  // the row keeps 6 digits
        return "the " + method + " samples' median " + formatNumber(again) + " is not the row's " + method + "_ms_median " +
               cellText(row, method + "_ms_median");
    return "";
}

}  // namespace

std::string samplesProblem(const Row& row, const std::map<std::string, std::vector<const Row*>>& byRun) {
    if (cellText(row, "status") != "ok" || cellText(row, "timing_repetitions").empty()) return "";
    const auto found = byRun.find(runKey(row));
    if (found == byRun.end()) return "no samples of its run and config hash";
    for (const char* method : {"kernel", "embree1", "embree16"}) {
        if (cellText(row, std::string(method) + "_ms_median").empty()) continue;
        if (std::string problem = methodProblem(row, method, found->second, "timing_repetitions"); !problem.empty()) return problem;
    }
    if (const std::string rounds = cellText(row, "build_rounds"); !rounds.empty() && rounds != "0")  // experiment.build_rounds
        for (const char* method : {"structure_build", "embree_build"})
            if (std::string problem = methodProblem(row, method, found->second, "build_rounds"); !problem.empty()) return problem;
    return "";
}

}  // namespace rtbench
