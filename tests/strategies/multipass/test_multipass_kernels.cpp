// The multipass kernels (Purcell et al. 2002 §3.2) on Vulkan: hand-counted passes on a tiny
// scene, identity with the branching kernel and the CPU simulator, oracle behaviour, pass cap.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <random>

#include "methods/accounting.h"
#include "strategies/branching/branching_strategy.h"
#include "strategies/branching/lane_counts.h"
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

using hand::handGrid;
using hand::handRays;

MultipassOptions oracle(double threshold, unsigned k = 1, unsigned m = 1, bool suppress = false) {
    return hand::multipassOptions(threshold, k, m, suppress);
}

class MultipassKernels : public VulkanTest {
protected:
    static MultipassRun run(const UniformGrid& grid, const std::vector<gpu::Ray>& rays, const MultipassOptions& o) {
        return runMultipass(*vk_, *gridStructure(grid), rays, o, {64, 0, 1});
    }
};

using K = PassKind;

TEST_F(MultipassKernels, HandCountedPassesWithThresholdZero) {
    // Threshold 0 intersects whenever a ray waits. After setup rays 0 and 2 wait (voxels 0 and 3):
    // I: ray 0 misses tri 0, list done -> traverse; ray 2 misses tri 1.  I: ray 2 hits tri 4.
    // I: ray 2 misses tri 5, hit within voxel 3 -> done.  T: ray 0 into empty voxel 1.
    // T: ray 0 into voxel 2 -> waits.  I: hits tri 2.  I: misses tri 3 -> done.
    const UniformGrid grid = handGrid();
    const MultipassRun r = run(grid, handRays(), oracle(0.0));
    EXPECT_EQ(r.counts.sequence, (std::vector<K>{K::Setup, K::Intersect, K::Intersect, K::Intersect, K::Traverse,
                                                 K::Traverse, K::Intersect, K::Intersect, K::Write}));
    EXPECT_EQ(r.counts.usefulTraverse, 2u);
    EXPECT_EQ(r.counts.usefulIntersect, 6u);      // 2 + 1 + 1 + 1 + 1
    EXPECT_EQ(r.counts.stencilWrites, 3u + 4u);   // setup writes all; then 4 state changes
    EXPECT_EQ(r.counts.structureReads, 4u + 6u + 4u);  // setup 2 per entered ray; 1 per served intersect; 2 per voxel entered
    EXPECT_EQ(r.counts.triangleReads, 6u);
    ASSERT_EQ(r.hits.size(), 3u);
    EXPECT_EQ(r.hits[0].primitive, 2u);
    EXPECT_EQ(r.hits[0].t, 3.5f);
    EXPECT_EQ(r.hits[0].cellsVisited, 3u);
    EXPECT_EQ(r.hits[0].trianglesTested, 3u);
    EXPECT_EQ(r.hits[0].traversalSteps, 2u);
    EXPECT_EQ(r.hits[1].primitive, gpu::kNoHit);
    EXPECT_EQ(r.hits[1].cellsVisited, 0u);
    EXPECT_EQ(r.hits[2].primitive, 4u);
    EXPECT_EQ(r.hits[2].t, 1.5f);
    EXPECT_EQ(r.hits[2].trianglesTested, 3u);

    const ArchitectureMetrics m = multipassMetrics(r.hits, r.counts, oracle(0.0), gridStructure(grid)->costs());
    EXPECT_EQ(m.passes, 9u);
    EXPECT_EQ(m.passesLowerBound, 2u + 3u);  // max steps / K + max tests / M
    EXPECT_DOUBLE_EQ(m.simdEfficiency, 8.0 / 21.0);  // 8 rays served in 7 loop passes over 3 rays
    EXPECT_DOUBLE_EQ(m.purcellSimdEfficiency, 8.0 / 21.0);
    EXPECT_EQ(m.bytes.stencil, 7u * 3u + 7u);
    EXPECT_EQ(m.bytes.cells, 14u * 4u);
    EXPECT_EQ(m.bytes.triangleList, 6u * 4u);
    EXPECT_EQ(m.bytes.vertices, 6u * 48u);
    EXPECT_EQ(m.bytes.output, 3u * 16u);
    EXPECT_EQ(m.bytes.state, 3u * 80u + 2u * 112u + 6u * 128u + 3u * 16u);
}

TEST_F(MultipassKernels, HandCountedPassesWithThresholdOne) {
    // Threshold 1 intersects only when no ray traverses: ray 2 waits while ray 0 walks to voxel 2.
    const UniformGrid grid = handGrid();
    const MultipassRun r = run(grid, handRays(), oracle(1.0));
    EXPECT_EQ(r.counts.sequence, (std::vector<K>{K::Setup, K::Intersect, K::Traverse, K::Traverse, K::Intersect,
                                                 K::Intersect, K::Write}));
    EXPECT_DOUBLE_EQ(multipassMetrics(r.hits, r.counts, oracle(1.0), gridStructure(grid)->costs()).simdEfficiency, 8.0 / 15.0);
    EXPECT_EQ(recordMismatches(r.hits, run(grid, handRays(), oracle(0.0)).hits), 0u);
}

TEST_F(MultipassKernels, NaiveSchedulingDrainsEachPhase) {
    MultipassOptions naive;
    naive.scheduling = "naive";
    const MultipassRun r = run(handGrid(), handRays(), naive);
    // Intersect until none waits (3 passes: ray 2 needs 3 tests), then traverse until none
    // traverses (2), then intersect (2).
    EXPECT_EQ(r.counts.sequence, (std::vector<K>{K::Setup, K::Intersect, K::Intersect, K::Intersect, K::Traverse,
                                                 K::Traverse, K::Intersect, K::Intersect, K::Write}));
}

TEST_F(MultipassKernels, UnrolledPassesReadTheDiscardedIterationsUnlessSuppressed) {
    const UniformGrid grid = handGrid();
    // K = 4, M = 4: every ray finishes its voxel's list or walk within one pass.
    const MultipassRun plain = run(grid, handRays(), oracle(0.0, 4, 4));
    const MultipassRun suppressed = run(grid, handRays(), oracle(0.0, 4, 4, true));
    EXPECT_EQ(plain.counts.sequence, suppressed.counts.sequence);
    EXPECT_EQ(recordMismatches(plain.hits, suppressed.hits), 0u);
    EXPECT_EQ(suppressed.counts.triangleReads, 6u);  // only the tests
    EXPECT_GT(plain.counts.triangleReads, suppressed.counts.triangleReads);
    EXPECT_EQ(plain.counts.triangleReads % 4, 0u);   // M reads per served ray and pass
    EXPECT_EQ(plain.counts.triangleReads, 4u * plain.counts.usefulIntersect);
}

TEST_F(MultipassKernels, AgreesWithBranchingAndTheCpuSimulatorForEveryUnrollAndThreshold) {
    const UniformGrid grid = hand::sceneBGrid();
    const std::vector<gpu::Ray> rays = hand::sceneBRays();
    const BranchingRun branching = runBranching(*vk_, *gridStructure(grid), rays, {64, 0, 1});
    for (unsigned k : {1u, 2u, 4u, 8u})
        for (unsigned m : {1u, 2u, 4u})
            for (double threshold : {0.0, 0.2, 1.0})
                for (bool suppress : {false, true}) {
                    SCOPED_TRACE("K=" + std::to_string(k) + " M=" + std::to_string(m) + " threshold " +
                                 std::to_string(threshold) + (suppress ? " suppressed" : ""));
                    const MultipassOptions o = oracle(threshold, k, m, suppress);
                    const MultipassRun gpu = run(grid, rays, o);
                    EXPECT_EQ(recordMismatches(gpu.hits, branching.hits), 0u);  // bit for bit, counters too
                    const MultipassResult cpu = simulateMultipass(*gridStructure(grid), rays, o);
                    EXPECT_EQ(recordMismatches(gpu.hits, cpu.hits), 0u);
                    EXPECT_TRUE(gpu.counts == cpu.counts);
                    const ArchitectureMetrics metrics = multipassMetrics(gpu.hits, gpu.counts, o, gridStructure(grid)->costs());
                    EXPECT_GE(metrics.passesTraverse + metrics.passesIntersect, metrics.passesLowerBound);
                }
}

// Rays in batches (strategy.batch_rays): 1,920 rays in batches of 512 are four pass loops (the
// last of 384 rays). Per-ray records and the events of the rays equal one stream's; the passes
// are each batch's, and add up to the four batches simulated one at a time on the CPU; the ray
// slots Purcell's efficiency divides by are each batch's loop passes times its rays.
TEST_F(MultipassKernels, ABatchedRunTracesAsOneStreamWithEachBatchsPasses) {
    const std::vector<gpu::Ray> rays = hand::sceneBRays();
    for (const auto& s : hand::sceneBStructures()) {  // the grid at min_dim 8, the BVH with leaves of up to 4
        SCOPED_TRACE(s->kernelPrefix());
        MultipassOptions o = oracle(0.2, 4, 2);
        const MultipassRun whole = runMultipass(*vk_, *s, rays, o, {64, 0, 1});
        o.batchRays = 512;
        const MultipassRun batched = runMultipass(*vk_, *s, rays, o, {64, 0, 1});
        EXPECT_EQ(whole.batches, 1u);
        EXPECT_EQ(batched.batches, 4u);
        EXPECT_EQ(recordMismatches(batched.hits, whole.hits), 0u);  // counters too
        EXPECT_EQ(batched.traversalStates, whole.traversalStates);
        EXPECT_EQ(batched.counts.usefulTraverse, whole.counts.usefulTraverse);
        EXPECT_EQ(batched.counts.usefulIntersect, whole.counts.usefulIntersect);
        EXPECT_EQ(batched.counts.structureReads, whole.counts.structureReads);
        EXPECT_EQ(batched.counts.triangleReads, whole.counts.triangleReads);
        EXPECT_EQ(batched.counts.stencilWrites, whole.counts.stencilWrites);
        std::array<std::uint64_t, kPassKinds> passes{};
        std::uint64_t slots = 0;
        for (std::size_t first = 0; first < rays.size(); first += 512) {
            const std::vector<gpu::Ray> part(rays.begin() + first, rays.begin() + std::min<std::size_t>(first + 512, rays.size()));
            const MultipassResult one = simulateMultipass(*s, part, o);
            for (int k = 0; k < kPassKinds; ++k) passes[k] += one.counts.passes[k];
            slots += (one.counts.passes[1] + one.counts.passes[2]) * part.size();
        }
        EXPECT_EQ(batched.counts.passes, passes);
        EXPECT_EQ(batched.counts.passes[0], 4u);  // a setup pass per batch
        EXPECT_EQ(batched.counts.streamSlots, slots);
        EXPECT_EQ(whole.counts.streamSlots, (whole.counts.passes[1] + whole.counts.passes[2]) * rays.size());
        EXPECT_TRUE(batched.counts == simulateMultipass(*s, rays, o, gpu::kQueryClosest, 512).counts);
        ASSERT_EQ(batched.counts.sequence.size(), batched.counts.totalPasses());
    }
}

// What one binding holds: the BVH's traversal state is 144 bytes a ray, so 134,217,728 bytes
// (lavapipe's maxStorageBufferRange) hold 932,067 rays, 932,032 in workgroups of 64: 1024 x 1024
// rays run in two batches.
TEST(MultipassBatches, TheLargestPerRayRecordSetsTheBatch) {
    DeviceInfo device;
    device.maxStorageBufferRange = 134217728;
    EXPECT_EQ(multipassBatchRays(device, 144, 0, 64), 932032u);
    EXPECT_EQ(multipassBatchRays(device, 16, 0, 64), 4194304u);  // the 32-byte ray and hit records bind first
    EXPECT_EQ(multipassBatchRays(device, 144, 1000, 64), 1000u);
    // The control on the device: four lists of a 4-byte entry per ray in each partition. Eight
    // partitions make 128 bytes a ray, over the grid's 32-byte state: 1,048,576 rays.
    EXPECT_EQ(multipassListBytes(1, 8), 128u);
    EXPECT_EQ(multipassBatchRays(device, 32, 0, 64, multipassListBytes(1, 8)), 1048576u);
    EXPECT_EQ(multipassBatchRays(device, 32, 0, 64, multipassListBytes(1, 2)), 4194304u);  // 32 bytes: as the state
}

TEST_F(MultipassKernels, CountsAreDeterministic) {
    const UniformGrid grid = handGrid();
    const TriangleMesh scene = christenSceneA();
    GridResolutionRule rule;
    rule.minDim = 6;
    const UniformGrid sceneGrid = buildUniformGrid(scene, rule);
    const std::vector<gpu::Ray> rays = generatePrimaryRays(fitCamera(scene.bounds()), 40, 30);
    const MultipassRun a = run(sceneGrid, rays, oracle(0.2, 2, 2));
    const MultipassRun b = run(sceneGrid, rays, oracle(0.2, 2, 2));
    EXPECT_TRUE(a.counts == b.counts);
    EXPECT_EQ(recordMismatches(a.hits, b.hits), 0u);
}

// With the oracle on the host a repetition's headline time is the live loop, read-backs included
// (Christen 2005 §4.3.4), and the replayed passes' GPU time is the part "replay": the sum of the
// pass kinds' parts, the state-test pass left out. With the oracle on the device the headline is
// the device's loop itself, the oracle's part in it, and there is no replay.
TEST_F(MultipassKernels, HostControlTimesTheLiveLoopAndKeepsTheReplayAsAPart) {
    for (bool device : {false, true}) {
        SCOPED_TRACE(device ? "device control" : "host control");
        MultipassOptions o = oracle(0.2);
        o.deviceControl = device;
        const MultipassRun r = run(handGrid(), handRays(), o);
        const TimedBatch batch = r.timer->time(1, 3);
        ASSERT_EQ(batch.ms.size(), 3u);
        std::map<std::string, std::vector<double>> parts;
        const std::vector<const TimedSeries*>& declared = multipassStrategyType().series;
        for (const auto& [series, ms] : batch.parts) {
            EXPECT_NE(std::find(declared.begin(), declared.end(), series), declared.end()) << series->name;
            parts[series->name] = ms;
        }
        EXPECT_EQ(parts.count("kernel_replay"), device ? 0u : 1u);
        EXPECT_EQ(parts.count("kernel_oracle"), device ? 1u : 0u);
        EXPECT_EQ(parts.count("kernel_stencil_pass"), device ? 0u : 1u);
        for (std::size_t i = 0; i < 3; ++i) {
            double passes = 0.0;
            for (const char* kind : {"kernel_setup", "kernel_traverse", "kernel_intersect", "kernel_write", "kernel_oracle"})
                if (parts.count(kind)) passes += parts[kind].at(i);
            EXPECT_GT(batch.ms[i], 0.0);
            if (device)
                EXPECT_DOUBLE_EQ(batch.ms[i], passes);
            else
                EXPECT_DOUBLE_EQ(parts["kernel_replay"].at(i), passes);
        }
        r.timer->checkHits();  // the live loops' hits are the instrumented run's
    }
}

TEST_F(MultipassKernels, PassCapTurnsARunawayIntoAClearError) {
    MultipassOptions o = oracle(0.0);
    o.maxPasses = 4;  // the hand scene needs 8 before the write pass
    try {
        run(handGrid(), handRays(), o);
        FAIL() << "expected the pass cap to fire";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "multipass: pass cap of 4 reached with 1 rays still active");  // ray 0 still walks
    }
    EXPECT_THROW(simulateMultipass(*gridStructure(handGrid()), handRays(), o), std::exception);
}

TEST_F(MultipassKernels, BranchingLaneCountsEqualTheCpuModel) {
    const UniformGrid grid = handGrid();
    const BranchingRun r = runBranching(*vk_, *gridStructure(grid), handRays(), {64, 0, 1});
    const std::uint64_t s = vk_->info().subgroupSize;
    // One subgroup holds the 3 rays. Voxel loop: {0,2}, {0}, {0}; triangle loops: voxel 0 of ray 0
    // (1 test) with voxel 3 of ray 2 (3 tests): 2, 1, 1 lanes; voxel 1: none; voxel 2: 1, 1.
    EXPECT_EQ(r.activeLanes, 10u);
    EXPECT_EQ(r.laneSlots, 8u * s);
    const LaneCounts cpu = branchingLaneCounts(*gridStructure(grid), handRays(), unsigned(s));
    EXPECT_EQ(cpu.activeLanes, r.activeLanes);
    EXPECT_EQ(cpu.laneSlots, r.laneSlots);
    const ArchitectureMetrics m = branchingMetrics(r.hits, r.activeLanes, r.laneSlots, gridStructure(grid)->costs());
    EXPECT_EQ(m.bytes.state, 3u * 32u);
    EXPECT_EQ(m.bytes.cells, 4u * 8u);
    EXPECT_EQ(m.bytes.triangleList, 6u * 4u);
    EXPECT_EQ(m.bytes.vertices, 6u * 48u);
}

TEST_F(MultipassKernels, BranchingLaneCountsMatchOnARealScene) {
    const TriangleMesh scene = christenSceneB();
    GridResolutionRule rule;
    rule.minDim = 12;
    const UniformGrid grid = buildUniformGrid(scene, rule);
    const std::vector<gpu::Ray> rays = generatePrimaryRays(fitCamera(scene.bounds()), 61, 37);  // a partial subgroup
    const BranchingRun r = runBranching(*vk_, *gridStructure(grid), rays, {64, 0, 1});
    const LaneCounts cpu = branchingLaneCounts(*gridStructure(grid), rays, vk_->info().subgroupSize);
    EXPECT_EQ(cpu.activeLanes, r.activeLanes);
    EXPECT_EQ(cpu.laneSlots, r.laneSlots);
    EXPECT_GT(r.laneSlots, r.activeLanes);
}

}  // namespace
}  // namespace rtbench
