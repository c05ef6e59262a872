// The median-split BVH: its tree worked out by hand (splits, leaves, boxes, SAH cost), ties split
// by triangle id, well formed on the test scenes, and traced by every kind of strategy as the
// BVH's kernels trace Embree's tree, judged against Embree and the exact reference.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>

#include "core/error.h"
#include "harness/columns.h"
#include "scene/procedural.h"
#include "structures/median_bvh/median_bvh_build.h"
#include "tests/harness/test_experiment.h"
#include "tests/structures/bvh/flat_bvh_checks.h"

namespace rtbench {
namespace {

// n right triangles in the plane z = 0, triangle i spanning x in [i, i + 1] and y in [0, 1],
// listed in the order `order` gives.
TriangleMesh row(const std::vector<int>& order) {
    TriangleMesh mesh;
    mesh.name = "row";
    for (int i : order) {
        const glm::uint v = glm::uint(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), {{float(i), 0, 0}, {float(i + 1), 0, 0}, {float(i), 1, 0}});
        mesh.triangles.push_back({v, v + 1, v + 2});
    }
    return mesh;
}

// Eight triangles in a row, listed out of order, leaves of two: the root splits x at 4, its
// children at 2 and 6. Boxes of width w have area 2w (height 1, depth 0): the root 16, inner
// children 8, leaves 4. SAH cost = (16 + 8 + 8) / 16 + 4 leaves * 2 triangles * 4 / 16 = 4.
TEST(MedianBvh, EightInARowSplitAtTheMediansByHand) {
    const std::vector<int> order = {5, 0, 7, 2, 4, 1, 6, 3};  // triangle id t lies at x = order[t]
    const FlatBvh bvh = buildMedianBvh(row(order), 2);
    ASSERT_EQ(bvh.nodes.size(), 3u);
    EXPECT_EQ(bvh.stats.leaves, 4u);
    EXPECT_EQ(bvh.stats.depth, 2u);
    EXPECT_EQ(bvh.stats.largestLeaf, 2u);
    EXPECT_DOUBLE_EQ(bvh.stats.sahCost, 4.0);
    // Depth first, child 0 (lower x) first; each leaf's ids ascending: x 0 and 1 are ids 1 and 5,
    // x 2 and 3 ids 7 and 3, x 4 and 5 ids 4 and 0, x 6 and 7 ids 6 and 2.
    EXPECT_EQ(bvh.triangleList, (std::vector<std::uint32_t>{1, 5, 3, 7, 0, 4, 2, 6}));
    const gpu::BvhNode& root = bvh.nodes[0];
    EXPECT_EQ(root.children.x, 1u);
    EXPECT_EQ(root.children.y, 2u);
    EXPECT_EQ(glm::vec3(root.min0), glm::vec3(0, 0, 0));
    EXPECT_EQ(glm::vec3(root.max0), glm::vec3(4, 1, 0));
    EXPECT_EQ(glm::vec3(root.min1), glm::vec3(4, 0, 0));
    EXPECT_EQ(glm::vec3(root.max1), glm::vec3(8, 1, 0));
    const gpu::BvhNode& upper = bvh.nodes[2];
    EXPECT_EQ(glm::vec3(upper.min0), glm::vec3(4, 0, 0));
    EXPECT_EQ(glm::vec3(upper.max1), glm::vec3(8, 1, 0));
    EXPECT_EQ(upper.children.x, gpu::kBvhLeaf | (1u << 24) | 4u) << "two triangles from list entry 4";
    EXPECT_EQ(upper.children.y, gpu::kBvhLeaf | (1u << 24) | 6u);
}

// A triangle 8 wide (box centre x = 4) among unit ones at x = 1, 2 and 5 (centres 1.5, 2.5, 5.5):
// by centre the halves are {1, 2} and {0, 3}; by the boxes' lower corners they would be {0, 1} and {2, 3}.
TEST(MedianBvh, TrianglesGoByTheirBoxCentres) {
    TriangleMesh mesh = row({1, 2, 5});
    const glm::uint v = glm::uint(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {{0, 0, 0}, {8, 0, 0}, {0, 1, 0}});
    mesh.triangles.insert(mesh.triangles.begin(), {v, v + 1, v + 2});  // id 0; the unit ones are ids 1 to 3
    const FlatBvh bvh = buildMedianBvh(mesh, 2);
    EXPECT_EQ(bvh.triangleList, (std::vector<std::uint32_t>{1, 2, 0, 3}));
}

// Five copies of one triangle: every centroid ties, so the split goes by id (2 | 3, then 1 | 2),
// the same on any machine; a scene within one leaf is a root with a single child.
TEST(MedianBvh, TiesSplitByTriangleIdAndOneLeafIsTheRootsOnlyChild) {
    const FlatBvh ties = buildMedianBvh(row({0, 0, 0, 0, 0}), 2);
    EXPECT_EQ(ties.triangleList, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(ties.stats.leaves, 3u);
    EXPECT_EQ(ties.nodes[0].children.x, gpu::kBvhLeaf | (1u << 24) | 0u);
    const FlatBvh one = buildMedianBvh(row({1, 0}), 4);
    ASSERT_EQ(one.nodes.size(), 1u);
    EXPECT_EQ(one.nodes[0].children.x, gpu::kBvhLeaf | (1u << 24) | 0u);
    EXPECT_EQ(one.nodes[0].children.y, gpu::kBvhNone);
    EXPECT_THROW(buildMedianBvh(row({}), 4), Error);
    EXPECT_THROW(buildMedianBvh(row({0}), 0), Error);
}

TEST(MedianBvh, EveryTriangleOnceInsideItsBoxesWithinTheLeafSize) {
    for (const TriangleMesh& mesh : {christenSceneA(), christenSceneB()})
        for (unsigned leaf : {1u, 4u, 16u}) {
            SCOPED_TRACE(mesh.name + " leaf " + std::to_string(leaf));
            const FlatBvh bvh = buildMedianBvh(mesh, leaf);
            expectWellFormed(bvh, mesh, leaf);
            const FlatBvh again = buildMedianBvh(mesh, leaf);
            EXPECT_EQ(again.triangleList, bvh.triangleList) << "the same tree built twice";
            ASSERT_EQ(again.nodes.size(), bvh.nodes.size());
            EXPECT_EQ(std::memcmp(again.nodes.data(), bvh.nodes.data(), bvh.nodes.size() * sizeof(gpu::BvhNode)), 0);
        }
}

// Scene B's camera and shadow rays over the median tree, traced by a kernel per ray (branching),
// by passes (multipass) and by the CPU: each ok, judged against Embree and the exact reference.
TEST(MedianBvh, EveryKindOfStrategyTracesItAgainstTheReferences) {
    TempDir dir;
    const ExperimentResult result = runTestConfig(
        dir, "median",
        "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 24\nheight = 16\nposition = [0, 3, 9.5]\n"
        "look_at = [0, 2.5, 0]\n[structure]\ntype = \"median_bvh\"\nleaf_size = 2\n[strategy]\n"
        "type = [\"branching\", \"multipass\", \"cpu\"]\n[rays]\ntype = [\"primary\", \"shadow\"]\n");
    ASSERT_EQ(result.rows.size(), 6u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        EXPECT_EQ(row.at("status"), "ok") << cellText(row, "error");
        EXPECT_EQ(cellText(row, "exact_wrong_ppm"), "0");
        EXPECT_EQ(cellText(row, "hit_miss_mismatches"), "0") << "Embree hit where it missed, or missed where it hit";
        // Any-hit queries (shadow rays) may end on any triangle: only the closest hit names one.
        if (cellText(row, "rays_type") == "primary") EXPECT_EQ(cellText(row, "primitive_mismatches"), "0") << "Embree hit another triangle";
        EXPECT_EQ(cellText(row, "bvh_largest_leaf"), "2");
    }
}

}  // namespace
}  // namespace rtbench
