// The any-hit query (gpu::kQueryAny, shadow rays): every structure's walk ends at the first hit it
// finds, through the one hook rtQueryDone. Checked against numbers derived by hand, against the
// closest-hit query of the same rays (a second formulation: a ray hits something in [tMin, tMax)
// exactly when its nearest hit there exists), and device against CPU model, bit for bit.
#include <gtest/gtest.h>

#include <cmath>

#include "strategies/branching/lane_counts.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/methods/hand_scenes.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;

// Every way one structure answers the query: CPU reference, branching and multipass on the device,
// the multipass simulator.
Answers anyHitAnswers(VulkanContext& vk, const Structure& s, const std::vector<gpu::Ray>& rays) {
    Answers a;
    a.cpu = s.trace(rays, gpu::kQueryAny);
    a.branching = runBranching(vk, s, rays, {64, 0, 1}, gpu::kQueryAny).hits;
    const MultipassOptions o;
    a.multipass = runMultipass(vk, s, rays, o, {64, 0, 1}, gpu::kQueryAny).hits;
    a.simulated = simulateMultipass(s, rays, o, gpu::kQueryAny).hits;
    return a;
}

// Three squares' lower-left triangles stacked along z, listed out of depth order:
//   triangle 0 at z = 3, triangle 1 at z = 1, triangle 2 at z = 2, each (0,0) (4,0) (0,4) in x, y.
// The ray o = (1, 1, 0), d = (0, 0, 1) crosses all three at t = 3, 1 and 2.
TriangleMesh stack() {
    auto at = [](float z) { return Tri{glm::vec3(0, 0, z), glm::vec3(4, 0, z), glm::vec3(0, 4, z)}; };
    return meshOf({at(3), at(1), at(2)});
}

using AnyHit = VulkanTest;

// Brute force and a 1x1x1 grid test the triangles in index order (the grid's one voxel lists all
// three, in order). Closest hit: all three tested, triangle 1 at t = 1. Any hit: triangle 0 is
// hit first, at t = 3, and ends the walk after one test. With tMax = 2.5 triangle 0 lies beyond
// the ray: triangle 1 is found by the second test; with tMax = 0.5 nothing is hit: brute force
// tests all three, the grid none (the ray ends before the box, which begins at z = 1).
TEST_F(AnyHit, TheFirstTriangleHitInListOrderEndsTheWalk) {
    const TriangleMesh mesh = stack();
    const std::vector<gpu::Ray> rays = {ray({1, 1, 0}, {0, 0, 1}), ray({1, 1, 0}, {0, 0, 1}, 0.0f, 2.5f),
                                        ray({1, 1, 0}, {0, 0, 1}, 0.0f, 0.5f)};
    for (const StructureCase& c : {bruteCase(), gridCase({1, 1, 1})}) {
        SCOPED_TRACE(c.name);
        const int shortRayTests = c.name == "brute_force" ? 3 : 0;
        const std::unique_ptr<Structure> s = c.build(mesh, vk_->info());
        const Answers closest = answersOf(*vk_, *s, rays);
        expectAnswers(closest, 0, {1, 1.0f, -1, 3});
        expectAnswers(closest, 1, {1, 1.0f, -1, 3});
        expectAnswers(closest, 2, {kNoHit, 0.0f, -1, shortRayTests});
        const Answers any = anyHitAnswers(*vk_, *s, rays);
        expectAnswers(any, 0, {0, 3.0f, -1, 1});
        expectAnswers(any, 1, {1, 1.0f, -1, 2});
        expectAnswers(any, 2, {kNoHit, 0.0f, -1, shortRayTests});
    }
}

// A 1x1x3 grid splits z in [1, 3] at 5/3 and 7/3: triangle 1 alone in the first voxel, 2 in the
// second, 0 in the third. Coming down from z = 4 (o = (1, 1, 4), d = (0, 0, -1)) the ray enters
// the third voxel first: any hit ends there with triangle 0 at t = 1 after one voxel and one test;
// the closest hit is the same (its exit lies beyond t = 1). Going up with tMax = 1.5 from z = 0.25
// it enters the first voxel, finds triangle 1 at t = 0.75 and ends there either way.
TEST_F(AnyHit, AGridEndsInTheVoxelOfTheFirstHit) {
    const std::unique_ptr<Structure> s = gridCase({1, 1, 3}).build(stack(), vk_->info());
    const std::vector<gpu::Ray> rays = {ray({1, 1, 4}, {0, 0, -1}), ray({1, 1, 0.25f}, {0, 0, 1}, 0.0f, 1.5f)};
    const Answers any = anyHitAnswers(*vk_, *s, rays);
    expectAnswers(any, 0, {0, 1.0f, 1, 1, 0});
    expectAnswers(any, 1, {1, 0.75f, 1, 1, 0});
}

// The record of an any-hit ray: a triangle the ray really meets in [tMin, tMax) (checked here in
// double, apart from the kernels' arithmetic), at the distance the triangle test gave.
void expectRealHit(const TriangleMesh& mesh, const gpu::Ray& r, const gpu::HitRecord& h, std::size_t i) {
    const glm::uvec3 t = mesh.triangles.at(h.primitive);
    const glm::dvec3 o(r.originTMin), d(r.directionTMax), v0(mesh.vertices[t.x]), v1(mesh.vertices[t.y]),
        v2(mesh.vertices[t.z]);
    const glm::dvec3 e1 = v1 - v0, e2 = v2 - v0, p = glm::cross(d, e2), s = o - v0, q = glm::cross(s, e1);
    const double det = glm::dot(e1, p), u = glm::dot(s, p) / det, v = glm::dot(d, q) / det, tHit = glm::dot(e2, q) / det;
    const double slack = 1e-4;
    EXPECT_TRUE(u >= -slack && v >= -slack && u + v <= 1 + slack) << "ray " << i << " u " << u << " v " << v;
    EXPECT_NEAR(tHit, h.t, 1e-4 * std::max(1.0, std::abs(tHit))) << "ray " << i;
    EXPECT_LT(h.t, r.directionTMax.w) << "ray " << i;
    EXPECT_GE(h.t, r.originTMin.w) << "ray " << i;
}

// On a scene of 2004 triangles, every structure and strategy: the any-hit query hits exactly the
// rays whose nearest hit lies in [tMin, tMax), with a triangle they meet there, after no more
// tests than the nearest hit took; the device's records, lane counts and pass counts equal the
// CPU model's.
TEST_F(AnyHit, HitsExactlyWhereTheClosestHitQueryHitsOnEveryStructure) {
    const TriangleMesh mesh = christenSceneB();
    std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 2000, 23);
    const float reach = glm::length(mesh.bounds().extent());
    for (std::size_t i = 0; i < rays.size(); ++i) rays[i].directionTMax.w = reach * float(i % 5) / 4.0f / glm::length(glm::vec3(rays[i].directionTMax));
    std::uint64_t shortened = 0;
    for (const StructureCase& c : {bruteCase(), gridCase({9, 9, 9}), bvhCase(4), bvhCase(1)}) {
        SCOPED_TRACE(c.name);
        const std::unique_ptr<Structure> s = c.build(mesh, vk_->info());
        const std::vector<gpu::HitRecord> closest = s->trace(rays);
        const Answers any = anyHitAnswers(*vk_, *s, rays);
        expectIdentical(any.branching, any.cpu);
        expectIdentical(any.multipass, any.cpu);
        expectIdentical(any.simulated, any.cpu);
        std::uint64_t hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const bool hit = any.cpu[i].primitive != kNoHit;
            ASSERT_EQ(hit, closest[i].primitive != kNoHit) << "ray " << i;
            EXPECT_LE(any.cpu[i].trianglesTested, closest[i].trianglesTested) << "ray " << i;
            shortened += any.cpu[i].trianglesTested < closest[i].trianglesTested;
            if (hit) ++hits, expectRealHit(mesh, rays[i], any.cpu[i], i);
        }
        EXPECT_GT(hits, 200u);  // the test means something: many rays hit within their reach
        const BranchingRun device = runBranching(*vk_, *s, rays, {64, 0, 1}, gpu::kQueryAny);
        const LaneCounts lanes = branchingLaneCounts(*s, rays, vk_->info().subgroupSize, 0, gpu::kQueryAny);
        EXPECT_EQ(device.activeLanes, lanes.activeLanes);
        EXPECT_EQ(device.laneSlots, lanes.laneSlots);
        const MultipassOptions o;
        EXPECT_TRUE(runMultipass(*vk_, *s, rays, o, {64, 0, 1}, gpu::kQueryAny).counts ==
                    simulateMultipass(*s, rays, o, gpu::kQueryAny).counts);
    }
    EXPECT_GT(shortened, 100u);  // and the early end happens
}

}  // namespace
}  // namespace rtbench
