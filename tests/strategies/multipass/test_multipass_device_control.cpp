// Multipass with the oracle on the device (strategy.control = "device"): the oracle kernel's
// choices against hand-counted sequences and against the host's loop on the same rays, the
// compacted lists' slots and appends by hand, and the fixed-point decision by hand.
#include <gtest/gtest.h>

#include "methods/accounting.h"
#include "strategies/branching/branching_strategy.h"
#include "structures/bvh/bvh_build.h"
#include "structures/bvh/bvh_structure.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "strategies/multipass/multipass_simulator.h"
#include "strategies/multipass/multipass_strategy.h"
#include "scene/camera.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/methods/hand_scenes.h"
#include "tests/strategies/multipass/multipass_options.h"

namespace rtbench {
namespace {

// The hand scene (tests/methods/hand_scenes.h): a 4x1x1 grid, voxel lists v0 {0}, v1 {}, v2 {2,3}, v3 {1,4,5};
// ray 0 along +x hits triangle 2, ray 1 misses the box, ray 2 along -x hits triangle 4.
using hand::handGrid;
using hand::handRays;

MultipassOptions onDevice(double threshold, unsigned k = 1, unsigned m = 1, bool suppress = false) {
    return hand::multipassOptions(threshold, k, m, suppress, true);
}

using K = PassKind;

TEST(MultipassOracle, TheThresholdInFixedPointByHand) {
    EXPECT_EQ(oracleThresholdQ31(0.2), 429496729u);  // floor(0.2 * 2^31 = 429496729.6)
    EXPECT_EQ(oracleThresholdQ31(1.0), 2147483648u);
    EXPECT_EQ(oracleThresholdQ31(0.0), 0u);
    EXPECT_THROW(oracleThresholdQ31(1.5), std::exception);
    auto next = [](double threshold, std::uint64_t traversing, std::uint64_t waiting) {
        MultipassOptions o;
        o.oracleThreshold = threshold;
        return PassScheduler(o, traversing + waiting).next(traversing, waiting);
    };
    EXPECT_EQ(next(0.2, 4, 1), K::Intersect);  // 1 of 5 waits: exactly 20%
    EXPECT_EQ(next(0.2, 5, 1), K::Traverse);   // 1 of 6
    EXPECT_EQ(next(0.2, 800000, 199999), K::Traverse);  // 0.1999992
    EXPECT_EQ(next(0.2, 800000, 200000), K::Intersect);  // exactly 20%
    EXPECT_EQ(next(1.0, 1, 1000), K::Traverse);  // only when none traverses
    EXPECT_EQ(next(1.0, 0, 1), K::Intersect);
    EXPECT_EQ(next(0.0, 1000, 1), K::Intersect);  // as soon as any waits
    EXPECT_EQ(next(0.5, 0, 0), K::Write);
}

// The waiting fraction's two bases by hand (strategy.oracle_basis): 3 traversing and 2 waiting of a
// stream of 10 are 2/5 = 40% of the active rays but 2/10 = 20% of all.
TEST(MultipassOracle, TheTwoBasesOfTheWaitingFractionByHand) {
    MultipassOptions o;
    o.oracleThreshold = 0.3;
    EXPECT_EQ(PassScheduler(o, 10).next(3, 2), K::Intersect);
    o.oracleBasis = "all";
    EXPECT_EQ(PassScheduler(o, 10).next(3, 2), K::Traverse);
    EXPECT_EQ(PassScheduler(o, 10).next(2, 3), K::Intersect);  // 3 of 10 = 30%
    EXPECT_EQ(PassScheduler(o, 10).next(0, 1), K::Intersect);  // none traverses: whatever the fraction
}

class MultipassDeviceControl : public VulkanTest {
protected:
    static MultipassRun run(const Structure& s, const std::vector<gpu::Ray>& rays, const MultipassOptions& o) {
        return runMultipass(*vk_, s, rays, o, {64, 0, 1});
    }
};

TEST_F(MultipassDeviceControl, HandCountedPassesListsAndBytes) {
    // The sequence of threshold 0 by hand (test_multipass_kernels.cpp HandCountedPassesWithThresholdZero),
    // now chosen by the oracle kernel. The lists each pass is dispatched for, by hand: after setup
    // rays 0 and 2 wait (2 slots); I leaves 0 traversing and 2 waiting (1); I: ray 2 (1); T: ray 0
    // (1); T (1); I (1); I (1): 8 slots, all served. Rays left active (list appends): setup 2,
    // then 2, 1, 0, 1, 1, 1, 0: 8.
    const UniformGrid grid = handGrid();
    const MultipassOptions o = onDevice(0.0);
    const MultipassRun r = run(*gridStructure(grid), handRays(), o);
    EXPECT_EQ(r.counts.sequence, (std::vector<K>{K::Setup, K::Intersect, K::Intersect, K::Intersect, K::Traverse,
                                                 K::Traverse, K::Intersect, K::Intersect, K::Write}));
    EXPECT_EQ(r.counts.usefulTraverse, 2u);
    EXPECT_EQ(r.counts.usefulIntersect, 6u);
    EXPECT_EQ(r.counts.stencilWrites, 7u);
    EXPECT_EQ(r.counts.streamSlots, 8u);
    EXPECT_EQ(r.counts.listAppends, 8u);
    EXPECT_EQ(r.hits[0].primitive, 2u);
    EXPECT_EQ(r.hits[1].primitive, gpu::kNoHit);
    EXPECT_EQ(r.hits[2].primitive, 4u);
    const ArchitectureMetrics m = multipassMetrics(r.hits, r.counts, o, gridStructure(grid)->costs());
    EXPECT_DOUBLE_EQ(m.simdEfficiency, 1.0);  // every slot of a compacted pass is a ray it serves
    EXPECT_EQ(r.counts.wholeStreamSlots, 7u * 3u);  // Purcell's over the whole stream: as the host loop's
    EXPECT_DOUBLE_EQ(m.purcellSimdEfficiency, 8.0 / 21.0);
    EXPECT_LT(m.laneUtilisation, 0.0);  // no ballots counted
    EXPECT_EQ(m.bytes.stencil, 7u);           // writes only: no pass reads the stencil
    EXPECT_EQ(m.bytes.compaction, (8u + 8u) * 4u);
    EXPECT_EQ(m.bytes.state, 3u * 80u + 2u * 112u + 6u * 128u + 3u * 16u);  // as with the stencil
}

// The hand scene's 3 rays at threshold 0.4. After setup rays 0 and 2 wait (none traverses:
// intersect); then ray 0 traverses and ray 2 waits: 1 of 2 active rays (50% >= 40%: intersect,
// the threshold-0 sequence) but 1 of 3 of all (33% < 40%: traverse, the threshold-1 sequence).
// The host's loop, the device's oracle and the CPU simulator alike.
TEST_F(MultipassDeviceControl, TheOracleBasesGiveTheHandCountedSequences) {
    const UniformGrid grid = handGrid();
    const auto structure = gridStructure(grid);
    const std::vector<K> active = {K::Setup, K::Intersect, K::Intersect, K::Intersect, K::Traverse, K::Traverse,
                                   K::Intersect, K::Intersect, K::Write};
    const std::vector<K> all = {K::Setup, K::Intersect, K::Traverse, K::Traverse, K::Intersect, K::Intersect, K::Write};
    for (const bool device : {false, true}) {
        for (const char* basis : {"active", "all"}) {
            SCOPED_TRACE(std::string(device ? "device" : "host") + ", basis " + basis);
            MultipassOptions o = hand::multipassOptions(0.4, 1, 1, false, device);
            o.oracleBasis = basis;
            const std::vector<K>& expected = std::string(basis) == "all" ? all : active;
            EXPECT_EQ(run(*structure, handRays(), o).counts.sequence, expected);
            EXPECT_EQ(simulateMultipass(*structure, handRays(), o).counts.sequence, expected);
        }
    }
}

TEST_F(MultipassDeviceControl, ThresholdOneAndTheNaiveScheduleByHand) {
    const UniformGrid grid = handGrid();
    EXPECT_EQ(run(*gridStructure(grid), handRays(), onDevice(1.0)).counts.sequence,
              (std::vector<K>{K::Setup, K::Intersect, K::Traverse, K::Traverse, K::Intersect, K::Intersect, K::Write}));
    MultipassOptions naive = onDevice(0.2);
    naive.scheduling = "naive";
    EXPECT_EQ(run(*gridStructure(grid), handRays(), naive).counts.sequence,
              (std::vector<K>{K::Setup, K::Intersect, K::Intersect, K::Intersect, K::Traverse, K::Traverse,
                              K::Intersect, K::Intersect, K::Write}));
}

// The oracle kernel chooses every pass the host's loop chooses on the same rays (a check that
// does not go through the simulator), its counts equal the simulator's, and its hits branching's,
// for every unroll, threshold and schedule, on the grid and the BVH.
TEST_F(MultipassDeviceControl, ChoosesAsTheHostLoopForEveryUnrollAndSchedule) {
    const std::vector<gpu::Ray> rays = hand::sceneBRays();
    for (const auto& s : hand::sceneBStructures()) {
        const BranchingRun branching = runBranching(*vk_, *s, rays, {64, 0, 1});
        for (auto [k, m] : {std::pair{1u, 1u}, std::pair{4u, 2u}})
            for (const char* schedule : {"0", "0.2", "1", "naive"})
                for (bool suppress : {false, true}) {
                    if (suppress && k == 1) continue;  // nothing to suppress
                        SCOPED_TRACE(s->kernelPrefix() + " K=" + std::to_string(k) + " M=" + std::to_string(m) + " " +
                                     schedule + (suppress ? " suppressed" : ""));
                        MultipassOptions o = onDevice(0.2, k, m, suppress);
                        if (std::string(schedule) == "naive")
                            o.scheduling = "naive";
                        else
                            o.oracleThreshold = std::stod(schedule);
                        const MultipassRun device = run(*s, rays, o);
                        MultipassOptions host = o;
                        host.deviceControl = false;
                        const MultipassRun hostRun = run(*s, rays, host);
                        EXPECT_EQ(device.counts.sequence, hostRun.counts.sequence);
                        EXPECT_EQ(device.counts.usefulTraverse, hostRun.counts.usefulTraverse);
                        EXPECT_EQ(device.counts.usefulIntersect, hostRun.counts.usefulIntersect);
                        EXPECT_EQ(device.counts.streamSlots, device.counts.usefulTraverse + device.counts.usefulIntersect);
                        EXPECT_EQ(recordMismatches(device.hits, branching.hits), 0u);  // counters too
                        EXPECT_EQ(device.traversalStates, hostRun.traversalStates);
                        EXPECT_TRUE(device.counts == simulateMultipass(*s, rays, o).counts);
                    }
    }
}

// Runs scene B's grid and BVH with the control on the device (K = 4, M = 2) at every number of
// list partitions and workgroup size given: each run must file every active ray once, so give the
// host loop's sequence, events, hits and final traversal states (its passes use no lists), and
// the simulator's counts.
void expectEachRayFiledOnce(VulkanContext& vk, std::initializer_list<unsigned> partitionCounts,
                            std::initializer_list<unsigned> workgroups) {
    const std::vector<gpu::Ray> rays = hand::sceneBRays();
    MultipassOptions o = onDevice(0.2, 4, 2);
    MultipassOptions host = o;
    host.deviceControl = false;
    for (const auto& s : hand::sceneBStructures()) {
        const MultipassRun hostRun = runMultipass(vk, *s, rays, host, {64, 0, 1});
        const MultipassCounts simulated = simulateMultipass(*s, rays, o).counts;
        for (unsigned partitions : partitionCounts)
            for (unsigned workgroup : workgroups) {
                SCOPED_TRACE(s->kernelPrefix() + " " + std::to_string(partitions) + " partitions, workgroup " +
                             std::to_string(workgroup));
                o.listPartitions = partitions;
                const MultipassRun device = runMultipass(vk, *s, rays, o, {workgroup, 0, 1});
                EXPECT_EQ(device.counts.sequence, hostRun.counts.sequence);
                EXPECT_TRUE(device.counts == simulated);
                EXPECT_EQ(recordMismatches(device.hits, hostRun.hits), 0u);
                EXPECT_EQ(device.traversalStates, hostRun.traversalStates);
            }
    }
}

// Each subgroup claims its rays' list entries by ballot (multipass_common.glsl mpAppend). Every
// workgroup shape must file each active ray once: one invocation, one subgroup, a partial last
// subgroup (on a device of 8 or 16 lanes), several full ones; the default two list partitions.
TEST_F(MultipassDeviceControl, EveryWorkgroupShapeFilesEachRayOnce) {
    expectEachRayFiledOnce(*vk_, {MultipassOptions{}.listPartitions}, {1u, 8u, 20u, 64u, 256u});
}

// Each list in partitions (strategy.list_partitions), a workgroup run appending to each
// (multipass_common.glsl mpPartition), the next pass reading them in order (mpServedRay): one, the
// default two, three (runs that do not divide the workgroups evenly) and eight, with one
// invocation a workgroup (a partition per workgroup run of a few) and 64.
TEST_F(MultipassDeviceControl, EveryListPartitioningFilesEachRayOnce) {
    expectEachRayFiledOnce(*vk_, {1u, 2u, 3u, unsigned(gpu::kMaxListPartitions)}, {1u, 64u});
}

// Timed repetitions rerun the oracle kernel's loop uninstrumented; their hits must equal the
// instrumented run's (the timer checks), and the oracle's own time is a part of its own.
TEST_F(MultipassDeviceControl, TimedRepetitionsRunTheSameLoop) {
    const auto grid = gridStructure(hand::sceneBGrid());
    MultipassRun r = runMultipass(*vk_, *grid, hand::sceneBRays(), onDevice(0.2, 4, 2), {64, 1, 3});
    EXPECT_EQ(r.gpuMs.size(), 3u);
    const TimedBatch batch = r.timer->time(0, 2);
    ASSERT_EQ(batch.parts.size(), 5u);
    EXPECT_EQ(batch.parts[4].first->name, "kernel_oracle");
    EXPECT_NO_THROW(r.timer->checkHits());
    const auto live = r.timer->timeHostLoops();  // the instrumented loop again, checked against the first
    ASSERT_EQ(live.size(), 1u);
    EXPECT_EQ(live[0].first->name, "multipass_live");
}

// Batches with the control on the device: each batch its own lists and oracle loop; records and
// events equal one stream's, passes each batch's, as with the control on the host.
TEST_F(MultipassDeviceControl, ABatchedRunTracesAsOneStream) {
    const std::vector<gpu::Ray> rays = hand::sceneBRays();
    const auto bvh = bvhStructure(buildBvh(christenSceneB(), BvhBuildOptions{}));
    MultipassOptions o = onDevice(0.2, 4, 2);
    const MultipassRun whole = run(*bvh, rays, o);
    o.batchRays = 512;
    const MultipassRun batched = run(*bvh, rays, o);
    EXPECT_EQ(batched.batches, 4u);
    EXPECT_EQ(recordMismatches(batched.hits, whole.hits), 0u);
    EXPECT_EQ(batched.counts.usefulTraverse + batched.counts.usefulIntersect,
              whole.counts.usefulTraverse + whole.counts.usefulIntersect);
    EXPECT_EQ(batched.counts.streamSlots, whole.counts.streamSlots);  // each ray's passes, whichever batch
    EXPECT_TRUE(batched.counts == simulateMultipass(*bvh, rays, o, gpu::kQueryClosest, 512).counts);
}

TEST_F(MultipassDeviceControl, PassCapTurnsARunawayIntoAClearError) {
    MultipassOptions o = onDevice(0.0);
    o.maxPasses = 4;  // the hand scene needs 8 before the write pass
    try {
        run(*gridStructure(handGrid()), handRays(), o);
        FAIL() << "expected the pass cap to fire";
    } catch (const std::exception& e) {
        // The oracle kernel itself stopped at the cap (not the host's replay of a loop run to its end).
        EXPECT_STREQ(e.what(), "multipass (device): the oracle kernel stopped the loop at the pass cap of 4 after 4 passes, "
                               "with 1 rays still active");
    }
}

}  // namespace
}  // namespace rtbench
