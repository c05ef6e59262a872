// The exact reference on hand-built cases whose exact answers are known: ties on shared edges and
// vertices, a grazing ray in a triangle's plane, near misses, and a scene where the float
// distances of two triangles are equal but the exact ones are not.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/exact_reference.h"

namespace rtbench {
namespace {

gpu::Ray ray(glm::vec3 origin, glm::vec3 direction, float tMin = 0.0f, float tMax = gpu::kNoHitT) {
    return {glm::vec4(origin, tMin), glm::vec4(direction, tMax)};
}

TriangleMesh mesh(std::vector<glm::vec3> vertices, std::vector<glm::uvec3> triangles) {
    TriangleMesh m;
    m.vertices = std::move(vertices);
    m.triangles = std::move(triangles);
    return m;
}

// Two triangles of the unit square at z = 1, sharing the diagonal (0,0)-(1,1).
TriangleMesh square() { return mesh({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, {{0, 1, 2}, {0, 2, 3}}); }

std::vector<std::uint32_t> tieSet(const ExactHit& hit, const std::vector<std::uint32_t>& ties) {
    return {ties.begin() + hit.tieFirst, ties.begin() + hit.tieFirst + hit.tieCount};
}

TEST(ExactReference, InteriorHitHasOneTriangleAndTheExactDistance) {
    const TriangleMesh m = square();
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    const ExactHit hit = exact.trace(ray({0.75f, 0.25f, 0}, {0, 0, 1}), ties);
    EXPECT_EQ(hit.primitive, 0u);
    EXPECT_EQ(hit.tieCount, 1u);
    EXPECT_EQ(hit.t, 1.0);
    const ExactHit scaled = exact.trace(ray({0.25f, 0.75f, 0}, {0, 0, 4}), ties);
    EXPECT_EQ(scaled.primitive, 1u);
    EXPECT_EQ(scaled.t, 0.25);  // t counts direction lengths
}

TEST(ExactReference, RayThroughASharedEdgeHitsBothTriangles) {
    const TriangleMesh m = square();
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    const ExactHit hit = exact.trace(ray({0.5f, 0.5f, 0}, {0, 0, 1}), ties);
    EXPECT_EQ(hit.tieCount, 2u);
    EXPECT_EQ(tieSet(hit, ties), (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(hit.t, 1.0);
}

TEST(ExactReference, RayThroughASharedVertexHitsTheWholeFan) {
    // Four triangles around the vertex (0,0,2).
    const TriangleMesh m = mesh({{0, 0, 2}, {1, 0, 2}, {0, 1, 2}, {-1, 0, 2}, {0, -1, 2}},
                                {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}});
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    const ExactHit hit = exact.trace(ray({0, 0, 0}, {0, 0, 1}), ties);
    EXPECT_EQ(hit.tieCount, 4u);
    EXPECT_EQ(hit.primitive, 0u);
    EXPECT_EQ(hit.t, 2.0);
}

TEST(ExactReference, ATieOfTrianglesInDifferentPlanesReportsTheLowestId) {
    // A valley: triangle 0 in the plane z = x, triangle 1 in z = -x, sharing the edge x = z = 0.
    // The ray from (-1.5, 2, 3) along (1, 0, -2) meets z = -x at t = 1.5 (3 - 2t = 1.5 - t) and
    // z = x at t = 1.5 (3 - 2t = t - 1.5): the point (0, 2, 0) of the shared edge, a tie.
    const TriangleMesh m = mesh({{0, 0, 0}, {0, 4, 0}, {2, 2, 2}, {-2, 2, 2}}, {{0, 1, 2}, {0, 1, 3}});
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    const ExactHit hit = exact.trace(ray({-1.5f, 2, 3}, {1, 0, -2}), ties);
    EXPECT_EQ(hit.t, 1.5);
    EXPECT_EQ(hit.tieCount, 2u);
    EXPECT_EQ(hit.primitive, 0u);
    // One ulp to the left (x0 = -1.5 - 2^-23 = -1.5 - e) the ray passes left of the edge: it meets
    // z = -x at t = 1.5 - e, at x = -2e (inside triangle 1), and z = x only at 1.5 + e/3, at
    // x = -2e/3 (outside triangle 0, whose x >= 0): triangle 1 alone.
    const ExactHit beside = exact.trace(ray({-1.5f - std::ldexp(1.0f, -23), 2, 3}, {1, 0, -2}), ties);
    EXPECT_EQ(beside.tieCount, 1u);
    EXPECT_EQ(beside.primitive, 1u);
    EXPECT_NEAR(beside.t, 1.5 - std::ldexp(1.0, -23), 1e-15);
}

TEST(ExactReference, RayJustOutsideAnEdgeMisses) {
    const TriangleMesh m = mesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}});
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    // x + y = 1 is the hypotenuse; the next float above 0.5 puts the ray outside.
    EXPECT_EQ(exact.trace(ray({std::nextafter(0.5f, 1.0f), 0.5f, 0}, {0, 0, 1}), ties).primitive, gpu::kNoHit);
    EXPECT_EQ(exact.trace(ray({0.5f, 0.5f, 0}, {0, 0, 1}), ties).primitive, 0u);  // on the edge: a hit
    EXPECT_EQ(exact.trace(ray({0.25f, 0.25f, 0}, {0, 0, -1}), ties).primitive, gpu::kNoHit);  // behind
}

TEST(ExactReference, GrazingRayInTheTrianglesPlaneHitsWhereItEnters) {
    const TriangleMesh m = mesh({{1, 0, 0}, {3, 0, 0}, {1, 2, 0}}, {{0, 1, 2}});
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    // Along +x in the plane z = 0, at y = 0.5: enters at x = 1.
    const ExactHit hit = exact.trace(ray({0, 0.5f, 0}, {1, 0, 0}), ties);
    EXPECT_EQ(hit.primitive, 0u);
    EXPECT_EQ(hit.t, 1.0);
    // Along the edge y = 0 itself: enters at its end point (1, 0, 0).
    EXPECT_EQ(exact.trace(ray({-1, 0, 0}, {2, 0, 0}), ties).t, 1.0);
    // Starting inside the triangle: the hit is at tMin.
    EXPECT_EQ(exact.trace(ray({1.5f, 0.5f, 0}, {1, 0, 0}, 0.25f), ties).t, 0.25);
}

TEST(ExactReference, TMinAndTMaxBoundTheHit) {
    const TriangleMesh m = square();
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    EXPECT_EQ(exact.trace(ray({0.75f, 0.25f, 0}, {0, 0, 1}, 1.0f), ties).primitive, 0u);  // t = tMin counts
    EXPECT_EQ(exact.trace(ray({0.75f, 0.25f, 0}, {0, 0, 1}, 1.5f), ties).primitive, gpu::kNoHit);
    EXPECT_EQ(exact.trace(ray({0.75f, 0.25f, 0}, {0, 0, 1}, 0.0f, 1.0f), ties).primitive, gpu::kNoHit);  // t < tMax
}

TEST(ExactReference, TellsApartDistancesThatFloatsCannot) {
    // Triangle 0 at z = 1; triangle 1 tilted: z = 1 - 2^-23 (1 - x - y). At (0.5, 0.25) it lies at
    // 1 - 2^-25, exactly between two floats: in float both distances round to 1, exactly it is nearer.
    const float low = 1.0f - std::ldexp(1.0f, -23);
    const TriangleMesh m = mesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0, 0, low}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}, {3, 4, 5}});
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    const ExactHit hit = exact.trace(ray({0.5f, 0.25f, 0}, {0, 0, 1}), ties);
    EXPECT_EQ(hit.primitive, 1u);
    EXPECT_EQ(hit.tieCount, 1u);
    EXPECT_EQ(hit.t, 1.0 - std::ldexp(1.0, -25));
    EXPECT_EQ(float(hit.t), 1.0f);
}

TEST(ExactReference, DegenerateTrianglesAreNeverHit) {
    const TriangleMesh m = mesh({{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {0, 0, 2}, {1, 0, 2}, {0, 1, 2}}, {{0, 1, 2}, {3, 4, 5}});
    const ExactReference exact(m);
    std::vector<std::uint32_t> ties;
    const ExactHit hit = exact.trace(ray({0.5f, 0, 0}, {0, 0, 1}), ties);
    EXPECT_EQ(hit.primitive, 1u);  // through the collinear triangle 0, onto triangle 1's edge
    EXPECT_EQ(hit.t, 2.0);
}

TEST(ExactReference, SampleIsAnEvenStrideFromRayZero) {
    EXPECT_EQ(sampleRays(5, 0), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(sampleRays(5, 9), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(sampleRays(10, 3), (std::vector<std::uint32_t>{0, 4, 8}));
    EXPECT_EQ(sampleRays(10, 5), (std::vector<std::uint32_t>{0, 2, 4, 6, 8}));
}

TEST(ExactReference, AccuracyCountsLeaksFalseHitsWrongTrianglesAndAcceptsTies) {
    const TriangleMesh m = square();
    const ExactReference exact(m);
    const std::vector<gpu::Ray> rays = {ray({0.75f, 0.25f, 0}, {0, 0, 1}), ray({0.5f, 0.5f, 0}, {0, 0, 1}),
                                        ray({2, 2, 0}, {0, 0, 1}), ray({0.25f, 0.75f, 0}, {0, 0, 1})};
    const ExactHits reference = exact.trace(rays, sampleRays(rays.size(), 0));
    auto record = [](std::uint32_t primitive, float t) {
        gpu::HitRecord h{};
        h.primitive = primitive;
        h.t = primitive == gpu::kNoHit ? gpu::kNoHitT : t;
        return h;
    };
    // Ray 1 (a tie) answered with triangle 1: correct. Ray 0 missed: a leak. Ray 2 hit: false.
    // Ray 3 on the wrong triangle at a distance off by 1%.
    const std::vector<gpu::HitRecord> hits = {record(gpu::kNoHit, 0), record(1, 1.0f), record(0, 3.0f), record(0, 1.01f)};
    const ExactAccuracy a = compareExact(hits, reference);
    EXPECT_EQ(a.rays, 4u);
    EXPECT_EQ(a.falseMisses, 1u);
    EXPECT_EQ(a.falseHits, 1u);
    EXPECT_EQ(a.wrongPrimitive, 1u);
    EXPECT_EQ(a.ties, 1u);
    EXPECT_EQ(a.wrong(), 3u);
    EXPECT_NEAR(a.distanceErrorMax, 0.01, 1e-6);
    EXPECT_NEAR(a.distanceErrorMean, 0.005, 1e-6);
}

}  // namespace
}  // namespace rtbench
