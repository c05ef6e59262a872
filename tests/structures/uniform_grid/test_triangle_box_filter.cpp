// The grid builder's float filters (structures/uniform_grid/voxel_block_filter.h, then
// triangle_box_filter.h) against CGAL's exact triangle-box test: where a filter answers, it
// answers as CGAL does; where a sign is too close to call, it says unsure. And the grids they
// build, on the scenes of record, list exactly the voxels CGAL's test gives each triangle.
#include <gtest/gtest.h>

#include <random>

#include "scene/procedural.h"
#include "scene/scene_description.h"
#include "structures/uniform_grid/triangle_box_filter.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "structures/uniform_grid/voxel_block_filter.h"

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

// Points for random triangles and boxes: uniform in [-2, 3)^3, or snapped to the integer lattice
// there (shared coordinates: faces and corners that touch).
struct RandomPoints {
    std::mt19937 rng;
    std::uniform_real_distribution<float> coord{-2.0f, 3.0f};
    std::uniform_int_distribution<int> lattice{-2, 3};
    explicit RandomPoints(unsigned seed) : rng(seed) {}
    glm::vec3 operator()(bool snapped) {
        return snapped ? glm::vec3(lattice(rng), lattice(rng), lattice(rng)) : glm::vec3(coord(rng), coord(rng), coord(rng));
    }
};

// A block of voxels with the given faces per axis (the same on every axis), and its filter for t.
struct Block {
    std::vector<double> lo, hi;
    VoxelBlockFilter filter;
    Block(const gpu::Triangle& t, std::vector<double> faceLo, std::vector<double> faceHi) : lo(std::move(faceLo)), hi(std::move(faceHi)) {
        VoxelBlock block;
        for (int a = 0; a < 3; ++a) block.lo[a] = lo.data(), block.hi[a] = hi.data();
        block.size = glm::ivec3(int(lo.size()));
        filter.reset({glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)}, block);
    }
};

Overlap blockFiltered(const gpu::Triangle& t, const VoxelBox& box) {
    VoxelBlockFilter filter;
    VoxelBlock block;
    for (int a = 0; a < 3; ++a) block.lo[a] = &box.min[a], block.hi[a] = &box.max[a];
    block.size = glm::ivec3(1);
    filter.reset({glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)}, block);
    return filter.at(0, 0, 0);
}

// Hand cases: each answer follows from the geometry (the box is [0, 1]^3). Both filters.
void expectHandCases(Overlap (*filtered)(const gpu::Triangle&, const VoxelBox&)) {
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
    // In the plane z = 0.5, beyond the box's edge x = 1 on the far side of the line x + y = 2.25
    // only: the bounding boxes overlap and the plane crosses the box; the edge axis decides.
    EXPECT_EQ(filtered(triangle({1.25f, 1, 0.5f}, {1, 1.25f, 0.5f}, {2, 2, 0.5f}), kUnitBox), Overlap::No);
    // The same line through the corner region, x + y = 1.75: it cuts the box's corner.
    EXPECT_EQ(filtered(triangle({0.75f, 1, 0.5f}, {1, 0.75f, 0.5f}, {2, 2, 0.5f}), kUnitBox), Overlap::Yes);
}

TEST(TriangleBoxFilter, AnswersTheCasesItCanBeSureOf) { expectHandCases(filtered); }
TEST(VoxelBlockFilter, AnswersTheCasesItCanBeSureOf) { expectHandCases(blockFiltered); }

// x + y + z = 3 touches the corner (1, 1, 1) and nothing else of the box: the plane's sign at that
// corner is exactly 0, which no float bound can certify from nonzero factors. Unsure, not a guess.
TEST(TriangleBoxFilter, IsUnsureWhereOnlyExactArithmeticCanTell) {
    const gpu::Triangle t = triangle({3, 0, 0}, {0, 3, 0}, {0, 0, 3});
    EXPECT_EQ(filtered(t, kUnitBox), Overlap::Unsure);
    EXPECT_EQ(blockFiltered(t, kUnitBox), Overlap::Unsure);
    EXPECT_TRUE(triangleOverlapsBox(t, kUnitBox));
}

// A triangle on a voxel face (z = 1, shared by two voxels) meets both: exact zeros, no rounding,
// so the block filter is sure; a segment (degenerate) is left to CGAL.
TEST(VoxelBlockFilter, IsSureOfExactZerosAndRefusesSegments) {
    Block face(triangle({0.25f, 0.25f, 1}, {0.75f, 0.25f, 1}, {0.25f, 0.75f, 1}), {0, 1}, {1, 2});
    ASSERT_TRUE(face.filter.proper());
    EXPECT_EQ(face.filter.at(0, 0, 0), Overlap::Yes);
    EXPECT_EQ(face.filter.at(0, 0, 1), Overlap::Yes);
    EXPECT_EQ(face.filter.at(1, 0, 0), Overlap::No);
    EXPECT_FALSE(Block(triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), {0}, {1}).filter.proper());
}

// Random triangles against blocks of 5^3 voxels, half of them on the lattice (the voxels' faces on
// it too): every answer the block filter gives is CGAL's, and it answers most.
TEST(VoxelBlockFilter, AgreesWithCgalWheneverItAnswers) {
    RandomPoints point(11);
    std::uint64_t answered = 0, total = 0, yes = 0;
    for (int i = 0; i < 40000; ++i) {
        const bool snapped = i % 2 == 0;
        const gpu::Triangle t = triangle(point(snapped), point(snapped), point(snapped));
        // Five voxels per axis: unit cells from -2.5 to 2.5, or random widths from a random start.
        std::vector<double> lo, hi;
        double face = snapped ? -2.5 : double(point.coord(point.rng)) - 1.0;
        for (int v = 0; v < 5; ++v, face = hi.back())
            lo.push_back(face), hi.push_back(face + (snapped ? 1.0 : 0.25 + double(point.coord(point.rng) + 2.0f) / 5.0));
        const Block block(t, lo, hi);
        if (!block.filter.proper()) continue;  // the builder sends these to CGAL
        for (int x = 0; x < 5; ++x)
            for (int y = 0; y < 5; ++y)
                for (int z = 0; z < 5; ++z) {
                    const VoxelBox box{{lo[x], lo[y], lo[z]}, {hi[x], hi[y], hi[z]}};
                    const Overlap o = block.filter.at(x, y, z);
                    ++total;
                    if (o == Overlap::Unsure) continue;
                    ++answered;
                    yes += o == Overlap::Yes;
                    ASSERT_EQ(o == Overlap::Yes, triangleOverlapsBox(t, box)) << "triangle " << i << ", voxel " << x << " " << y << " " << z;
                }
    }
    EXPECT_GT(answered, total * 95 / 100) << answered << " of " << total;
    EXPECT_GT(yes, answered / 20);
    EXPECT_LT(yes, answered * 9 / 10);
}

// Random triangles against random boxes, a third of them on the lattice: every answer the filter
// gives is CGAL's, and it answers most.
TEST(TriangleBoxFilter, AgreesWithCgalWheneverItAnswers) {
    RandomPoints point(7);
    std::uint64_t answered = 0, total = 0, yes = 0;
    for (int i = 0; i < 200000; ++i) {
        const bool snapped = i % 3 == 0;
        const gpu::Triangle t = triangle(point(snapped), point(snapped), point(snapped));
        glm::dvec3 a = glm::dvec3(point(snapped)), b = glm::dvec3(point(snapped));
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

// Boxes with a corner on a triangle's edge line, or a few ulps off it, at a point with many bits
// (start + (end - start) k / 2^20, then moved by -2 to 2 ulps per axis): the exact edge function
// there is 0 or about as small as its products' rounding. Where that rounding could flip a sign
// the filters must say unsure, and wherever they answer, CGAL agrees.
TEST(VoxelBlockFilter, AgreesWithCgalWhereAnEdgeLineGrazesACorner) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(1.0f, 2.0f);
    std::uniform_int_distribution<int> fraction(1, (1 << 20) - 1), side(0, 1), ulps(-2, 2);
    std::uniform_real_distribution<double> size(0.01, 1.0);
    std::uint64_t unsure = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 start(coord(rng), coord(rng), coord(rng)), end(coord(rng), coord(rng), coord(rng)), third(coord(rng), coord(rng), coord(rng));
        const double t = std::ldexp(double(fraction(rng)), -20);
        glm::dvec3 corner = glm::dvec3(start) + (glm::dvec3(end) - glm::dvec3(start)) * t;
        const bool onTheLine = i % 2 == 0;
        for (int a = 0; a < 3 && !onTheLine; ++a)
            for (int step = ulps(rng); step != 0; step += step < 0 ? 1 : -1) corner[a] = std::nextafter(corner[a], step < 0 ? 0.0 : 4.0);
        glm::dvec3 lo, hi;
        for (int a = 0; a < 3; ++a) {
            const double extent = size(rng);
            lo[a] = side(rng) ? corner[a] : corner[a] - extent;
            hi[a] = lo[a] == corner[a] ? corner[a] + extent : corner[a];
        }
        const gpu::Triangle tri = triangle(start, end, third);
        if (glm::length(glm::cross(glm::dvec3(tri.v1 - tri.v0), glm::dvec3(tri.v2 - tri.v0))) == 0.0) continue;
        const VoxelBox box{lo, hi};
        const Overlap block = blockFiltered(tri, box), corners = filtered(tri, box);
        unsure += block == Overlap::Unsure;
        const bool exact = triangleOverlapsBox(tri, box);
        if (onTheLine) {
            ASSERT_TRUE(exact) << "triangle " << i << ": the edge passes through the box's corner";
        }
        if (block != Overlap::Unsure) {
            ASSERT_EQ(block == Overlap::Yes, exact) << "triangle " << i;
        }
        if (corners != Overlap::Unsure) {
            ASSERT_EQ(corners == Overlap::Yes, exact) << "triangle " << i;
        }
    }
    EXPECT_GT(unsure, 0u);  // some really are too close to call
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
