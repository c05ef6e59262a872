// The tie rule between equally near triangles, fixed for every structure and both triangle tests
// (issue 15 §6.1), with the answers derived by hand rather than taken from the CPU reference
// (which shares the kernels' GLSL and so shares their bugs).
//
// The rule, as the shared GLSL states it: a triangle test updates the nearest hit only when
// t < tBest (kernels/ray_math.glsl, both tests: "hit in [tMin, tBest)"), so at equal t the triangle
// TESTED FIRST is kept. Which one is tested first is the structure's order:
//   brute force  - ids in increasing order: the lowest id wins;
//   uniform grid - voxels in the order the ray enters them, each voxel's list in increasing id
//                  (a stable counting sort, structures/uniform_grid/uniform_grid.cpp): the first triangle met
//                  in an earlier voxel wins, even against a lower id met later;
//   BVH          - the nearer child box first, child 0 when both are entered at the same distance
//                  (rtBvhChildren), each leaf's ids increasing (structures/bvh/bvh_build.cpp).
// The exact reference (harness/exact_reference.h) accepts either triangle of a tie; the rule is
// what makes a method's choice the same on every machine, and the golden counts depend on it.
#include <gtest/gtest.h>

#include "harness/exact_reference.h"
#include "tests/device/test_device.h"
#include "tests/methods/hand_scenes.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;

// The valley and its two rays (tests/methods/hand_scenes.h): both rays meet the shared edge at
// (0, 2, 0), t = 1.5, with every value of both tests exact (the hand computation is there).

// A fan of four triangles around the vertex (0, 0, 2) in the plane z = 2, quadrants in order:
// triangle i = (0,0,2), P_i, P_(i+1) with P = (1,0,2), (0,1,2), (-1,0,2), (0,-1,2). The ray up the
// z axis from the origin meets all four at their shared vertex, t = 2: for each, Moller-Trumbore's
// u and v are +-0 (s = (0,0,-2) is orthogonal to p and q) and t = 2 det / det; watertight's sheared
// v0 is (0, 0), so two edge functions are exactly 0 and t = 2 e / e.
TriangleMesh fan() {
    const glm::vec3 c(0, 0, 2), p[4] = {{1, 0, 2}, {0, 1, 2}, {-1, 0, 2}, {0, -1, 2}};
    return meshOf({{c, p[0], p[1]}, {c, p[1], p[2]}, {c, p[2], p[3]}, {c, p[3], p[0]}});
}
std::vector<gpu::Ray> fanRays() { return {ray({0, 0, 0}, {0, 0, 1})}; }

const std::uint32_t kTests[] = {gpu::kTriangleTestMollerTrumbore, gpu::kTriangleTestWatertight};

// The tie is real: each triangle alone is hit at the hand's distance, and the exact reference
// finds all of them at that distance.
void expectEachAloneHitAt(const TriangleMesh& mesh, const gpu::Ray& r, float t, const DeviceInfo& device) {
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (std::uint32_t test : kTests) {
            SCOPED_TRACE("triangle " + std::to_string(i) + " alone, " + testName(test));
            TriangleMesh one = mesh;
            one.triangles = {mesh.triangles[i]};
            const std::unique_ptr<Structure> s = bruteOf(one, device);
            s->setTriangleTest(test);
            const gpu::HitRecord h = s->trace({r})[0];
            EXPECT_EQ(h.primitive, 0u);
            EXPECT_EQ(h.t, t);
        }
    const ExactReference exact(mesh);
    std::vector<std::uint32_t> ties;
    const ExactHit e = exact.trace(r, ties);
    EXPECT_EQ(e.tieCount, mesh.triangles.size());
    EXPECT_EQ(e.t, double(t));
}

using TieRule = VulkanTest;

TEST_F(TieRule, BothValleyTrianglesAreHitAtTheSharedEdgeAtTheSameDistance) {
    for (const gpu::Ray& r : valleyRays()) expectEachAloneHitAt(valley(), r, 1.5f, vk_->info());
}

TEST_F(TieRule, AllFourFanTrianglesAreHitAtTheSharedVertexAtTheSameDistance) {
    expectEachAloneHitAt(fan(), fanRays()[0], 2.0f, vk_->info());
}

// The first triangle tested wins; the expected triangle and counters per structure, by hand:
//   brute force: tests 0 then 1 (2 tests): 0 for both rays.
//   grid 1x1x1: one voxel listing {0, 1}: 0 for both rays (1 voxel, 2 tests, 0 steps: the hit at
//     1.5 lies within the voxel, which the ray leaves at t = 1.5).
//   grid 8x1x1 over [-2,2] x [0,4] x [0,2] (voxels 0.5 wide in x; voxel i spans x in
//     [-2 + i/2, -1.5 + i/2]): lists v0-v2 {1}, v3 {0,1} (R touches x = 0), v4 {0,1}, v5-v7 {0}.
//     Ray 0 (grid frame o = (0.5, 2, 3), 1/d = (1, -, -0.5)) enters at t = 0.5 (the top z = 2) at
//     x = 1, i.e. voxel 2, whose x boundary is at t = 1.0: it tests L (1), a hit at 1.5 beyond the
//     voxel, kept; steps to voxel 3 (boundary t = 1.5 = where it leaves through z = 0), tests 0
//     (1.5, not < 1.5: rejected) and 1 (rejected); 1.5 <= 1.5 ends the walk. So L (1) wins over the
//     lower id: 2 voxels, 3 tests, 1 step. Ray 1 (grid frame o = (3.5, 2, 3)) enters at t = 0.5 at
//     x = 3, on the boundary of voxels 5 and 6: floor(3 / 0.5) = 6 picks voxel 6 although the ray
//     moves to -x, and leaves it at once (its boundary x = 3 lies at t = 0.5): voxel 6 {0}, then
//     5 {0}, then 4 {0,1} (boundary at t = 1.5): R (0) first: 3 voxels, 4 tests, 2 steps. (An entry
//     rule picking the voxel the ray moves into would save the zero-length visit: 2, 3, 1.)
//   BVH leaf 1: a root with the leaves {0} (box x in [0,2]) and {1} (box x in [-2,0]). Ray 0 enters
//     L's box at t = max(-0.5, 0.5) = 0.5 and R's at max(1.5, 0.5) = 1.5 (leaving it at 1.5): L's
//     leaf first, its hit 1.5; R's leaf popped, tested and rejected: 1 node, 2 tests, 3 steps
//     (root, two leaves). Ray 1 mirrors it: R first, 0.
//   BVH leaf 2: a root with one leaf {0, 1}: 0 for both (1 node, 2 tests, 2 steps).
TEST_F(TieRule, ValleyEdgeGoesToTheTriangleTestedFirstInEveryStructureAndTest) {
    struct Case {
        StructureCase structure;
        Expect left, right;
    };
    const Case cases[] = {
        {bruteCase(), {0, 1.5f, -1, 2, -1}, {0, 1.5f, -1, 2, -1}},
        {gridCase({1, 1, 1}), {0, 1.5f, 1, 2, 0}, {0, 1.5f, 1, 2, 0}},
        {gridCase({8, 1, 1}), {1, 1.5f, 2, 3, 1}, {0, 1.5f, 3, 4, 2}},
        {bvhCase(1), {1, 1.5f, 1, 2, 3}, {0, 1.5f, 1, 2, 3}},
        {bvhCase(2), {0, 1.5f, 1, 2, 2}, {0, 1.5f, 1, 2, 2}},
    };
    for (const Case& c : cases)
        for (std::uint32_t test : kTests) {
            SCOPED_TRACE(c.structure.name + ", " + testName(test));
            const std::unique_ptr<Structure> s = c.structure.build(valley(), vk_->info());
            s->setTriangleTest(test);
            const Answers a = answersOf(*vk_, *s, valleyRays());
            expectAnswers(a, 0, c.left);
            expectAnswers(a, 1, c.right);
        }
}

// A BVH over the fan: every box the walk clips is flat at z = 2 and contains the z axis, so the
// ray enters each at exactly t = 2; on such ties rtBvhChildren takes child 0. The winner is
// therefore the first (lowest) id of the leaf reached from the root through child 0 at every level
// (found here from the flattened tree, not by tracing), and every reference is visited: after the
// first hit at t = 2 every box still touches [0, 2].
Expect fanBvhExpectation(const FlatBvh& bvh) {
    std::uint32_t ref = 0;
    while (!(ref & gpu::kBvhLeaf)) ref = bvh.nodes.at(ref).children.x;
    return {bvh.triangleList.at(ref & 0x00FFFFFFu), 2.0f, int(bvh.stats.innerNodes), 4,
            int(bvh.stats.innerNodes + bvh.stats.leaves)};
}

TEST_F(TieRule, FanVertexGoesToTheTriangleTestedFirstInEveryStructureAndTest) {
    const FlatBvh leaf1 = bvhOf(fan(), 1), leaf4 = bvhOf(fan(), 4);
    ASSERT_EQ(leaf1.stats.leaves, 4u);  // four leaves under three inner nodes
    ASSERT_EQ(leaf1.stats.depth, 2u);
    struct Case {
        StructureCase structure;
        Expect expect;
    };
    // brute force: 0 of 4 tests. Grids: the ray enters at (0, 0) in the grid's frame x = y = 1, which
    // floors to voxel (1, 1) of 2x2x1; all four triangles touch that voxel's corner, so it lists
    // {0,1,2,3} and 0 wins (1 voxel, 4 tests). BVHs: the child-0 leaf's first triangle. (With leaf size 4 too
    // Embree's SAH splits the fan: one leaf costs 1 + 4 x 8/8 = 5, two leaves of two half-boxes
    // 1 + 2 x 2 x 4/8 = 3.)
    const Case cases[] = {
        {bruteCase(), {0, 2.0f, -1, 4, -1}},
        {gridCase({1, 1, 1}), {0, 2.0f, 1, 4, 0}},
        {gridCase({2, 2, 1}), {0, 2.0f, 1, 4, 0}},
        {bvhCase(4), fanBvhExpectation(leaf4)},
        {bvhCase(1), fanBvhExpectation(leaf1)},
    };
    for (const Case& c : cases)
        for (std::uint32_t test : kTests) {
            SCOPED_TRACE(c.structure.name + ", " + testName(test));
            const std::unique_ptr<Structure> s = c.structure.build(fan(), vk_->info());
            s->setTriangleTest(test);
            expectAnswers(answersOf(*vk_, *s, fanRays()), 0, c.expect);
        }
}

// The same rule makes the barycentrics those of the winner: at (0, 2, 0), the midpoint of the
// shared edge (0,0,0)-(0,4,0), the winner's u (weight of v1 = (0,4,0)) is 0.5 and v (of v2) is 0,
// whichever triangle wins, in both tests (the hand values above).
TEST_F(TieRule, TheWinnersBarycentricsAreThoseOfTheSharedEdgesMidpoint) {
    for (std::uint32_t test : kTests) {
        SCOPED_TRACE(testName(test));
        const std::unique_ptr<Structure> s = bvhCase(1).build(valley(), vk_->info());
        s->setTriangleTest(test);
        const Answers a = answersOf(*vk_, *s, valleyRays());
        for (const auto* hits : {&a.cpu, &a.branching, &a.multipass})
            for (const gpu::HitRecord& h : *hits) {
                EXPECT_EQ(h.u, 0.5f);
                EXPECT_EQ(h.v, 0.0f);
            }
    }
}

}  // namespace
}  // namespace rtbench
