// The branching kernel on Vulkan against the CPU reference traversal (same rays, same source):
// hits and per-ray counters must be identical, and the validation layer must stay silent.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "strategies/branching/branching_strategy.h"
#include "strategies/persistent/persistent_layout.h"
#include "harness/embree_reference.h"
#include "methods/metrics.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "strategies/stream_batches.h"
#include "scene/camera.h"
#include "structures/uniform_grid/grid_reference.h"
#include "structures/uniform_grid/grid_structure.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {

using BranchingKernel = VulkanTest;

TEST_F(BranchingKernel, RunsOnLavapipeUnlessAnotherDeviceIsNamed) {
    if (testDeviceName() == "llvmpipe") {
        EXPECT_NE(vk_->info().name.find("llvmpipe"), std::string::npos);
    }
    EXPECT_GT(vk_->info().subgroupSize, 0u);
}

TEST_F(BranchingKernel, PerRayHitsAndCountersEqualTheCpuReferenceOnRandomRays) {
    for (const TriangleMesh& mesh : {christenSceneA(), christenSceneB()}) {
        for (unsigned minDim : {1u, 4u, 13u, 32u}) {
            SCOPED_TRACE(mesh.name + " min_dim " + std::to_string(minDim));
            GridResolutionRule rule;
            rule.minDim = minDim;
            const UniformGrid grid = buildUniformGrid(mesh, rule);
            const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 20000, minDim);
            const BranchingRun run = runBranching(*vk_, *gridStructure(grid), rays, {64, 0, 1});
            const std::vector<gpu::HitRecord> cpu = traceGridReference(grid, rays);
            expectIdentical(run.hits, cpu);
            const WorkStats w = workStats(cpu);
            EXPECT_GT(w.hits, 1000u);  // the rays do hit things
            EXPECT_GT(w.cellsTotal, 0u);
        }
    }
}

// More workgroups than maxComputeWorkGroupCount[0] (lavapipe: 65,535): the dispatch is a grid of
// two rows (device/vulkan_context.h workgroupGrid), and every ray, the last ones of row 2 too,
// gets its own record.
TEST_F(BranchingKernel, ADispatchOfMoreGroupsThanOneRowHoldsTracesEveryRay) {
    const std::uint32_t workgroup = vk_->info().subgroupSize;
    const std::uint64_t groups = vk_->info().maxWorkGroupCountX + 2;
    if (groups * workgroup > 8'000'000) GTEST_SKIP() << "maxComputeWorkGroupCount[0] " << vk_->info().maxWorkGroupCountX;
    const TriangleMesh mesh = christenSceneA();
    GridResolutionRule rule;
    rule.minDim = 8;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), groups * workgroup - 3, 8);
    const BranchingRun run = runBranching(*vk_, *gridStructure(grid), rays, {workgroup, 0, 0});
    expectIdentical(run.hits, traceGridReference(grid, rays));
}

TEST_F(BranchingKernel, PrimaryRaysOnSceneBAgreeWithEmbree) {
    const TriangleMesh mesh = christenSceneB();
    GridResolutionRule rule;
    rule.minDim = 16;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    // Scene B's own viewpoint: inside the room, looking at its far wall.
    const std::vector<gpu::Ray> rays = generatePrimaryRays(*proceduralCamera("christen_b", 70.0f), 160, 120);
    const BranchingRun run = runBranching(*vk_, *gridStructure(grid), rays, {32, 1, 2});
    EXPECT_EQ(run.gpuMs.size(), 2u);
    EmbreeReference embree(mesh, "");
    std::vector<gpu::HitRecord> reference;
    embree.trace(rays, EmbreeMode::Intersect1, reference);
    const Agreement a = compareHits(run.hits, reference);
    EXPECT_GE(a.hitMissAgreement, 0.999);
    EXPECT_EQ(workStats(run.hits).hits, rays.size());  // inside a closed room every ray hits
    EXPECT_LT(a.relDistanceErrorMean, 1e-5);
    std::vector<gpu::HitRecord> packets;
    embree.trace(rays, EmbreeMode::Intersect16, packets);
    EXPECT_EQ(compareHits(packets, reference).hitMissMismatches, 0u);
}

TEST_F(BranchingKernel, DegenerateTrianglesAreNeverHit) {
    TriangleMesh mesh = christenSceneA();
    const unsigned base = unsigned(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {{-4, 0.5f, 3}, {4, 0.5f, 3}, {0, 0.5f, 3}, {0, 1, 3}});
    mesh.triangles.emplace_back(base, base + 1, base + 2);  // collinear, across the view
    mesh.triangles.emplace_back(base + 3, base + 3, base + 3);  // a point
    ASSERT_EQ(mesh.degenerateCount(), 2u);
    GridResolutionRule rule;
    rule.minDim = 8;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const std::vector<gpu::Ray> rays = generatePrimaryRays(fitCamera(mesh.bounds()), 96, 64);
    const BranchingRun run = runBranching(*vk_, *gridStructure(grid), rays, {64, 0, 1});
    expectIdentical(run.hits, traceGridReference(grid, rays));
    std::size_t hits = 0;
    for (const gpu::HitRecord& h : run.hits) {
        if (h.primitive == gpu::kNoHit) continue;
        EXPECT_LT(h.primitive, 36u);  // one of the boxes' triangles, never a degenerate one
        ++hits;
    }
    EXPECT_GT(hits, 100u);
}

// A stream in batches of whole workgroups (what runs when one binding cannot hold the ray or hit
// records): 1,001 rays in batches of 256 are four dispatches (the last of 233 rays). Records and
// every counter equal one dispatch's, for branching and the megakernel, whose subgroups are the
// same; persistent threads run a fetch loop per batch, so the fetch counter ends at the batches'
// ends summed (by hand below), the records and lanes again as of one.
TEST_F(BranchingKernel, AStreamInBatchesTracesAsOneDispatch) {
    const TriangleMesh mesh = christenSceneB();
    GridResolutionRule rule;
    rule.minDim = 16;
    const auto s = gridStructure(buildUniformGrid(mesh, rule));
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 1001, 16);
    for (const char* kernel : {"branching", "megakernel"}) {
        SCOPED_TRACE(kernel);
        TraceLaunch launch;
        launch.kernel = kernel;
        const BranchingRun whole = runBranching(*vk_, *s, rays, {64, 0, 0}, gpu::kQueryClosest, launch);
        launch.batchRays = 256;
        const BranchingRun batched = runBranching(*vk_, *s, rays, {64, 0, 2}, gpu::kQueryClosest, launch);
        EXPECT_EQ(whole.batches, 1u);
        EXPECT_EQ(batched.batches, 4u);
        EXPECT_EQ(batched.gpuMs.size(), 2u);  // each repetition every batch's, the hits checked
        EXPECT_EQ(recordMismatches(batched.hits, whole.hits), 0u);  // counters too
        for (std::uint32_t c = 0; c < gpu::kCountSlots; ++c) EXPECT_EQ(batched.counters.counts[c], whole.counters.counts[c]) << c;
        EXPECT_GT(batched.laneSlots, 0u);
    }
    // Persistent threads, 2 workgroups of 64 fetching 8 rays a time (subgroup size 8 on llvmpipe):
    // batches of 256, 256, 256 and 233 rays hand out 256 + 128 (16 subgroups' last fetch) each, the
    // last 240 + 128: 3 x 384 + 368 = 1,520.
    if (vk_->info().subgroupSize != 8) GTEST_SKIP() << "the hand count assumes subgroups of 8";
    TraceLaunch launch;
    launch.kernel = "persistent";
    launch.invocations = 2 * 64;
    launch.constants = {{gpu::kSpecRaysPerFetch, 8}};
    launch.countersWhenTimed = true;
    launch.batchRays = 256;
    const BranchingRun persistent = runBranching(*vk_, *s, rays, {64, 0, 0}, gpu::kQueryClosest, launch);
    launch = TraceLaunch{};
    const BranchingRun branching = runBranching(*vk_, *s, rays, {64, 0, 0}, gpu::kQueryClosest, launch);
    EXPECT_EQ(recordMismatches(persistent.hits, branching.hits), 0u);
    EXPECT_EQ(persistent.counters.counts[gpu::kCountRaysTraced], 1001u);
    EXPECT_EQ(persistent.counters.counts[gpu::kCountRaysFetched], 1520u);
}

// The batch arithmetic by hand: lavapipe's 134,217,728-byte binding holds 4,194,304 rays of 32
// bytes (ray and hit record), so 4096 x 4096 rays are 4 dispatches; a record that fits fewer
// than a workgroup still gets one workgroup; a stream's batches cover it once, the last shorter.
TEST(StreamBatches, TheBindingSetsTheBatchAndTheBatchesCoverTheStream) {
    DeviceInfo device;
    device.maxStorageBufferRange = 134217728;
    EXPECT_EQ(wholeTraversalBatchRays(device, 64), 4194304u);
    EXPECT_EQ(streamBatches(4096u * 4096u, 4194304u).size(), 4u);
    EXPECT_EQ(raysPerBinding(device, 144, 64), 932032u);  // the BVH multipass state (multipassBatchRays)
    EXPECT_EQ(raysPerBinding(device, 1u << 30, 64), 64u);
    const auto b = streamBatches(1001, 256);
    ASSERT_EQ(b.size(), 4u);
    EXPECT_EQ(b[0], (std::pair<std::uint64_t, std::uint64_t>{0, 256}));
    EXPECT_EQ(b[3], (std::pair<std::uint64_t, std::uint64_t>{768, 1001}));
    EXPECT_TRUE(streamBatches(0, 256).empty());
}

TEST_F(BranchingKernel, BufferOverTheBindingLimitIsAClearError) {
    try {
        vk_->createStorageBuffer(vk_->info().maxStorageBufferRange + 4, "test");
        FAIL();
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("over " + vk_->info().name + "'s maxStorageBufferRange of " +
                                             std::to_string(vk_->info().maxStorageBufferRange) + " bytes"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace rtbench

namespace rtbench {
namespace {

// The lane model is the judge only where subgroups run in lock step (llvmpipe); on another
// device a difference is a warning naming both counts, and the run stands.
TEST(LaneVerdict, ADifferenceFailsOnALockStepDeviceAndWarnsElsewhere) {
    DeviceInfo lavapipe;
    lavapipe.name = "llvmpipe (LLVM 15.0.6, 256 bits)";
    lavapipe.lockStepSubgroups = true;
    DeviceInfo nvidia;
    nvidia.name = "NVIDIA H200";
    for (const DeviceInfo* d : {&lavapipe, &nvidia}) {
        const LaneVerdict same = judgeLaneCounts(*d, 700, 800, 700, 800);
        EXPECT_EQ(same.mismatch, "");
        EXPECT_EQ(same.warning, "");
    }
    const LaneVerdict wrong = judgeLaneCounts(lavapipe, 690, 800, 700, 800);
    EXPECT_EQ(wrong.mismatch, "subgroup lane counts differ (690/800 on the device, 700/800 in the CPU model)");
    EXPECT_EQ(wrong.warning, "");
    const LaneVerdict apart = judgeLaneCounts(nvidia, 700, 832, 700, 800);
    EXPECT_EQ(apart.mismatch, "");
    EXPECT_NE(apart.warning.find("(700/832 on the device, 700/800 in the CPU model): NVIDIA H200 need not run"), std::string::npos)
        << apart.warning;
}

// lavapipe says it runs subgroups in lock step (the suite's device), so its lane counts are judged.
TEST(LaneVerdict, TheTestDeviceIsLockStep) {
    const std::vector<DeviceInfo> devices = VulkanContext::listDevices();
    ASSERT_FALSE(devices.empty());
    for (const DeviceInfo& d : devices) {
        if (d.driver.find("llvmpipe") != std::string::npos) {
            EXPECT_TRUE(d.lockStepSubgroups) << d.name;
        }
    }
}

}  // namespace
}  // namespace rtbench
