// Timing in rounds. A run's repetitions are split into rounds; each round times the strategy's
// host-controlled loops (if any), then a batch of the kernel, then of each Embree method, so that
// drift (clocks, caches, a neighbour's load) hits all of them alike. With experiment.target_ci,
// rounds are added until every method's interval of the median (order statistics) is narrow enough (a
// stopping rule like nvbench's, which stops on the relative standard deviation instead), from
// kMinAdaptiveRepetitions on, up to a count and a time budget. Every sample is kept.
#pragma once
#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "strategies/strategy.h"
#include "schema/columns.h"
#include "schema/keys.h"

namespace rtbench {

// The fewest samples whose median has a distribution-free 95% interval (statistics.h).
constexpr int kMinAdaptiveRepetitions = 6;

struct RoundsOptions {
    int warmups = 1;        // untimed, before each method's first batch
    int repetitions = 5;    // of each method (the minimum when adaptive)
    int rounds = 5;         // the repetitions split into this many (at most one per repetition)
    double targetCi = 0.0;  // adaptive: every median's interval within +- this fraction (0: off)
    int maxRepetitions = 200;
    double budgetSeconds = 30.0;
};
RoundsOptions roundsOptions(const RunConfig& run);

// A method the rounds time: `time(warmups, repetitions)` runs them back to back and returns each
// repetition's ms (and its parts: see TimedBatch).
struct TimedMethod {
    std::string name;  // samples.csv's method: kernel, embree1, embree16
    std::function<TimedBatch(int warmups, int repetitions)> time;
};

// One timed repetition, as samples.csv keeps it.
struct TimingSample {
    std::string method;  // a TimedMethod's name, <name>_<part>, or a host loop's name
    int round = 0;       // 0-based
    int repetition = 0;  // 0-based, over the run, per method
    double ms = 0.0;
    // Steady-clock seconds since `origin` (the invocation's start: kept rows and merged shards
    // keep their own) when the repetition began: its batch's start plus the warm-ups' and the
    // earlier repetitions' times (on a GPU, their GPU times).
    double t = 0.0;
};

struct RoundsResult {
    std::vector<TimingSample> samples;  // in the order taken
    // Each series' ms in order: the methods, their parts, the host loops (by TimedSeries::name).
    std::vector<std::pair<std::string, std::vector<double>>> series;
    int rounds = 0;
    int repetitions = 0;  // of each method
    std::string stop;     // repetitions, converged, max_repetitions, time_budget
    double seconds = 0.0;  // spent in the rounds (a run's own, in an interleaved sweep too)
    const std::vector<double>& of(const std::string& name) const;  // empty when none
};

// The strategy's host-controlled loops, timed once per round (KernelTimer::timeHostLoops).
using HostLoops = std::function<HostLoopTimes()>;

// One run's rounds, a round at a time: a sweep timed in interleaved order (experiment.order)
// runs round r of every run before round r + 1 of any.
class Rounds {
public:
    Rounds(std::vector<TimedMethod> methods, HostLoops hostLoops, const RoundsOptions& options,
           std::chrono::steady_clock::time_point origin);
    bool done() const { return !result_.stop.empty(); }
    // The next round: the host loops, then a batch of each method; then whether to stop.
    void runRound();
    // Whole rounds an earlier, interrupted invocation finished (its samples.csv rows of this run):
    // taken as this run's first rounds, so that the rounds go on from there; then whether to stop.
    // The warm-ups still come before this invocation's first batch.
    void resume(const std::vector<TimingSample>& earlier);
    const RoundsResult& result() const { return result_; }

private:
    void add(const std::string& name, int round, double ms, double t);
    // After round `result_.rounds - 1`: whether to stop, the judging counted from `start`.
    void judge(std::chrono::steady_clock::time_point start);
    bool warmedUp_ = false;
    std::vector<TimedMethod> methods_;
    HostLoops hostLoops_;
    RoundsOptions options_;
    std::chrono::steady_clock::time_point origin_;
    int initialRounds_, perRound_;
    RoundsResult result_;
    std::map<std::string, std::size_t> index_;  // series name -> position in result_.series
    std::map<std::string, int> taken_;          // samples per series so far
};

// All of one run's rounds.
RoundsResult timeInRounds(const std::vector<TimedMethod>& methods, const HostLoops& hostLoops, const RoundsOptions& options,
                          std::chrono::steady_clock::time_point origin);

// The columns of samples.csv, in order.
const std::vector<std::string>& sampleColumns();

// samples.csv (or a shard's) as the runner writes it: its header holds exactly sampleColumns().
// Throws rtbench::Error naming the file otherwise.
std::vector<Row> parseSamplesCsv(const std::string& text, const std::string& path);
std::vector<Row> readSamplesCsv(const std::string& path);

}  // namespace rtbench
