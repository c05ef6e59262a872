// A run's verdict (harness/run_verdict.h): the first reason its records or counts cannot be
// trusted, and the timed run's check deferring to it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "harness/run_verdict.h"
#include "core/error.h"
#include "tests/error_of.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;
using ::testing::Not;

// A timer whose timed run's records differ from the instrumented run's, or do not.
class FakeTimer : public KernelTimer {
public:
    explicit FakeTimer(bool differs) : differs_(differs) {}
    TimedBatch time(int, int) override { return {}; }
    void checkHits() override {
        if (differs_) throw Error("fake kernel: the timed run's hits differ from the instrumented run's on 2 of 9 rays");
    }

private:
    bool differs_;
};

StrategyRun runWith(bool timedDiffers) {
    StrategyRun run;
    run.timer = std::make_unique<FakeTimer>(timedDiffers);
    return run;
}

TEST(RunVerdict, ATrustedRunHasNoFailure) {
    StrategyRun run = runWith(false);
    EXPECT_EQ(instrumentedRunFailure(run, "", 9), "");
    EXPECT_NO_THROW(checkTimedRecords(run, "", 9));
}

// In order: shading, rays cut short, records, counts, multipass against branching, models; each
// named when the ones before it are absent.
TEST(RunVerdict, TheFirstCauseInOrderIsNamed) {
    StrategyRun run = runWith(false);
    run.modelMismatch = "models differ";
    EXPECT_EQ(instrumentedRunFailure(run, "", 9), "models differ");
    run.branchingMismatches = 4;
    EXPECT_EQ(instrumentedRunFailure(run, "", 9), "the multipass hit records differ from the branching caster's on 4 of 9 rays");
    run.countsMismatch = "passes differ";
    EXPECT_EQ(instrumentedRunFailure(run, "", 9), "the kernel's passes differ from the CPU reference's");
    run.cpuMismatches = 3;
    EXPECT_EQ(instrumentedRunFailure(run, "", 9), "the kernel's hit records differ from the CPU reference's on 3 of 9 rays");
    run.truncatedRays = 2;
    run.truncatedWhy = "2 rays cut short";
    EXPECT_EQ(instrumentedRunFailure(run, "", 9), "2 rays cut short");
    EXPECT_EQ(instrumentedRunFailure(run, "shading differs", 9), "shading differs");
}

// A timed run that differs fails the run; where the instrumented run had already failed, the
// error names that cause first (persistent threads cut short by llvmpipe's loop limit used to say
// only "different results on the same input" while their instrumented records were already wrong).
TEST(RunVerdict, ATimedRunThatDiffersNamesTheInstrumentedRunsFailureFirst) {
    StrategyRun run = runWith(true);
    EXPECT_THAT(errorOf([&] { checkTimedRecords(run, "", 9); }), HasSubstr("fake kernel: the timed run's hits differ"));
    run.cpuMismatches = 3;
    const std::string error = errorOf([&] { checkTimedRecords(run, "", 9); });
    EXPECT_THAT(error, HasSubstr("the kernel's hit records differ from the CPU reference's on 3 of 9 rays; "
                                 "the timed run's records differ from the instrumented run's too"));
    EXPECT_THAT(error, Not(HasSubstr("fake kernel")));
}

}  // namespace
}  // namespace rtbench
