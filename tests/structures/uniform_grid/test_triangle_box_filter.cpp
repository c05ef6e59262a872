// The grid builder's float filter (structures/uniform_grid/triangle_box_filter.h) against CGAL's
// exact triangle-box test: where the filter answers, it answers as CGAL does; where a sign is too
// close to call, it says unsure. And the grids it builds, on the scenes of record, list exactly
// the voxels CGAL's test gives each triangle.
#include <gtest/gtest.h>

#include <random>

#include "scene/procedural.h"
#include "scene/scene_description.h"
#include "structures/uniform_grid/triangle_box_filter.h"
#include "structures/uniform_grid/uniform_grid.h"

namespace rtbench {
namespace {

gpu::Triangle triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    return {glm::vec4(a, 0.0f), glm::vec4(b, 0.0f), glm::vec4(c, 0.0f)};
}

Overlap filtered(const gpu::Triangle& t, const VoxelBox& box) {
    const FilterTriangle f({glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)});
    return filteredTriangleBoxOverlap(f, box.min, box.max);
}

const VoxelBox kUnitBox{{0, 0, 0}, {1, 1, 1}};

// Hand cases: each answer follows from the geometry (the box is [0, 1]^3).
TEST(TriangleBoxFilter, AnswersTheCasesItCanBeSureOf) {
    // A vertex inside; far away on x; the plane y = 0.5 through the box, no vertex in it.
    EXPECT_EQ(filtered(triangle({0.5f, 0.5f, 0.5f}, {5, 5, 5}, {5, 6, 5}), kUnitBox), Overlap::Yes);
    EXPECT_EQ(filtered(triangle({2, 0, 0}, {3, 1, 0}, {2, 1, 1}), kUnitBox), Overlap::No);
    EXPECT_EQ(filtered(triangle({-10, 0.5f, -10}, {10, 0.5f, -10}, {0, 0.5f, 10}), kUnitBox), Overlap::Yes);
    // The plane x + y + z = 3 + 2^-20 passes the corner (1, 1, 1) by 2^-20: the plane separates.
    const float d = 3.0f + 0x1p-20f;
    EXPECT_EQ(filtered(triangle({d, 0, 0}, {0, d, 0}, {0, 0, d}), kUnitBox), Overlap::No);
    // In the box's face plane z = 1, crossing it with no vertex inside: exact zeros, touching.
    EXPECT_EQ(filtered(triangle({-5, 0.5f, 1}, {5, -5, 1}, {5, 5, 1}), kUnitBox), Overlap::Yes);
    // Its bounding box overlaps the box, yet an edge axis separates them: the triangle passes
    // the corner (1, 1, z) diagonally, beyond x + y = 2.5.
    EXPECT_EQ(filtered(triangle({2.5f, 0, 0.5f}, {0, 2.5f, 0.5f}, {2.5f, 2.5f, 0.5f}), kUnitBox), Overlap::No);
}

// x + y + z = 3 touches the corner (1, 1, 1) and nothing else of the box: the plane's sign at that
// corner is exactly 0, which no float bound can certify from nonzero factors. Unsure, not a guess.
TEST(TriangleBoxFilter, IsUnsureWhereOnlyExactArithmeticCanTell) {
    const gpu::Triangle t = triangle({3, 0, 0}, {0, 3, 0}, {0, 0, 3});
    EXPECT_EQ(filtered(t, kUnitBox), Overlap::Unsure);
    EXPECT_TRUE(triangleOverlapsBox(t, kUnitBox));
}

// Random triangles against random boxes, many of them on one lattice (shared coordinates, faces
// and corners that touch): every answer the filter gives is CGAL's, and it answers most.
TEST(TriangleBoxFilter, AgreesWithCgalWheneverItAnswers) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-2.0f, 3.0f);
    std::uniform_int_distribution<int> lattice(-2, 3);
    std::uint64_t answered = 0, total = 0, yes = 0;
    for (int i = 0; i < 200000; ++i) {
        const bool snapped = i % 3 == 0;
        auto point = [&] { return snapped ? glm::vec3(lattice(rng), lattice(rng), lattice(rng)) : glm::vec3(coord(rng), coord(rng), coord(rng)); };
        const gpu::Triangle t = triangle(point(), point(), point());
        glm::dvec3 a = glm::dvec3(point()), b = glm::dvec3(point());
        const VoxelBox box{glm::min(a, b), glm::max(a, b)};
        const Overlap o = filtered(t, box);
        const bool degenerate = glm::length(glm::cross(glm::dvec3(t.v1 - t.v0), glm::dvec3(t.v2 - t.v0))) == 0.0;
        if (degenerate) continue;  // the builder sends these to CGAL
        ++total;
        if (o == Overlap::Unsure) continue;
        ++answered;
        yes += o == Overlap::Yes;
        ASSERT_EQ(o == Overlap::Yes, triangleOverlapsBox(t, box)) << "triangle " << i;
    }
    EXPECT_GT(answered, total * 95 / 100) << answered << " of " << total;
    EXPECT_GT(yes, answered / 10);
    EXPECT_LT(yes, answered * 9 / 10);
}

// Every voxel CGAL's test gives a triangle, over its bounding box widened by a cell each way,
// against the builder's lists: the same (cell, triangle) pairs, in the same order.
void expectExactCells(const TriangleMesh& mesh, unsigned minDim) {
    GridResolutionRule rule;
    rule.minDim = minDim;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const auto& r = grid.stats.resolution;
    std::vector<std::vector<std::uint32_t>> expected(grid.cellCount());
    for (std::uint32_t i = 0; i < grid.triangles.size(); ++i) {
        const gpu::Triangle& t = grid.triangles[i];
        glm::ivec3 lo, hi;
        for (int a = 0; a < 3; ++a) {
            const double local0 = (std::min({t.v0[a], t.v1[a], t.v2[a]}) - double(grid.params.boundsMin[a])) / grid.params.cellSize[a];
            const double local1 = (std::max({t.v0[a], t.v1[a], t.v2[a]}) - double(grid.params.boundsMin[a])) / grid.params.cellSize[a];
            lo[a] = std::max(0, int(std::floor(local0)) - 1);
            hi[a] = std::min(int(r[a]) - 1, int(std::floor(local1)) + 1);
        }
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    if (triangleOverlapsBox(t, grid.voxelBounds(x, y, z))) expected[x + r[0] * (y + std::uint64_t(r[1]) * z)].push_back(i);
    }
    for (std::uint64_t c = 0; c < grid.cellCount(); ++c)
        ASSERT_EQ(std::vector<std::uint32_t>(grid.triangleList.begin() + grid.cellOffsets[c],
                                             grid.triangleList.begin() + grid.cellOffsets[c + 1]),
                  expected[c])
            << mesh.name << " min_dim " << minDim << ", cell " << c;
    // The filter decides nearly every voxel (were it unsure of all, this build would be CGAL's).
    EXPECT_LT(grid.stats.exactTests * 20, grid.stats.voxelTests) << grid.stats.exactTests << " of " << grid.stats.voxelTests;
}

TEST(TriangleBoxFilter, GridsOfTheScenesOfRecordListTheExactCells) {
    const std::string configs = std::string(RTBENCH_SOURCE_DIR) + "/configs";
    for (const char* source : {"procedural:christen_a", "procedural:christen_b", "cgal:bunny00", "../scenes/christen_c.toml",
                               "../scenes/teapot_in_stadium.toml"}) {
        const TriangleMesh mesh = loadSceneSource(source, configs);
        for (unsigned minDim : {32u, 64u}) expectExactCells(mesh, minDim);
    }
}

}  // namespace
}  // namespace rtbench
