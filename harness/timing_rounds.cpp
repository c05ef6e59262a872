#include "timing_rounds.h"

#include <algorithm>
#include <map>

#include "statistics.h"
#include "structures/error.h"
#include "structures/input_file.h"
#include "writers.h"

namespace rtbench {

RoundsOptions roundsOptions(const RunConfig& run) {
    RoundsOptions o;
    o.warmups = int(run.getInt("experiment.warmups"));
    o.repetitions = int(run.getInt("experiment.repetitions"));
    o.rounds = int(run.getInt("experiment.rounds"));
    o.targetCi = run.getFloat("experiment.target_ci");
    o.maxRepetitions = int(run.getInt("experiment.max_repetitions"));
    o.budgetSeconds = run.getFloat("experiment.time_budget_s");
    return o;
}

const std::vector<double>& RoundsResult::of(const std::string& name) const {
    static const std::vector<double> none;
    for (const auto& [n, ms] : series)
        if (n == name) return ms;
    return none;
}

const std::vector<std::string>& sampleColumns() {
    static const std::vector<std::string> columns = {"run", "config_hash", "method", "round", "repetition", "ms", "t_s"};
    return columns;
}

std::vector<Row> parseSamplesCsv(const std::string& text, const std::string& path) {
    std::vector<Row> rows = parseCsv(text, path);
    if (!rows.empty()) {
        std::vector<std::string> header;
        for (const auto& [column, value] : rows[0]) header.push_back(column);
        std::vector<std::string> expected = sampleColumns();
        std::sort(expected.begin(), expected.end());
        if (header != expected) throw Error(path + ": not a samples file (expected the columns run,config_hash,method,round,repetition,ms,t_s)");
    }
    return rows;
}

std::vector<Row> readSamplesCsv(const std::string& path) {
    return parseSamplesCsv(readInputFile(path, kMaxResultsFileBytes, "CSV file"), path);
}

RoundsResult timeInRounds(const std::vector<TimedMethod>& methods,
                          const std::function<std::vector<std::pair<std::string, double>>()>& hostLoops,
                          const RoundsOptions& options, std::chrono::steady_clock::time_point origin) {
    using Clock = std::chrono::steady_clock;
    const auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
    RoundsResult result;
    std::map<std::string, std::size_t> index;  // series name -> position
    std::map<std::string, int> taken;          // samples per series so far
    auto add = [&](const std::string& name, int round, double ms, double t) {
        if (!index.count(name)) {
            index[name] = result.series.size();
            result.series.push_back({name, {}});
        }
        result.series[index[name]].second.push_back(ms);
        result.samples.push_back({name, round, taken[name]++, ms, t});
    };
    const int initialRounds = std::max(1, std::min(options.rounds, options.repetitions));
    const int perRound = (options.repetitions + initialRounds - 1) / initialRounds;
    const Clock::time_point start = Clock::now();
    for (int round = 0;; ++round) {
        // The initial rounds split experiment.repetitions evenly; adaptive rounds add perRound.
        int count = round < initialRounds
                        ? options.repetitions * (round + 1) / initialRounds - options.repetitions * round / initialRounds
                        : std::min(perRound, options.maxRepetitions - result.repetitions);
        if (hostLoops)
            for (const auto& [name, ms] : hostLoops()) add(name, round, ms, seconds(origin, Clock::now()) - ms / 1e3);
        for (const TimedMethod& method : methods) {
            const double batchStart = seconds(origin, Clock::now());
            const TimedBatch batch = method.time(round == 0 ? options.warmups : 0, count);
            double t = batchStart + batch.warmupMs / 1e3;
            for (std::size_t i = 0; i < batch.ms.size(); ++i) {
                add(method.name, round, batch.ms[i], t);
                for (const auto& [part, ms] : batch.parts) add(method.name + "_" + part, round, ms.at(i), t);
                t += batch.ms[i] / 1e3;
            }
        }
        result.repetitions += count;
        result.rounds = round + 1;
        if (round + 1 < initialRounds) continue;
        if (options.targetCi <= 0) {
            result.stop = "repetitions";
            break;
        }
        // An interval of a handful of samples says little (one sample's is a point): judged from
        // kMinAdaptiveRepetitions on.
        bool converged = result.repetitions >= kMinAdaptiveRepetitions;
        for (const TimedMethod& method : methods)
            converged = converged && summarize(result.of(method.name)).relativeHalfWidth() <= options.targetCi;
        if (converged) {
            result.stop = "converged";
            break;
        }
        if (result.repetitions >= options.maxRepetitions) {
            result.stop = "max_repetitions";
            break;
        }
        if (seconds(start, Clock::now()) >= options.budgetSeconds) {
            result.stop = "time_budget";
            break;
        }
    }
    result.seconds = seconds(start, Clock::now());
    return result;
}

}  // namespace rtbench
