// Timing in rounds with synthetic methods: the schedule (rounds alternate the methods, warm-ups
// only before the first batch, the repetitions split evenly), adaptive stopping, and the noise
// guard's /proc parsers.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/noise_guard.h"
#include "harness/timing_rounds.h"

namespace rtbench {
namespace {

// A method whose repetitions take the times of `pattern` in turn; it logs every call.
struct FakeMethod {
    std::string name;
    std::vector<double> pattern;
    std::vector<std::pair<int, int>> calls;  // (warmups, repetitions)
    std::size_t next = 0;
    TimedMethod method() {
        return {name, [this](int warmups, int repetitions) {
                    calls.push_back({warmups, repetitions});
                    TimedBatch b;
                    for (int i = 0; i < repetitions; ++i) b.ms.push_back(pattern[next++ % pattern.size()]);
                    return b;
                }};
    }
};

RoundsOptions fixed(int repetitions, int rounds, int warmups = 2) {
    RoundsOptions o;
    o.repetitions = repetitions;
    o.rounds = rounds;
    o.warmups = warmups;
    return o;
}

TEST(TimingRounds, RoundsAlternateTheMethodsAndWarmUpOnlyFirst) {
    FakeMethod kernel{"kernel", {10.0}}, embree{"embree1", {20.0}};
    const RoundsResult r = timeInRounds({kernel.method(), embree.method()}, nullptr, fixed(5, 5),
                                        std::chrono::steady_clock::now());
    EXPECT_EQ(r.rounds, 5);
    EXPECT_EQ(r.repetitions, 5);
    EXPECT_EQ(r.stop, "repetitions");
    ASSERT_EQ(r.samples.size(), 10u);
    for (std::size_t i = 0; i < r.samples.size(); ++i) {
        EXPECT_EQ(r.samples[i].method, i % 2 ? "embree1" : "kernel") << i;
        EXPECT_EQ(r.samples[i].round, int(i / 2)) << i;
        EXPECT_EQ(r.samples[i].repetition, int(i / 2)) << i;
        if (i) {
            EXPECT_GE(r.samples[i].t, r.samples[i - 1].t) << i;  // in the order taken
        }
    }
    const std::vector<std::pair<int, int>> expected = {{2, 1}, {0, 1}, {0, 1}, {0, 1}, {0, 1}};
    EXPECT_EQ(kernel.calls, expected);
    EXPECT_EQ(embree.calls, expected);
    EXPECT_EQ(r.of("kernel"), std::vector<double>(5, 10.0));
    EXPECT_TRUE(r.of("nothing").empty());
}

TEST(TimingRounds, RepetitionsAreSplitEvenlyAndRoundsNeverExceedThem) {
    FakeMethod kernel{"kernel", {1.0}};
    timeInRounds({kernel.method()}, nullptr, fixed(7, 3, 0), std::chrono::steady_clock::now());
    const std::vector<std::pair<int, int>> sevenInThree = {{0, 2}, {0, 2}, {0, 3}};
    EXPECT_EQ(kernel.calls, sevenInThree);
    FakeMethod few{"kernel", {1.0}};
    const RoundsResult r = timeInRounds({few.method()}, nullptr, fixed(2, 5, 0), std::chrono::steady_clock::now());
    EXPECT_EQ(r.rounds, 2);
    EXPECT_EQ(r.repetitions, 2);
}

TEST(TimingRounds, PartsAndHostLoopsBecomeSeriesOfTheirOwn) {
    int loops = 0;
    static const TimedSeries setup{"kernel_setup", Column<double>({"kernel_ms_setup", ColumnKind::Timing, "ms", "setup"})};
    static const TimedSeries traverse{"kernel_traverse", Column<double>({"kernel_ms_traverse", ColumnKind::Timing, "ms", "traverse"})};
    static const TimedSeries live{"multipass_live", Column<double>({"multipass_live_ms_median", ColumnKind::Timing, "ms", "live"})};
    TimedMethod kernel{"kernel", [](int, int repetitions) {
                           TimedBatch b;
                           b.parts = {{&setup, {}}, {&traverse, {}}};
                           for (int i = 0; i < repetitions; ++i) {
                               b.ms.push_back(3.0);
                               b.parts[0].second.push_back(1.0);
                               b.parts[1].second.push_back(2.0);
                           }
                           return b;
                       }};
    const RoundsResult r = timeInRounds({kernel}, [&] {
        ++loops;
        return HostLoopTimes{{&live, 9.0}};
    }, fixed(4, 2, 0), std::chrono::steady_clock::now());
    EXPECT_EQ(loops, 2);  // once per round
    EXPECT_EQ(r.of("kernel_setup"), std::vector<double>(4, 1.0));
    EXPECT_EQ(r.of("kernel_traverse"), std::vector<double>(4, 2.0));
    EXPECT_EQ(r.of("multipass_live"), std::vector<double>(2, 9.0));
    // The host loop comes first in its round: the kernel batch is the last to write the hits.
    EXPECT_EQ(r.samples.front().method, "multipass_live");
}

TEST(TimingRounds, AdaptiveRoundsStopWhenTheIntervalIsNarrow) {
    RoundsOptions o = fixed(6, 6, 0);
    o.targetCi = 0.02;
    FakeMethod steady{"kernel", {10.0}};
    const RoundsResult r = timeInRounds({steady.method()}, nullptr, o, std::chrono::steady_clock::now());
    EXPECT_EQ(r.stop, "converged");
    EXPECT_EQ(r.repetitions, 6);
}

TEST(TimingRounds, AdaptiveRoundsJudgeNoIntervalOfFewerThanSixSamples) {
    RoundsOptions o = fixed(1, 5, 0);
    o.targetCi = 0.02;
    FakeMethod steady{"kernel", {10.0}};
    const RoundsResult r = timeInRounds({steady.method()}, nullptr, o, std::chrono::steady_clock::now());
    EXPECT_EQ(r.stop, "converged");
    EXPECT_EQ(kMinAdaptiveRepetitions, 6);  // the fewest samples with a distribution-free 95% interval
    EXPECT_EQ(r.repetitions, kMinAdaptiveRepetitions);  // not 1: one sample has no interval
}

TEST(TimingRounds, AdaptiveRoundsStopAtTheCountOrTheBudget) {
    RoundsOptions o = fixed(5, 5, 0);
    o.targetCi = 0.02;
    o.maxRepetitions = 12;
    FakeMethod noisy{"kernel", {1.0, 100.0}};  // its median's interval never narrows
    RoundsResult r = timeInRounds({noisy.method()}, nullptr, o, std::chrono::steady_clock::now());
    EXPECT_EQ(r.stop, "max_repetitions");
    EXPECT_EQ(r.repetitions, 12);
    EXPECT_EQ(r.rounds, 12);
    o.budgetSeconds = 0.0;
    FakeMethod again{"kernel", {1.0, 100.0}};
    r = timeInRounds({again.method()}, nullptr, o, std::chrono::steady_clock::now());
    EXPECT_EQ(r.stop, "time_budget");
    EXPECT_EQ(r.repetitions, 5);  // the initial rounds are always run
}

// experiment.time_budget_s bounds the whole adaptive loop, the judging after each round included:
// methods that cost nothing leave the judging (thousands of samples sorted a round) as the only
// cost, and it must be in the seconds the budget is held to (it once ran outside them: a 3 s
// budget took 88 s).
TEST(TimingRounds, TheTimeBudgetCountsTheJudgingAfterEachRound) {
    RoundsOptions o = fixed(6, 1, 0);
    o.targetCi = 1e-9;
    o.maxRepetitions = 100000000;
    o.budgetSeconds = 0.3;
    FakeMethod noisy{"kernel", {}};  // 997 distinct times in turn: its median's interval never narrows
    for (int i = 1; i <= 997; ++i) noisy.pattern.push_back(double(i));
    const auto start = std::chrono::steady_clock::now();
    const RoundsResult r = timeInRounds({noisy.method()}, nullptr, o, start);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.stop, "time_budget");
    EXPECT_GT(r.rounds, 1);
    EXPECT_GE(r.seconds, 0.9 * wall) << "the loop's time is the budget's";
}

TEST(NoiseGuard, ProcParsers) {
    // user nice system idle iowait irq softirq steal: busy = all but idle and iowait.
    EXPECT_DOUBLE_EQ(machineBusyTicks("cpu  10 20 30 400 50 6 7 8 0 0\ncpu0 1 2 3 4 5 6 7 8 0 0\n"), 81.0);
    EXPECT_DOUBLE_EQ(machineBusyTicks("intr 1 2 3\n"), -1.0);
    // utime and stime are fields 14 and 15; the command name may hold spaces and parentheses.
    EXPECT_DOUBLE_EQ(selfTicks("4242 (rt (b) x) S 1 2 3 4 5 6 7 8 9 10 11 22 0 0 20"), 33.0);
    EXPECT_DOUBLE_EQ(selfTicks("4242 no parenthesis"), -1.0);
    CpuTimes before, after;
    before.valid = after.valid = true;
    before.machineBusyTicks = 100, before.selfTicks = 10, before.wallSeconds = 5.0;
    after.machineBusyTicks = 300, after.selfTicks = 60, after.wallSeconds = 6.0;
    // Others: 200 - 50 = 150 ticks = 1.5 s of 2 cores x 1 s.
    EXPECT_DOUBLE_EQ(otherCpuFraction(before, after, 2, 100.0), 0.75);
    // A window of 2 cores x 0.1 s is 20 ticks: too short to tell.
    after.wallSeconds = 5.1;
    EXPECT_DOUBLE_EQ(otherCpuFraction(before, after, 2, 100.0), -1.0);
    after.wallSeconds = 6.0;
    after.valid = false;
    EXPECT_DOUBLE_EQ(otherCpuFraction(before, after, 2, 100.0), -1.0);
    EXPECT_EQ(deviceHostThreads(false, 16), 0u);
}

TEST(NoiseGuard, JudgesTheMediansIntervalFromSixRepetitionsAndTheCvBelow) {
    const std::vector<double> oneSlowOfTen = {10, 10, 10, 10, 100, 10, 10, 10, 10, 10};
    // n = 10 at 95%: [x(2), x(9)] (coverage 1 - 2 * 11/1024 = 0.979) = [10, 10]: the median is
    // certain although one repetition took 10x (CV = sqrt(810) / 19 = 1.50).
    const SampleStats slow = summarize(oneSlowOfTen);
    ASSERT_NEAR(*slow.cv, std::sqrt(810.0) / 19.0, 1e-12);
    EXPECT_EQ(spreadWarning("kernel", slow, 0.05, 0.05), "");
    // Half at 10 ms and half at 12: the median 11 in [10, 12], +-1/11 = 9.09%.
    const SampleStats split = summarize({10, 12, 10, 12, 10, 12, 10, 12, 10, 12});
    EXPECT_EQ(spreadWarning("embree1", split, 0.05, 1.0), "embree1 interval +-9.09% > experiment.noise_ci 0.05");
    EXPECT_EQ(spreadWarning("embree1", split, 0.1, 0.0), "");
    // Half at 10 and half at 11: +-0.5/10.5 = 4.76%, within 5%.
    EXPECT_EQ(spreadWarning("kernel", summarize({10, 11, 10, 11, 10, 11, 10, 11, 10, 11}), 0.05, 0.0), "");
    // Six repetitions give [x(1), x(6)] (coverage 1 - 2/64): {1 x5, 25} has median 1 in [1, 25],
    // +-12 = 1200%, written in plain digits (the sanitizer build once wrote "1.14e+03%").
    EXPECT_EQ(spreadWarning("kernel", summarize({1, 1, 1, 1, 1, 25}), 0.05, 0.0), "kernel interval +-1200% > experiment.noise_ci 0.05");
    // 3 repetitions give no interval: the CV judges. {10, 10, 12}: sd sqrt(4/3), mean 32/3.
    const SampleStats three = summarize({10, 10, 12});
    ASSERT_FALSE(three.ci);
    ASSERT_NEAR(*three.cv, std::sqrt(4.0 / 3.0) / (32.0 / 3.0), 1e-12);
    EXPECT_EQ(spreadWarning("kernel", three, 0.0, 0.05), "kernel CV 0.108 (3 repetitions: no interval) > experiment.noise_cv 0.05");
    EXPECT_EQ(spreadWarning("kernel", three, 0.0, 0.2), "");
    // One repetition: no spread to judge (the caller says its noise is not measured).
    EXPECT_EQ(spreadWarning("kernel", summarize({10}), 0.0, 0.0), "");
}

}  // namespace
}  // namespace rtbench
