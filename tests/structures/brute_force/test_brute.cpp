// Brute force: every ray against every triangle, on the device and in its CPU reference bit for
// bit; the nearest hits every structure must reproduce; and the refusal of runs too large for it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "methods/accounting.h"
#include "structures/triangle_store.h"
#include "strategies/branching/branching_strategy.h"
#include "strategies/branching/lane_counts.h"
#include "structures/brute_force/brute_structure.h"
#include "structures/bvh/bvh_structure.h"
#include "strategies/multipass/multipass_simulator.h"
#include "strategies/multipass/multipass_strategy.h"
#include "core/error.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

RunConfig bruteRun(double maxTests) {
    RunConfig run;
    run.values["structure.max_tests"] = maxTests;
    return run;
}

TEST(BruteForce, MoreTestsThanTheLimitAreRefusedNamingTheProduct) {
    DeviceInfo device;
    device.maxStorageBufferRange = 1u << 27;
    try {
        bruteStructureType().build(christenSceneB(), std::vector<gpu::Ray>(10000), bruteRun(1e6), device);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("10000 rays x 2004 triangles = 20040000 ray-triangle tests, over structure.max_tests = 1000000"));
    }
    EXPECT_NO_THROW(bruteStructureType().build(christenSceneB(), std::vector<gpu::Ray>(100), bruteRun(1e6), device));
}

using BruteKernels = VulkanTest;

TEST_F(BruteKernels, BothStrategiesEqualTheCpuReferenceAndTheBvhsNearestHits) {
    const TriangleMesh mesh = christenSceneB();
    DeviceInfo device;
    device.maxStorageBufferRange = 1u << 27;
    const std::unique_ptr<Structure> brute = bruteStructureType().build(mesh, std::vector<gpu::Ray>(3000), bruteRun(1e9), device);
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 3000, 17);
    const BranchingRun branching = runBranching(*vk_, *brute, rays, {64, 0, 1});
    const std::vector<gpu::HitRecord> cpu = brute->trace(rays);
    expectIdentical(branching.hits, cpu);
    const LaneCounts lanes = branchingLaneCounts(*brute, rays, vk_->info().subgroupSize);
    EXPECT_EQ(branching.activeLanes, lanes.activeLanes);
    EXPECT_EQ(branching.laneSlots, lanes.laneSlots);
    for (const gpu::HitRecord& h : branching.hits) ASSERT_EQ(h.trianglesTested, 2004u);

    MultipassOptions o;
    o.intersectionsPerPass = 64;
    const MultipassRun multipass = runMultipass(*vk_, *brute, rays, o, {64, 0, 1});
    const MultipassResult simulated = simulateMultipass(*brute, rays, o);
    expectIdentical(multipass.hits, simulated.hits);
    EXPECT_TRUE(multipass.counts == simulated.counts);
    expectIdentical(multipass.hits, cpu);
    // 1 setup, ceil(2004 / 64) = 32 intersect passes, 1 write; nothing to traverse.
    EXPECT_EQ(multipass.counts.sequence.size(), 34u);

    BvhBuildOptions bvhOptions;
    EXPECT_EQ(differentNearestHits(cpu, bvhStructure(buildBvh(mesh, bvhOptions))->trace(rays)), 0u);
}

// Packed vertices (scene.vertex_bits): each triangle a brute-force ray tests reads its five
// packed words, 20 bytes, where float vertices read three vec4s, 48: bytes_vertices is every
// test times that (1,000 rays x 2,004 triangles), and the packed triangles trace as the floats.
TEST_F(BruteKernels, PackedVerticesCostTwentyBytesATestAndTraceAsTheFloats) {
    const TriangleMesh packed = snapToLattice(christenSceneB(), 10);
    TriangleMesh floats = packed;
    floats.lattice = VertexLattice{};
    DeviceInfo device;
    device.maxStorageBufferRange = 1u << 27;
    const auto packedBrute = bruteStructureType().build(packed, std::vector<gpu::Ray>(1000), bruteRun(1e9), device);
    const auto floatBrute = bruteStructureType().build(floats, std::vector<gpu::Ray>(1000), bruteRun(1e9), device);
    ASSERT_EQ(packedBrute->vertexLattice().bits, 10u);
    EXPECT_EQ(packedBrute->costs().bytesPerTriangle, 20u);
    EXPECT_EQ(floatBrute->costs().bytesPerTriangle, 48u);
    const std::vector<gpu::Ray> rays = randomRays(packed.bounds(), 1000, 23);
    const BranchingRun run = runBranching(*vk_, *packedBrute, rays, {64, 0, 1});
    expectIdentical(run.hits, floatBrute->trace(rays));
    const ArchitectureMetrics m = branchingMetrics(run.hits, run.activeLanes, run.laneSlots, packedBrute->costs());
    EXPECT_EQ(m.bytes.vertices, 1000u * 2004u * 20u);
}

}  // namespace
}  // namespace rtbench
