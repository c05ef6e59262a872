// The watertight test's exact fallback (Woop, Benthin & Wald 2013 §3.3; kernels/ray_math.glsl):
// an edge function that is 0 in float is recomputed in double, where the products of floats are
// exact, so its sign is the exact sign. Rays are placed deliberately where one float edge
// function rounds to 0 although the exact value is not (issue 15 §6.2): the answer must then be
// the exact reference's (harness/exact_reference.h) and the one reasoned out below, on every
// structure, in the kernels and the CPU reference alike.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/exact_reference.h"
#include "tests/device/test_device.h"
#include "tests/methods/hand_scenes.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;

// The ray goes up the z axis from (0, 0, -1): its direction's largest component is z, so the
// shear is (0, 0, 1) and the 2D coordinates of a vertex are just its x and y (exact), every
// vertex lying at z = 0 (t = 1).
//   B = (-(1 + 2^-22), -(1 + 2^-23)),  C = (1 + 2^-23, 1),
// the edge B-C passes 2^-47 below the origin (at x = 0), a long edge (length 2.8) through the ray.
// Its edge function C.x B.y - C.y B.x is exactly -(1 + 2^-22 + 2^-46) + (1 + 2^-22) = -2^-46, but
// in float the first product rounds to -(1 + 2^-22) (2^-46 is below half an ulp, 2^-24) and the
// difference is 0. With the third vertex
//   A_in  = (-1,  1): the other two edge functions are -(2 + 2^-23) and -(2 + 3 2^-23): all three
//           negative, the ray is inside (by 2^-47 in y): a hit at t = 1;
//   A_out = ( 1, -1): they are +(2 + 2^-23) and +(2 + 3 2^-23): mixed signs, the ray is outside
//           (by 2^-47 in y): a miss. Without the fallback the float 0 would count as "on the edge" and
//           this triangle would be hit.
// Rotating the vertices (A,B,C) -> (B,C,A) -> (C,A,B) moves the edge B-C to the w and then the v
// edge function, with the very same float products, so each of the three recomputations is used.
const float kE22 = std::ldexp(1.0f, -22), kE23 = std::ldexp(1.0f, -23);
const glm::vec3 kB(-(1.0f + kE22), -(1.0f + kE23), 0.0f), kC(1.0f + kE23, 1.0f, 0.0f);
const glm::vec3 kAIn(-1.0f, 1.0f, 0.0f), kAOut(1.0f, -1.0f, 0.0f);

gpu::Ray upTheAxis() { return ray({0, 0, -1}, {0, 0, 1}); }

Tri rotated(const glm::vec3& a, int rotation) {
    if (rotation == 0) return {a, kB, kC};
    if (rotation == 1) return {kB, kC, a};
    return {kC, a, kB};
}

// The construction does what the comment says, in float and in double.
TEST(WatertightEdgeConstruction, TheFloatEdgeFunctionIsZeroAndTheExactOneIsMinusTwoToTheMinus46) {
    const volatile float cx = kC.x, cy = kC.y, bx = kB.x, by = kB.y;  // volatile: no folding, no FMA
    const float p = cx * by, q = cy * bx;
    EXPECT_EQ(p, q);
    EXPECT_EQ(p - q, 0.0f);
    EXPECT_EQ(double(cx) * double(by) - double(cy) * double(bx), -std::ldexp(1.0, -46));
}

// The exact reference agrees with the reasoning above: A_in's triangles are hit at t = 1 without
// a tie, A_out's are missed, and in the quad of both (sharing B-C) only A_in's triangle is hit.
TEST(WatertightEdgeConstruction, TheExactReferenceHitsOnlyTheTriangleOnTheRaysSide) {
    std::vector<std::uint32_t> ties;
    for (int rotation = 0; rotation < 3; ++rotation) {
        SCOPED_TRACE("rotation " + std::to_string(rotation));
        const ExactHit in = ExactReference(meshOf({rotated(kAIn, rotation)})).trace(upTheAxis(), ties);
        EXPECT_EQ(in.primitive, 0u);
        EXPECT_EQ(in.t, 1.0);
        EXPECT_EQ(in.tieCount, 1u);
        EXPECT_EQ(ExactReference(meshOf({rotated(kAOut, rotation)})).trace(upTheAxis(), ties).primitive, kNoHit);
    }
    const ExactHit quad = ExactReference(meshOf({rotated(kAOut, 0), rotated(kAIn, 0)})).trace(upTheAxis(), ties);
    EXPECT_EQ(quad.primitive, 1u);
    EXPECT_EQ(quad.tieCount, 1u);
}

using WatertightEdges = VulkanTest;

// Every structure with intersection.test = watertight, every way it runs, against the hand and
// the exact reference. t = 1: the sheared z of every vertex is 1, so the scaled distance equals
// the determinant.
TEST_F(WatertightEdges, AFloatZeroEdgeFunctionTakesTheExactSignInEveryStructure) {
    const StructureCase structures[] = {bruteCase(), gridCase({1, 1, 1}), gridCase({3, 3, 1}), bvhCase(1)};
    for (const StructureCase& sc : structures)
        for (int rotation = 0; rotation < 3; ++rotation)
            for (bool inside : {true, false}) {
                SCOPED_TRACE(sc.name + ", rotation " + std::to_string(rotation) + (inside ? ", A_in" : ", A_out"));
                const TriangleMesh mesh = meshOf({rotated(inside ? kAIn : kAOut, rotation)});
                const std::unique_ptr<Structure> s = sc.build(mesh, vk_->info());
                s->setTriangleTest(gpu::kTriangleTestWatertight);
                const Answers a = answersOf(*vk_, *s, {upTheAxis()});
                expectAnswers(a, 0, inside ? Expect{0, 1.0f} : Expect{kNoHit});
                // The exact reference says the same (no tie to accept here).
                const ExactHits exact = ExactReference(mesh).trace(std::vector<gpu::Ray>{upTheAxis()}, {0u});
                EXPECT_EQ(compareExact(a.branching, exact).wrong(), 0u);
                EXPECT_EQ(compareExact(a.cpu, exact).wrong(), 0u);
            }
}

// The quad split along B-C: float edge functions alone would put the ray on the shared edge of
// both triangles, a tie the lower id (A_out's, 0) would win (test_tie_rule.cpp); exactly it lies
// inside A_in's triangle (1) only, and that is what every structure must report.
TEST_F(WatertightEdges, TheQuadSplitAlongTheNearlyZeroEdgeReportsTheExactSide) {
    const TriangleMesh quad = meshOf({rotated(kAOut, 0), rotated(kAIn, 0)});
    const ExactHits exact = ExactReference(quad).trace(std::vector<gpu::Ray>{upTheAxis()}, {0u});
    for (const StructureCase& sc : {bruteCase(), gridCase({1, 1, 1}), bvhCase(1), bvhCase(2)}) {
        SCOPED_TRACE(sc.name);
        const std::unique_ptr<Structure> s = sc.build(quad, vk_->info());
        s->setTriangleTest(gpu::kTriangleTestWatertight);
        const Answers a = answersOf(*vk_, *s, {upTheAxis()});
        expectAnswers(a, 0, Expect{1, 1.0f});
        EXPECT_EQ(compareExact(a.multipass, exact).wrong(), 0u);
    }
}

}  // namespace
}  // namespace rtbench
