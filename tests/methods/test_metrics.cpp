// Independent checks of the formulas: made-up inputs whose answers are computed by hand here, not
// by the code under test (a scheduler bug cannot hide behind the GPU and the simulator sharing it).
#include <gtest/gtest.h>

#include "methods/accounting.h"
#include "methods/metrics.h"
#include "strategies/multipass/multipass_schedule.h"

namespace rtbench {
namespace {

gpu::HitRecord hit(std::uint32_t primitive, float t, std::uint32_t steps = 0,
                   std::uint32_t tests = 0) {
    gpu::HitRecord h{};
    h.primitive = primitive;
    h.t = primitive == gpu::kNoHit ? gpu::kNoHitT : t;
    h.traversalSteps = steps;
    h.trianglesTested = tests;
    return h;
}

TEST(Oracle, IntersectsWhenTheWaitingFractionReachesTheThresholdExactly) {
    MultipassOptions o;
    o.oracleThreshold = 0.25;
    // 1 of 4 active rays waits: 0.25 >= 0.25 (Purcell §3.2: intersect once the fraction is
    // reached).
    EXPECT_EQ(PassScheduler(o, 0).next(3, 1), PassKind::Intersect);
    // 1 of 5: 0.2 < 0.25.
    EXPECT_EQ(PassScheduler(o, 0).next(4, 1), PassKind::Traverse);
}

TEST(Oracle, UsesTheWaitingNotTheTraversingFraction) {
    MultipassOptions o;
    o.oracleThreshold = 0.5;
    // 1 waiting of 10: 0.1 < 0.5 -> traverse (the traversing fraction, 0.9, would intersect).
    EXPECT_EQ(PassScheduler(o, 0).next(9, 1), PassKind::Traverse);
    // 9 waiting of 10: 0.9 >= 0.5 -> intersect (the traversing fraction, 0.1, would traverse).
    EXPECT_EQ(PassScheduler(o, 0).next(1, 9), PassKind::Intersect);
}

TEST(Oracle, NaiveSchedulingStaysInItsPhaseUntilItDrains) {
    MultipassOptions o;
    o.scheduling = "naive";
    PassScheduler s(o, 0);
    EXPECT_EQ(s.next(5, 0), PassKind::Traverse);
    EXPECT_EQ(s.next(4, 100), PassKind::Traverse);   // rays still traverse: stay
    EXPECT_EQ(s.next(0, 100), PassKind::Intersect);  // none traverses: switch
    EXPECT_EQ(s.next(100, 1), PassKind::Intersect);  // rays still wait: stay
    EXPECT_EQ(s.next(0, 0), PassKind::Write);
}

TEST(PassCap, IsFourTimesThePerRayBoundPlusSixteen) {
    // Vmax = 2 + 3 + 4 = 9 voxels; Lmax = 5. K = 2: ceil(9/2) = 5; M = 3: ceil(45/3) = 15.
    MultipassOptions o;
    o.traverseStepsPerPass = 2;
    o.intersectionsPerPass = 3;
    EXPECT_EQ(multipassPassCap(2 + 3 + 4, 5, o), 4u * (5 + 15) + 16);
    o.traverseStepsPerPass = o.intersectionsPerPass = 1;
    EXPECT_EQ(multipassPassCap(2 + 3 + 4, 0, o), 4u * (9 + 9) + 16);  // an empty grid still gets Lmax 1
}

TEST(PassLoop, ThePassCapTurnsARunawayIntoAnError) {
    MultipassOptions o;
    int passes = 0;
    // A pass that never finishes any ray: the cap must stop it after exactly `cap` passes.
    EXPECT_THROW(runPassLoop(o, 7, 1,
                             [&](PassKind) {
                                 ++passes;
                                 PassSums s;
                                 s.traversing = 1;
                                 return s;
                             }),
                 std::exception);
    EXPECT_EQ(passes, 7);
}

TEST(LowerBound, RoundsEachTermUp) {
    // Max 5 steps with K = 2 -> 3 passes; max 7 tests with M = 3 -> 3 passes: bound 6.
    const std::vector<gpu::HitRecord> hits = {hit(0, 1.0f, 5, 1), hit(gpu::kNoHit, 0, 2, 7),
                                              hit(1, 2.0f, 4, 6)};
    MultipassOptions o;
    o.traverseStepsPerPass = 2;
    o.intersectionsPerPass = 3;
    EXPECT_EQ(multipassMetrics(hits, MultipassCounts{}, o, StructureCosts{}).passesLowerBound, 6u);
    o.traverseStepsPerPass = 5;
    o.intersectionsPerPass = 7;
    EXPECT_EQ(multipassMetrics(hits, MultipassCounts{}, o, StructureCosts{}).passesLowerBound, 2u);  // exact division
}

TEST(Agreement, FractionsUseTheirOwnDenominators) {
    // 5 rays: ray 1 is a hit/miss mismatch; rays 0, 2, 3 both hit, ray 3 on another triangle;
    // ray 4 both miss.
    const std::vector<gpu::HitRecord> mine = {hit(7, 2.0f), hit(1, 1.0f), hit(3, 4.0f),
                                              hit(9, 1.5f), hit(gpu::kNoHit, 0)};
    const std::vector<gpu::HitRecord> ref = {hit(7, 2.0f), hit(gpu::kNoHit, 0), hit(3, 5.0f),
                                             hit(8, 1.0f), hit(gpu::kNoHit, 0)};
    const Agreement a = compareHits(mine, ref);
    EXPECT_EQ(a.hitMissMismatches, 1u);
    EXPECT_EQ(a.bothHit, 3u);
    EXPECT_EQ(a.primitiveMismatches, 1u);
    EXPECT_DOUBLE_EQ(a.hitMissAgreement, 4.0 / 5.0);        // of all rays
    EXPECT_DOUBLE_EQ(a.samePrimitiveAgreement, 2.0 / 3.0);  // of rays both hit
    // |4 - 5| / 5 = 0.2 and |1.5 - 1| / 1 = 0.5 over 3 rays both hit.
    EXPECT_DOUBLE_EQ(a.relDistanceErrorMean, (0.0 + 0.2 + 0.5) / 3.0);
    EXPECT_DOUBLE_EQ(a.relDistanceErrorMax, 0.5);
}

TEST(WorkStats, MeansAndMaximaOverRays) {
    std::vector<gpu::HitRecord> hits = {hit(0, 1.0f, 3, 4), hit(gpu::kNoHit, 0, 6, 0)};
    hits[0].cellsVisited = 3, hits[1].cellsVisited = 5;
    const WorkStats w = workStats(hits);
    EXPECT_EQ(w.hits, 1u);
    EXPECT_DOUBLE_EQ(w.cellsPerRayMean, 4.0);
    EXPECT_EQ(w.cellsPerRayMax, 5u);
    EXPECT_DOUBLE_EQ(w.trianglesPerRayMean, 2.0);
    EXPECT_EQ(w.stepsPerRayMax, 6u);
    EXPECT_EQ(w.stepsTotal, 9u);
}

// The two SIMD measures by hand. Ray 0 takes 3 steps and 4 tests (7 iterations), ray 1 6 steps
// (6), ray 2 nothing: in lock step the stream runs 7 iterations over 3 rays, 21 slots of which
// 3 + 4 + 6 = 13 work (Purcell's measure); the ballots' lanes are another count altogether.
TEST(SimdEfficiency, PurcellsOverTheStreamInLockStepAndTheLaneUtilisationApart) {
    std::vector<gpu::HitRecord> hits = {hit(0, 1.0f, 3, 4), hit(gpu::kNoHit, 0, 6, 0), hit(gpu::kNoHit, 0, 0, 0)};
    const WorkStats w = workStats(hits);
    EXPECT_EQ(w.workPerRayMax, 7u);
    EXPECT_DOUBLE_EQ(lockStepStreamEfficiency(w, hits.size()), 13.0 / 21.0);
    const ArchitectureMetrics m = branchingMetrics(hits, 30, 48, StructureCosts{});
    EXPECT_DOUBLE_EQ(m.laneUtilisation, 30.0 / 48.0);
    EXPECT_DOUBLE_EQ(m.simdEfficiency, 30.0 / 48.0);
    EXPECT_DOUBLE_EQ(m.purcellSimdEfficiency, 13.0 / 21.0);
    EXPECT_DOUBLE_EQ(lockStepStreamEfficiency(workStats({hit(gpu::kNoHit, 0, 0, 0)}), 1), 1.0);  // no work: nothing idles
}

}  // namespace
}  // namespace rtbench
