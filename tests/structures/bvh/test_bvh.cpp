// The BVH: Embree's builder flattened to the GPU layout (complete, bounded, deterministic on any
// machine and Embree ISA), its kernels against its CPU reference bit for bit (hits, counters,
// lanes, passes), and its nearest hits against the grid's, brute force's and Embree's.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <numeric>

#include "harness/embree_config.h"
#include "harness/embree_reference.h"
#include "strategies/branching/branching_strategy.h"
#include "strategies/branching/lane_counts.h"
#include "structures/bvh/bvh_structure.h"
#include "structures/uniform_grid/grid_reference.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "methods/metrics.h"
#include "strategies/multipass/multipass_simulator.h"
#include "strategies/multipass/multipass_strategy.h"
#include "scene/camera.h"
#include "core/error.h"
#include "scene/mesh_io.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/structures/bvh/flat_bvh_checks.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

BvhBuildOptions leafSize(unsigned n, const std::string& quality = "medium") {
    BvhBuildOptions o;
    o.maxLeafSize = n;
    o.quality = quality;
    return o;
}

TEST(BvhBuild, EveryTriangleOnceInsideItsBoxesWithinTheLeafSizeAndTheStack) {
    for (const TriangleMesh& mesh : {christenSceneA(), christenSceneB()})
        for (unsigned leaf : {1u, 4u, 16u})
            for (const char* quality : {"medium", "low"}) {
                SCOPED_TRACE(mesh.name + " leaf " + std::to_string(leaf) + " " + quality);
                const FlatBvh bvh = buildBvh(mesh, leafSize(leaf, quality));
                expectWellFormed(bvh, mesh, leaf);
                EXPECT_GT(bvh.stats.sahCost, 0.0);
            }
}

TEST(BvhBuild, ASceneThatFitsOneLeafGetsARootWithOneChild) {
    TriangleMesh mesh;  // one triangle: Embree's root is a leaf
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    const FlatBvh bvh = buildBvh(mesh, leafSize(4));
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.nodes[0].children.y, gpu::kBvhNone);
    EXPECT_EQ(bvh.stats.leaves, 1u);
    expectWellFormed(bvh, mesh, 4);
    // Rays down the z axis: through the triangle at (0.2, 0.2), beside it at (0.8, 0.8).
    const std::vector<gpu::Ray> rays = {{glm::vec4(0.2f, 0.2f, 1.0f, 0.0f), glm::vec4(0, 0, -1, gpu::kNoHitT)},
                                        {glm::vec4(0.8f, 0.8f, 1.0f, 0.0f), glm::vec4(0, 0, -1, gpu::kNoHitT)}};
    const std::vector<gpu::HitRecord> hits = traceBvhReference(bvh, rays);
    EXPECT_EQ(hits[0].primitive, 0u);
    EXPECT_EQ(hits[0].t, 1.0f);
    EXPECT_EQ(hits[0].cellsVisited, 1u);    // the root
    EXPECT_EQ(hits[0].traversalSteps, 2u);  // the root, then the leaf
    EXPECT_EQ(hits[1].primitive, gpu::kNoHit);
}

// The flattened tree is what the counts depend on, so it must not depend on Embree's thread
// count or on the ISA it runs.
TEST(BvhBuild, TheSameTreeWithOneThreadAndWithEveryEmbreeIsaThisCpuRuns) {
  for (const TriangleMesh& mesh : {christenSceneB(), readMeshFile(resolveCgalMesh("bunny00"))}) {
    SCOPED_TRACE(mesh.name);
    BvhBuildOptions options = leafSize(4);
    const FlatBvh reference = buildBvh(mesh, options);
    std::vector<std::string> configs = {"threads=1"};
    for (const std::string& isa : embreeIsasSupportedHere()) configs.push_back("isa=" + isa);
    for (const std::string& config : configs) {
        SCOPED_TRACE(config);
        options.embreeConfig = config;
        const FlatBvh again = buildBvh(mesh, options);
        ASSERT_EQ(again.nodes.size(), reference.nodes.size());
        EXPECT_EQ(std::memcmp(again.nodes.data(), reference.nodes.data(), reference.nodes.size() * sizeof(gpu::BvhNode)), 0);
        EXPECT_EQ(again.triangleList, reference.triangleList);
    }
  }
}

TEST(BvhBuild, LimitsAreClearErrors) {
    EXPECT_THROW(buildBvh(TriangleMesh{}, leafSize(4)), Error);
    try {
        buildBvh(christenSceneA(), leafSize(200));
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("leaf size 200 outside 1..128"));
    }
}

// The device's binding limit is checked before the build: here a limit smaller than the scene.
TEST(BvhBuild, ABufferOverTheBindingLimitIsRefusedBeforeTheBuild) {
    RunConfig run;
    run.values["structure.leaf_size"] = std::int64_t(4);
    run.values["structure.quality"] = std::string("medium");
    run.values["baseline.embree_config"] = std::string("");
    DeviceInfo device;
    device.name = "a small device";
    device.maxStorageBufferRange = 1000;
    try {
        bvhStructureType().build(christenSceneB(), {}, run, device);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("triangle vertex (2004 triangles)"));
        EXPECT_THAT(e.what(), HasSubstr("96192 bytes"));
        EXPECT_THAT(e.what(), HasSubstr("maxStorageBufferRange of 1000 bytes"));
    }
}

using BvhKernels = VulkanTest;

// lavapipe's real limit: one storage binding holds 128 MiB, so 2.8M triangles' vertices (48 bytes
// each) do not fit; the run is refused before the build, naming the buffer, its size and the limit.
TEST_F(BvhKernels, ASceneOverTheDevicesBindingLimitIsRefusedNamingTheSize) {
    const std::uint64_t limit = vk_->info().maxStorageBufferRange;
    const std::uint64_t triangles = limit / sizeof(gpu::Triangle) + 1;
    TriangleMesh mesh;  // the check needs the count only: every triangle shares three vertices
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles.assign(triangles, glm::uvec3(0, 1, 2));
    RunConfig run;
    run.values["structure.leaf_size"] = std::int64_t(4);
    run.values["structure.quality"] = std::string("medium");
    run.values["baseline.embree_config"] = std::string("");
    try {
        bvhStructureType().build(mesh, {}, run, vk_->info());
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("triangle vertex (" + std::to_string(triangles) + " triangles)"));
        EXPECT_THAT(e.what(), HasSubstr(std::to_string(triangles * sizeof(gpu::Triangle)) + " bytes"));
        EXPECT_THAT(e.what(), HasSubstr("maxStorageBufferRange of " + std::to_string(limit) + " bytes"));
    }
}

TEST_F(BvhKernels, BranchingHitsCountersAndLanesEqualTheCpuReference) {
    for (const TriangleMesh& mesh : {christenSceneA(), christenSceneB()})
        for (unsigned leaf : {1u, 4u, 16u}) {
            SCOPED_TRACE(mesh.name + " leaf " + std::to_string(leaf));
            const std::unique_ptr<Structure> bvh = bvhStructure(buildBvh(mesh, leafSize(leaf)));
            const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 20000, leaf);
            const BranchingRun run = runBranching(*vk_, *bvh, rays, {64, 0, 1});
            expectIdentical(run.hits, bvh->trace(rays));
            const LaneCounts lanes = branchingLaneCounts(*bvh, rays, vk_->info().subgroupSize);
            EXPECT_EQ(run.activeLanes, lanes.activeLanes);
            EXPECT_EQ(run.laneSlots, lanes.laneSlots);
            EXPECT_GT(workStats(run.hits).hits, 1000u);
        }
}

TEST_F(BvhKernels, MultipassEqualsItsSimulatorAndTheBranchingWalk) {
    const TriangleMesh mesh = christenSceneB();
    const std::unique_ptr<Structure> bvh = bvhStructure(buildBvh(mesh, leafSize(4)));
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 3000, 11);
    const std::vector<gpu::HitRecord> branching = bvh->trace(rays);
    struct Unrolling { unsigned k, m; bool suppress; };
    for (const Unrolling u : {Unrolling{1, 1, false}, Unrolling{4, 3, false}, Unrolling{4, 3, true}}) {
                const unsigned k = u.k, m = u.m;
                const bool suppress = u.suppress;
                SCOPED_TRACE("K " + std::to_string(k) + " M " + std::to_string(m) + " suppress " + std::to_string(suppress));
                MultipassOptions o;
                o.traverseStepsPerPass = k;
                o.intersectionsPerPass = m;
                o.suppressFinishedReads = suppress;
                const MultipassRun gpuRun = runMultipass(*vk_, *bvh, rays, o, {64, 0, 1});
                const MultipassResult cpu = simulateMultipass(*bvh, rays, o);
                expectIdentical(gpuRun.hits, cpu.hits);
                EXPECT_TRUE(gpuRun.counts == cpu.counts);
                expectIdentical(gpuRun.hits, branching);  // the two strategies walk the same tree the same way
            }
}

// Three structures, one answer: the nearest hit (an exact tie may pick either triangle), and
// Embree's on nearly every ray.
TEST_F(BvhKernels, NearestHitsEqualTheGridsBruteForcesAndEmbrees) {
    const TriangleMesh mesh = christenSceneB();
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 20000, 5);
    const std::vector<gpu::HitRecord> bvhHits = runBranching(*vk_, *bvhStructure(buildBvh(mesh, leafSize(4))), rays, {64, 0, 1}).hits;
    GridResolutionRule rule;
    rule.minDim = 16;
    const std::vector<gpu::HitRecord> gridHits = traceGridReference(buildUniformGrid(mesh, rule), rays);
    EXPECT_EQ(differentNearestHits(bvhHits, gridHits), 0u);
    std::vector<gpu::HitRecord> embreeHits;
    EmbreeReference embree(mesh, "");
    embree.trace(rays, EmbreeMode::Intersect1, embreeHits);
    EXPECT_GE(compareHits(bvhHits, embreeHits).hitMissAgreement, 0.999);
}

}  // namespace
}  // namespace rtbench
