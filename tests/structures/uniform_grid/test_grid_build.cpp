#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "scene/procedural.h"
#include "structures/uniform_grid/uniform_grid.h"

namespace rtbench {
namespace {

// Random triangles in [0, 4]^3 with a fixed seed: small, large, and some with vertices snapped
// exactly onto voxel boundary planes (a 1x1x1 voxel lattice), plus degenerate ones.
TriangleMesh randomTriangles(unsigned count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(0.0f, 4.0f), size(0.05f, 1.5f);
    TriangleMesh mesh;
    mesh.name = "random";
    auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const unsigned base = unsigned(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), {a, b, c});
        mesh.triangles.emplace_back(base, base + 1, base + 2);
    };
    // Pin the box to [0, 4]^3 so voxel boundaries are integers at resolution 4.
    add({0, 0, 0}, {4, 0, 0}, {0, 4, 4});
    for (unsigned i = 0; i < count; ++i) {
        const glm::vec3 centre(coord(rng), coord(rng), coord(rng));
        const float s = size(rng);
        glm::vec3 v[3];
        for (auto& p : v) {
            p = glm::clamp(centre + s * glm::vec3(coord(rng) - 2.0f, coord(rng) - 2.0f, coord(rng) - 2.0f) * 0.5f,
                           glm::vec3(0.0f), glm::vec3(4.0f));
            if (i % 5 == 0) p = glm::round(p);  // on boundary planes, edges and corners
        }
        if (i % 17 == 0) v[2] = v[1];                    // degenerate: repeated vertex
        if (i % 19 == 0) v[2] = 0.5f * (v[0] + v[1]);    // degenerate: collinear
        add(v[0], v[1], v[2]);
    }
    return mesh;
}

void expectMembershipMatchesBruteForce(const UniformGrid& grid) {
    const auto& r = grid.stats.resolution;
    std::uint64_t references = 0;
    for (unsigned z = 0; z < r[2]; ++z)
        for (unsigned y = 0; y < r[1]; ++y)
            for (unsigned x = 0; x < r[0]; ++x) {
                const std::uint64_t cell = x + r[0] * (y + std::uint64_t(r[1]) * z);
                std::set<std::uint32_t> listed(grid.triangleList.begin() + grid.cellOffsets[cell],
                                               grid.triangleList.begin() + grid.cellOffsets[cell + 1]);
                std::set<std::uint32_t> expected;
                for (std::uint32_t t = 0; t < grid.triangles.size(); ++t)
                    if (triangleOverlapsBox(grid.triangles[t], grid.voxelBounds(x, y, z))) expected.insert(t);
                ASSERT_EQ(listed, expected) << "voxel " << x << "," << y << "," << z;
                references += expected.size();
            }
    EXPECT_EQ(grid.stats.references, references);
}

TEST(GridBuild, MembershipEqualsBruteForceTriangleBoxTestOnRandomTriangles) {
    for (unsigned seed : {1u, 2u, 3u}) {
        const TriangleMesh mesh = randomTriangles(300, seed);
        for (std::array<unsigned, 3> res : {std::array<unsigned, 3>{4, 4, 4}, {7, 5, 6}, {1, 9, 2}}) {
            GridResolutionRule rule;
            rule.kind = GridResolutionRule::Kind::Explicit;
            rule.resolution = res;
            SCOPED_TRACE("seed " + std::to_string(seed) + " res " + std::to_string(res[0]) + "x" +
                         std::to_string(res[1]) + "x" + std::to_string(res[2]));
            expectMembershipMatchesBruteForce(buildUniformGrid(mesh, rule));
        }
    }
}

TEST(GridBuild, TriangleOnAVoxelFaceBelongsToBothVoxels) {
    TriangleMesh mesh;
    appendBox(mesh, {0, 0, 0}, {2, 1, 1});  // the faces x = 0 and x = 2 ...
    mesh.vertices.insert(mesh.vertices.end(), {{1, 0.2f, 0.2f}, {1, 0.8f, 0.2f}, {1, 0.2f, 0.8f}});
    mesh.triangles.emplace_back(8, 9, 10);  // ... and a triangle in the plane x = 1
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = {2, 1, 1};
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    auto listed = [&](unsigned cell, std::uint32_t tri) {
        return std::count(grid.triangleList.begin() + grid.cellOffsets[cell],
                          grid.triangleList.begin() + grid.cellOffsets[cell + 1], tri);
    };
    EXPECT_EQ(listed(0, 12), 1);
    EXPECT_EQ(listed(1, 12), 1);
}

// Memberships worked out by hand on a 2x2x2 grid over [0, 2]^3 (voxel index x + 2 (y + 2 z)),
// independent of the predicate under test.
TEST(GridBuild, MembershipEqualsHandComputedVoxels) {
    TriangleMesh mesh;
    auto tri = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const unsigned base = unsigned(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), {a, b, c});
        mesh.triangles.emplace_back(base, base + 1, base + 2);
    };
    tri({0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0});  // 0: a corner of the box, voxel (0,0,0) only
    tri({2, 2, 2}, {1.9f, 2, 2}, {2, 1.9f, 2});  // 1: the opposite corner, voxel (1,1,1) only
    // 2: in the plane x + y = 1.5. Its bounding box [0.1, 1.4]^2 x [0.2, 0.8] overlaps voxel
    // (1,1,0), where x + y >= 2: the triangle itself does not touch that voxel.
    tri({1.4f, 0.1f, 0.2f}, {0.1f, 1.4f, 0.2f}, {0.75f, 0.75f, 0.8f});
    tri({1, 0.2f, 0.2f}, {1, 0.8f, 0.2f}, {1, 0.2f, 0.8f});  // 3: on the face x = 1: both voxels
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = {2, 2, 2};
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const std::vector<std::vector<std::uint32_t>> expected = {{0, 2, 3}, {2, 3}, {2}, {}, {}, {}, {}, {1}};
    for (unsigned cell = 0; cell < 8; ++cell)
        EXPECT_EQ(std::vector<std::uint32_t>(grid.triangleList.begin() + grid.cellOffsets[cell],
                                             grid.triangleList.begin() + grid.cellOffsets[cell + 1]),
                  expected[cell])
            << "voxel " << cell;
}

TEST(GridBuild, StatsAreConsistentWithTheLayout) {
    const TriangleMesh mesh = christenSceneB();
    GridResolutionRule rule;
    rule.minDim = 16;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const GridStats& s = grid.stats;
    EXPECT_EQ(s.cells, grid.cellCount());
    EXPECT_EQ(s.references, grid.triangleList.size());
    EXPECT_EQ(grid.cellOffsets.back(), grid.triangleList.size());
    EXPECT_TRUE(std::is_sorted(grid.cellOffsets.begin(), grid.cellOffsets.end()));
    std::uint64_t empty = 0;
    std::uint32_t maxRefs = 0;
    for (std::size_t c = 0; c < s.cells; ++c) {
        const std::uint32_t n = grid.cellOffsets[c + 1] - grid.cellOffsets[c];
        empty += n == 0;
        maxRefs = std::max(maxRefs, n);
    }
    EXPECT_DOUBLE_EQ(s.emptyFraction, double(empty) / double(s.cells));
    EXPECT_EQ(s.maxReferencesInCell, maxRefs);
    EXPECT_EQ(s.bytes, (s.cells + 1) * 4 + s.references * 4 + mesh.triangles.size() * 48);
    EXPECT_GE(s.referencesPerTriangle, 1.0);  // every triangle lies in at least one voxel
    EXPECT_EQ(mesh.triangles.size(), 2004u);
}

TEST(GridBuild, RefusesMoreCellsThanTheLimit) {
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = {100, 100, 100};
    try {
        buildUniformGrid(christenSceneA(), rule, 1000);
        FAIL() << "expected an error";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "grid: resolution 100x100x100 = 1000000 cells exceeds the limit of 1000 cells");
    }
}

// Scene A at min_dim 32 has 43 cells along y over [0, 4]: 43 x fl(4/43) falls short of 4, and box
// 3's top face at y = 4 was once in no voxel at all (the exact reference found the rays that went
// through it). The voxels must cover the whole box, and every triangle must be listed.
TEST(GridBuild, VoxelsCoverTheWholeBoxAndListEveryTriangle) {
    const TriangleMesh mesh = christenSceneA();
    for (unsigned minDim : {4u, 7u, 13u, 32u, 43u, 100u}) {
        SCOPED_TRACE("min_dim " + std::to_string(minDim));
        GridResolutionRule rule;
        rule.minDim = minDim;
        const UniformGrid grid = buildUniformGrid(mesh, rule);
        const auto& r = grid.stats.resolution;
        const VoxelBox last = grid.voxelBounds(r[0] - 1, r[1] - 1, r[2] - 1);
        for (int a = 0; a < 3; ++a) EXPECT_GE(last.max[a], double(grid.params.boundsMax[a]));
        std::set<std::uint32_t> listed(grid.triangleList.begin(), grid.triangleList.end());
        EXPECT_EQ(listed.size(), mesh.triangles.size());
    }
}

}  // namespace
}  // namespace rtbench
