// The uniform grid's walk counted by hand (issue 15 §6.5): the voxels a ray visits (3D-DDA,
// Amanatides & Woo 1987, in the order and with the tie rule of structures/uniform_grid/grid_traversal.glsl),
// the triangles it tests, its steps, the DDA's boundary distances, and the bytes read, on a 2x2x1
// grid small enough to follow on paper. The kernels and the CPU reference share the GLSL, so both
// are held to these numbers.
#include <gtest/gtest.h>

#include <cmath>

#include "methods/accounting.h"
#include "structures/uniform_grid/grid_reference.h"
#include "tests/device/test_device.h"
#include "tests/methods/hand_scenes.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;

// The grid box [0,2] x [0,2] x [0,1] (set by triangles 0 and 1), 2x2x1 unit voxels (x, y).
// Each triangle lies strictly inside one voxel, so each voxel's list is known:
//   0: a corner at z = 0 in (0,0)                     voxel (0,0): {0}
//   1: a corner at z = 1 in (1,1)                     voxel (1,0): {2}
//   2: z = 0.25 in (1,0)                              voxel (0,1): {3, 5}
//   3, 5: z = 0.25 and z = 0.75 in (0,1)              voxel (1,1): {1, 4}
//   4: in the plane x + y = 3, in (1,1): (1.25,1.75,0.25) (1.75,1.25,0.25) (1.5,1.5,0.75)
// Every triangle but 4 is parallel to the rays below (constant z; the rays keep z constant), so
// only 4 is ever hit, at the point (1.5, 1.5, 0.5).
TriangleMesh cornerScene() {
    return meshOf({
        {glm::vec3(0, 0, 0), glm::vec3(0.25f, 0, 0), glm::vec3(0, 0.25f, 0)},
        {glm::vec3(2, 2, 1), glm::vec3(1.75f, 2, 1), glm::vec3(2, 1.75f, 1)},
        {glm::vec3(1.25f, 0.25f, 0.25f), glm::vec3(1.75f, 0.25f, 0.25f), glm::vec3(1.5f, 0.75f, 0.25f)},
        {glm::vec3(0.25f, 1.25f, 0.25f), glm::vec3(0.75f, 1.25f, 0.25f), glm::vec3(0.5f, 1.75f, 0.25f)},
        {glm::vec3(1.25f, 1.75f, 0.25f), glm::vec3(1.75f, 1.25f, 0.25f), glm::vec3(1.5f, 1.5f, 0.75f)},
        {glm::vec3(0.25f, 1.25f, 0.75f), glm::vec3(0.75f, 1.25f, 0.75f), glm::vec3(0.5f, 1.75f, 0.75f)},
    });
}

UniformGrid cornerGrid() { return gridOf(cornerScene(), {2, 2, 1}); }

// The rays, with their walks (the grid's frame is the world's: its min corner is the origin):
//   A  o = (-1,-1,0.5), d = (1,1,0): enters at t = 1 at (0,0): voxel (0,0), boundaries at
//      t = 2 on x and on y, a tie: the lowest axis, x, first -> (1,0) (x boundary now 3) ->
//      y at 2 -> (1,1); triangle 4 hit at t = 2.5 (Moller-Trumbore: det 0.5, u 0.25, v 0.5), within
//      (1,1), which the ray leaves at 3. Voxels 3, tests 1 + 1 + 2 = 4, steps 2. Stepping y first
//      would visit (0,1) instead: 5 tests.
//   B  o = (-1,0.5,0.5), d = (1,0,0), tMax = 2: enters (0,0) at 1; its x boundary at 2 is not
//      below tMax = 2, so the walk ends there: voxels 1, tests 1, steps 1, no hit.
//   C  the same without tMax: (0,0) then (1,0) (boundary 3 = where it leaves the box): voxels 2,
//      tests 2, steps 2, no hit.
//   D  o = (0.5,3,0.9), d = (0,-1,0): enters (0,1) at t = 1 from the top, steps down at 2 into
//      (0,0), leaves at 3: voxels 2, tests 2 + 1 = 3, steps 2, no hit.
//   E  o = (-1,0.25,0.5), d = (2,1,0): 1/d = (0.5, 1); enters at t = max(0.5, -0.25) = 0.5 at
//      (0, 0.75): voxel (0,0) with boundaries x at (1 + 1) 0.5 = 1 and y at 0.75; steps y (0.75)
//      -> (0,1), y boundary 0.75 + 1 = 1.75; x (1) -> (1,1), x boundary 1 + 0.5 = 1.5 (= where the
//      ray leaves the box at x = 2); triangle 4 (x + y = 3 at -1 + 2t + 0.25 + t = 3) at
//      t = 1.25: voxels 3, tests 1 + 2 + 2 = 5, steps 2.
//   F  ray A with tMax = 2.5: hits count in [tMin, tMax), so triangle 4 at exactly 2.5 is not one;
//      the walk ends in (1,1) (its boundaries at 3 lie past tMax): voxels 3, tests 4, steps 3
//      (the last step attempt fails), no hit.
std::vector<gpu::Ray> cornerRays() {
    return {ray({-1, -1, 0.5f}, {1, 1, 0}), ray({-1, 0.5f, 0.5f}, {1, 0, 0}, 0.0f, 2.0f),
            ray({-1, 0.5f, 0.5f}, {1, 0, 0}), ray({0.5f, 3, 0.9f}, {0, -1, 0}),
            ray({-1, 0.25f, 0.5f}, {2, 1, 0}), ray({-1, -1, 0.5f}, {1, 1, 0}, 0.0f, 2.5f)};
}

const Expect kCornerAnswers[] = {
    {4, 2.5f, 3, 4, 2}, {kNoHit, 0.0f, 1, 1, 1}, {kNoHit, 0.0f, 2, 2, 2}, {kNoHit, 0.0f, 2, 3, 2}, {4, 1.25f, 3, 5, 2},
    {kNoHit, 0.0f, 3, 4, 3},
};

TEST(GridHandCounts, TheCornerGridListsEachTriangleInItsVoxel) {
    const UniformGrid g = cornerGrid();
    // Voxel index x + 2 y: (0,0) {0}, (1,0) {2}, (0,1) {3,5}, (1,1) {1,4}.
    EXPECT_EQ(g.cellOffsets, (std::vector<std::uint32_t>{0, 1, 2, 4, 6}));
    EXPECT_EQ(g.triangleList, (std::vector<std::uint32_t>{0, 2, 3, 5, 1, 4}));
    EXPECT_EQ(glm::vec3(g.params.cellSize), glm::vec3(1, 1, 1));
}

// Membership at a boundary (CGAL's exact triangle-box test over each triangle's candidate cells,
// which are widened by a cell within 1e-4 cells of a boundary): grid 2x1x1 over [0,2] x [0,1] x
// [0,1], voxels [0,1] and [1,2] in x. Triangle 0 spans both; triangle 1 starts 2^-20 above x = 1
// (a candidate for voxel 0 too, but outside its closed box), triangle 2 ends 2^-20 below it. By
// hand: voxel 0 lists {0, 2}, voxel 1 lists {0, 1}.
TEST(GridHandCounts, TrianglesWithinRoundingOfABoundaryAreListedOnlyWhereTheyLie) {
    const float e = std::ldexp(1.0f, -20);
    const UniformGrid g = gridOf(meshOf({{glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 1, 1)},
                                         {glm::vec3(1 + e, 0.25f, 0.25f), glm::vec3(1.5f, 0.25f, 0.25f),
                                          glm::vec3(1.25f, 0.75f, 0.5f)},
                                         {glm::vec3(0.5f, 0.25f, 0.25f), glm::vec3(1 - e, 0.25f, 0.25f),
                                          glm::vec3(0.75f, 0.75f, 0.5f)}}),
                                 {2, 1, 1});
    EXPECT_EQ(g.cellOffsets, (std::vector<std::uint32_t>{0, 2, 4}));
    EXPECT_EQ(g.triangleList, (std::vector<std::uint32_t>{0, 2, 0, 1}));
}

TEST(GridHandCounts, TheWalksVoxelsInOrder) {
    const UniformGrid g = cornerGrid();
    const std::vector<gpu::Ray> rays = cornerRays();
    using V = std::vector<glm::ivec3>;
    EXPECT_EQ(ddaVoxels(g, rays[0]), (V{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}));
    EXPECT_EQ(ddaVoxels(g, rays[1]), (V{{0, 0, 0}}));
    EXPECT_EQ(ddaVoxels(g, rays[2]), (V{{0, 0, 0}, {1, 0, 0}}));
    EXPECT_EQ(ddaVoxels(g, rays[3]), (V{{0, 1, 0}, {0, 0, 0}}));
    EXPECT_EQ(ddaVoxels(g, rays[4]), (V{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
    EXPECT_EQ(ddaVoxels(g, rays[5]), (V{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}));
}

// The DDA's state itself (what multipass saves between passes): the boundary distance per axis
// after entering and after each step, for rays A and E (hand values above; z never moves: its
// boundary distance is kNoHitT).
TEST(GridHandCounts, TheBoundaryDistancesAfterEachStep) {
    gridref::GridKernels k = gridKernels(cornerGrid());
    const std::vector<gpu::Ray> rays = cornerRays();
    struct Walk {
        gpu::Ray ray;
        std::vector<glm::vec2> tMax;  // x, y after entering, then after each step
        float tLeave;
        glm::vec2 tDelta;
    };
    for (const Walk& w : {Walk{rays[0], {{2, 2}, {3, 2}, {3, 3}}, 3.0f, {1, 1}},
                          Walk{rays[4], {{1, 0.75f}, {1, 1.75f}, {1.5f, 1.75f}}, 1.5f, {0.5f, 1}}}) {
        gridref::GridKernels::RtDda s;
        ASSERT_TRUE(k.rtEnterGrid(w.ray, s));
        EXPECT_EQ(s.tLeave, w.tLeave);
        EXPECT_EQ(glm::vec2(s.tDelta), w.tDelta);
        EXPECT_EQ(s.tMaxAxis.z, gpu::kNoHitT);
        for (std::size_t i = 0; i < w.tMax.size(); ++i) {
            EXPECT_EQ(glm::vec2(s.tMaxAxis), w.tMax[i]) << "after step " << i;
            EXPECT_EQ(k.rtDdaStep(s), i + 1 < w.tMax.size()) << "step " << i + 1;
        }
    }
}

using GridHandKernels = VulkanTest;

TEST_F(GridHandKernels, VoxelsTestsAndStepsOfEachRayByHandInBothTests) {
    for (std::uint32_t test : {gpu::kTriangleTestMollerTrumbore, gpu::kTriangleTestWatertight}) {
        SCOPED_TRACE(testName(test));
        const std::unique_ptr<Structure> s = gridStructure(cornerGrid());
        s->setTriangleTest(test);
        const std::vector<gpu::Ray> rays = cornerRays();
        const Answers a = answersOf(*vk_, *s, rays);
        for (std::size_t i = 0; i < rays.size(); ++i) expectAnswers(a, i, kCornerAnswers[i]);
        // Branching bytes: 3 + 1 + 2 + 2 + 3 + 3 = 14 voxels entered x 2 offsets of 4 bytes;
        // 4 + 1 + 2 + 3 + 5 + 4 = 19 tests x (4 + 48).
        const BranchingRun run = runBranching(*vk_, *s, rays, {64, 0, 1});
        const ArchitectureMetrics m = branchingMetrics(run.hits, run.activeLanes, run.laneSlots, s->costs());
        EXPECT_EQ(m.bytes.cells, 14u * 8u);
        EXPECT_EQ(m.bytes.triangleList, 19u * 4u);
        EXPECT_EQ(m.bytes.vertices, 19u * 48u);
        EXPECT_EQ(m.work.stepsPerRayMax, 3u);
    }
}

// A hit on the exit face of the voxel being walked ends the walk there (grid_traversal.glsl's and
// grid_multipass.glsl's hit.t <= the voxel's exit). Grid [0,2] x [0,1] x [0,1] of 2x1x1 unit voxels
// (bounds set by 0, a corner at z = 0 in voxel 0, and 1, a corner at z = 1 in voxel 1); triangle 2
// lies in the face x = 1 and so in both voxels: lists {0, 2} and {1, 2}. The ray
// o = (-1, 0.375, 0.375), d = (1, 0, 0) enters voxel 0 at t = 1, misses 0 (parallel), hits 2 at
// t = 2 (Moller-Trumbore: det -0.25, u = v = 0.25, all exact), where it leaves voxel 0: voxels 1,
// tests 2, steps 0. A walk that went on would enter voxel 1 and test 1 and 2 again: voxels 2, tests 4.
TEST_F(GridHandKernels, AHitOnTheVoxelsExitFaceEndsTheWalkInEveryStrategy) {
    const TriangleMesh scene = meshOf({
        {glm::vec3(0, 0, 0), glm::vec3(0.25f, 0, 0), glm::vec3(0, 0.25f, 0)},
        {glm::vec3(2, 1, 1), glm::vec3(1.75f, 1, 1), glm::vec3(2, 0.75f, 1)},
        {glm::vec3(1, 0.25f, 0.25f), glm::vec3(1, 0.75f, 0.25f), glm::vec3(1, 0.25f, 0.75f)},
    });
    const UniformGrid grid = gridOf(scene, {2, 1, 1});
    ASSERT_EQ(grid.cellOffsets, (std::vector<std::uint32_t>{0, 2, 4}));
    for (std::uint32_t test : {gpu::kTriangleTestMollerTrumbore, gpu::kTriangleTestWatertight}) {
        SCOPED_TRACE(testName(test));
        const std::unique_ptr<Structure> s = gridStructure(grid);
        s->setTriangleTest(test);
        const std::vector<gpu::Ray> rays = {ray({-1, 0.375f, 0.375f}, {1, 0, 0})};
        const Expect onTheFace{2, 2.0f, 1, 2, 0};
        expectAnswers(answersOf(*vk_, *s, rays), 0, onTheFace);
        MultipassOptions o;
        o.deviceControl = true;
        expectRecord(runMultipass(*vk_, *s, rays, o, {64, 0, 1}).hits[0], onTheFace, "multipass, the oracle on the device");
    }
}

// Multipass on ray A alone, K = M = 1, oracle 0: S (enters (0,0): waits) I (triangle 0; the list
// ends: traversing) T (-> (1,0): waits) I (2) T (-> (1,1): waits) I (1) I (4: a hit at 2.5 within
// the voxel: done) W. Offsets read: 2 per voxel entered (3) + 1 per intersect pass served (4) = 10;
// list entries and vertices: 4 tests. State: setup 80, traverse 2 x 112, intersect 4 x 128, write 16.
TEST_F(GridHandKernels, MultipassEventsOfTheCornerRayByHand) {
    const std::unique_ptr<Structure> s = gridStructure(cornerGrid());
    MultipassOptions o;
    o.oracleThreshold = 0.0;
    const std::vector<gpu::Ray> rays = {cornerRays()[0]};
    const MultipassRun r = runMultipass(*vk_, *s, rays, o, {64, 0, 1});
    using K = PassKind;
    EXPECT_EQ(r.counts.sequence, (std::vector<K>{K::Setup, K::Intersect, K::Traverse, K::Intersect, K::Traverse,
                                                 K::Intersect, K::Intersect, K::Write}));
    EXPECT_TRUE(r.counts == simulateMultipass(*s, rays, o).counts);
    EXPECT_EQ(r.counts.structureReads, 10u);
    EXPECT_EQ(r.counts.triangleReads, 4u);
    EXPECT_EQ(r.counts.stencilWrites, 1u + 5u);  // setup; waiting/traversing changes 4, done 1
    expectRecord(r.hits[0], kCornerAnswers[0], "ray A");
    const ArchitectureMetrics m = multipassMetrics(r.hits, r.counts, o, s->costs());
    EXPECT_EQ(m.bytes.state, 80u + 2u * 112u + 4u * 128u + 16u);
    EXPECT_EQ(m.bytes.stack, 0u);  // the grid's state has no stack
    EXPECT_EQ(m.bytes.cells, 10u * 4u);
    EXPECT_EQ(m.passesLowerBound, 2u + 4u);  // 2 steps / K + 4 tests / M
}

}  // namespace
}  // namespace rtbench
