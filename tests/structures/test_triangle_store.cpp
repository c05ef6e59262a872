// Packed vertices (intersection.vertex_bits): the lattice, the snap and the packing the kernels decode.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "structures/bvh/bvh_build.h"
#include "structures/bvh/bvh_structure.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "structures/triangle_store.h"
#include "tests/methods/test_rays.h"
#include "scene/procedural.h"
#include "tests/error_of.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

Bounds3 box(glm::vec3 lo, glm::vec3 hi) {
    Bounds3 b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

TEST(VertexLattice, StepIsTheLeastPowerOfTwoCoveringTheBox) {
    for (unsigned bits : {1u, 8u, 16u}) {
        const VertexLattice l = vertexLattice(box({-1.0f, 2.0f, 0.5f}, {0.3f, 2.5f, 3.5f}), bits);
        SCOPED_TRACE(bits);
        int exponent;
        EXPECT_EQ(std::frexp(l.step, &exponent), 0.5f);  // a power of two
        const double steps = double((1u << bits) - 1u);
        EXPECT_GE(double(l.step) * steps, 3.0);          // covers the largest extent (z: 3)
        EXPECT_LT(double(l.step) / 2 * steps, 3.0);      // and half of it would not
        EXPECT_EQ(l.origin, glm::vec3(-1.0f, 2.0f, 0.5f));
    }
    EXPECT_EQ(errorOf([] { vertexLattice(box({0, 0, 0}, {1, 1, 1}), 17); }), "vertex lattice: 17 bits per axis, expected 1 to 16");
    EXPECT_EQ(errorOf([] { vertexLattice(box({0, 0, 0}, {1, 1, 1}), 0); }), "vertex lattice: 0 bits per axis, expected 1 to 16");
}

TEST(VertexLattice, SnapMovesEachVertexByAtMostHalfAStepPerAxis) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-3.0f, 5.0f);
    TriangleMesh mesh;
    for (int i = 0; i < 3000; ++i) mesh.vertices.push_back({u(rng), u(rng), u(rng)});
    for (std::uint32_t i = 0; i + 2 < 3000; i += 3) mesh.triangles.push_back({i, i + 1, i + 2});
    for (unsigned bits : {4u, 10u, 16u}) {
        SCOPED_TRACE(bits);
        const TriangleMesh snapped = snapToLattice(mesh, bits);
        ASSERT_EQ(snapped.lattice.bits, bits);
        for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
            for (int axis = 0; axis < 3; ++axis)  // half a step, plus the sum's rounding
                EXPECT_LE(std::abs(snapped.vertices[i][axis] - mesh.vertices[i][axis]),
                          snapped.lattice.step * 0.5f + 8.0f * std::numeric_limits<float>::epsilon());
    }
}

// What the kernels decode (kernels/traversal_common.glsl rtStoredVertices) is the snapped float
// vertex, bit for bit: unpack the words here as the kernel does.
TEST(TriangleStore, PackedWordsDecodeToTheSnappedVerticesBitForBit) {
    const TriangleMesh snapped = snapToLattice(proceduralScene("icosphere"), 12);
    std::vector<gpu::Triangle> triangles;
    for (const glm::uvec3& t : snapped.triangles)
        triangles.push_back({glm::vec4(snapped.vertices[t.x], 0), glm::vec4(snapped.vertices[t.y], 0), glm::vec4(snapped.vertices[t.z], 0)});
    const TriangleStore store(triangles, snapped.lattice);
    const StructureBuffer buffer = store.buffer();
    ASSERT_EQ(buffer.bytes, triangles.size() * 20);
    const auto* words = static_cast<const std::uint32_t*>(buffer.data);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const std::uint32_t* w = words + 5 * i;
        const std::uint32_t q[9] = {w[0] & 0xFFFFu, w[0] >> 16, w[1] & 0xFFFFu, w[1] >> 16, w[2] & 0xFFFFu,
                                    w[2] >> 16,     w[3] & 0xFFFFu, w[3] >> 16, w[4]};
        const glm::vec4* corners[3] = {&triangles[i].v0, &triangles[i].v1, &triangles[i].v2};
        for (int c = 0; c < 3; ++c) {
            const glm::vec3 decoded = latticePoint(snapped.lattice, {q[3 * c], q[3 * c + 1], q[3 * c + 2]});
            const glm::vec3 stored(*corners[c]);
            EXPECT_EQ(std::memcmp(&decoded, &stored, sizeof decoded), 0) << "triangle " << i << " corner " << c;
        }
    }
    // Float vertices: the Triangle array itself, 48 bytes a triangle.
    EXPECT_EQ(TriangleStore(triangles, VertexLattice{}).buffer().bytes, triangles.size() * sizeof(gpu::Triangle));
}

TEST(TriangleStore, RefusesAVertexOffTheLattice) {
    const TriangleMesh snapped = snapToLattice(proceduralScene("tetrahedron"), 8);
    std::vector<gpu::Triangle> triangles;
    for (const glm::uvec3& t : snapped.triangles)
        triangles.push_back({glm::vec4(snapped.vertices[t.x], 0), glm::vec4(snapped.vertices[t.y], 0), glm::vec4(snapped.vertices[t.z], 0)});
    triangles[2].v1.x += snapped.lattice.step * 0.25f;
    EXPECT_THAT(errorOf([&] { TriangleStore(triangles, snapped.lattice); }),
                HasSubstr("a vertex of triangle 2 is not a point of the scene's lattice"));
}

// The CPU references run the kernels' own source (kernels/traversal_common.glsl rtStoredVertices):
// decoding the packed words must give every structure the same hit records, bit for bit, as the
// same snapped vertices stored as floats.
TEST(TriangleStore, PackedAndFloatStorageTraceTheSameHits) {
    const TriangleMesh packed = snapToLattice(proceduralScene("christen_b"), 10);
    TriangleMesh floats = packed;
    floats.lattice = VertexLattice{};
    const std::vector<gpu::Ray> rays = randomRays(packed.bounds(), 20000, 11);
    GridResolutionRule rule;
    rule.minDim = 16;
    const auto packedGrid = gridStructure(buildUniformGrid(packed, rule)), floatGrid = gridStructure(buildUniformGrid(floats, rule));
    ASSERT_EQ(packedGrid->vertexLattice().bits, 10u);
    ASSERT_EQ(floatGrid->vertexLattice().bits, 0u);
    expectIdentical(packedGrid->trace(rays), floatGrid->trace(rays));
    BvhBuildOptions options;
    const auto packedBvh = bvhStructure(buildBvh(packed, options)), floatBvh = bvhStructure(buildBvh(floats, options));
    const std::vector<gpu::HitRecord> hits = packedBvh->trace(rays);
    expectIdentical(hits, floatBvh->trace(rays));
    std::size_t hit = 0;
    for (const gpu::HitRecord& h : hits) hit += h.primitive != gpu::kNoHit;
    EXPECT_GT(hit, 5000u);  // the rays meet the scene
    EXPECT_EQ(packedBvh->costs().bytesPerTriangle, 20u);
    EXPECT_EQ(floatBvh->costs().bytesPerTriangle, 48u);
}

}  // namespace
}  // namespace rtbench
