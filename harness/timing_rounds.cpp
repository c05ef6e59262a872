#include "timing_rounds.h"

#include <algorithm>
#include <map>

#include "statistics.h"
#include "core/error.h"
#include "core/input_file.h"
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

namespace {
using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }
}  // namespace

Rounds::Rounds(std::vector<TimedMethod> methods, HostLoops hostLoops, const RoundsOptions& options, Clock::time_point origin)
    : methods_(std::move(methods)), hostLoops_(std::move(hostLoops)), options_(options), origin_(origin),
      initialRounds_(std::max(1, std::min(options.rounds, options.repetitions))),
      perRound_((options.repetitions + initialRounds_ - 1) / initialRounds_) {}

void Rounds::add(const std::string& name, int round, double ms, double t) {
    if (!index_.count(name)) {
        index_[name] = result_.series.size();
        result_.series.push_back({name, {}});
    }
    result_.series[index_[name]].second.push_back(ms);
    result_.samples.push_back({name, round, taken_[name]++, ms, t});
}

void Rounds::runRound() {
    if (done()) return;
    const Clock::time_point start = Clock::now();
    const int round = result_.rounds;
    // The initial rounds split experiment.repetitions evenly; adaptive rounds add perRound_.
    const int count = round < initialRounds_ ? options_.repetitions * (round + 1) / initialRounds_ -
                                                   options_.repetitions * round / initialRounds_
                                             : std::min(perRound_, options_.maxRepetitions - result_.repetitions);
    if (hostLoops_)
        for (const auto& [series, ms] : hostLoops_()) add(series->name, round, ms, seconds(origin_, Clock::now()) - ms / 1e3);
    for (const TimedMethod& method : methods_) {
        const double batchStart = seconds(origin_, Clock::now());
        const TimedBatch batch = method.time(warmedUp_ ? 0 : options_.warmups, count);
        double t = batchStart + batch.warmupMs / 1e3;
        for (std::size_t i = 0; i < batch.ms.size(); ++i) {
            add(method.name, round, batch.ms[i], t);
            for (const auto& [part, ms] : batch.parts) add(part->name, round, ms.at(i), t);
            t += batch.ms[i] / 1e3;
        }
    }
    warmedUp_ = true;
    result_.repetitions += count;
    result_.rounds = round + 1;
    judge(start);
}

void Rounds::resume(const std::vector<TimingSample>& earlier) {
    for (const TimingSample& s : earlier) {
        add(s.method, s.round, s.ms, s.t);
        result_.rounds = std::max(result_.rounds, s.round + 1);
    }
    result_.repetitions = int(result_.of(methods_.front().name).size());
    if (result_.rounds > 0) judge(Clock::now());
}

void Rounds::judge(Clock::time_point start) {
    if (result_.rounds < initialRounds_ || options_.targetCi <= 0) {
        result_.seconds += seconds(start, Clock::now());
        if (result_.rounds >= initialRounds_) result_.stop = "repetitions";
        return;
    }
    // An interval needs kMinAdaptiveRepetitions samples (statistics.h): judged from there on. The
    // judging counts against the time budget like the round it follows.
    bool converged = result_.repetitions >= kMinAdaptiveRepetitions;
    for (const TimedMethod& method : methods_)
        converged = converged && summarize(result_.of(method.name)).relativeHalfWidth() <= options_.targetCi;
    result_.seconds += seconds(start, Clock::now());
    if (converged)
        result_.stop = "converged";
    else if (result_.repetitions >= options_.maxRepetitions)
        result_.stop = "max_repetitions";
    else if (result_.seconds >= options_.budgetSeconds)
        result_.stop = "time_budget";
}

RoundsResult timeInRounds(const std::vector<TimedMethod>& methods, const HostLoops& hostLoops, const RoundsOptions& options,
                          std::chrono::steady_clock::time_point origin) {
    Rounds rounds(methods, hostLoops, options, origin);
    while (!rounds.done()) rounds.runRound();
    return rounds.result();
}

}  // namespace rtbench
