// The sorted-rays variant of branching (strategies/sorted): the order by hand (octant first, then
// the origin's Morton code, ties in the batch's order), and whole runs beside branching on the same
// rays, where every exact count but the lanes' must be the same and the hits come back in order.
#include <gtest/gtest.h>

#include <set>

#include "harness/columns.h"
#include "strategies/sorted/sorted_strategy.h"
#include "tests/harness/test_experiment.h"

namespace rtbench {
namespace {

gpu::Ray ray(glm::vec3 origin, glm::vec3 direction) {
    return {glm::vec4(origin, 0.0f), glm::vec4(direction, 1e30f)};
}

// Octant before origin: a ray heading -x with the smallest origin code comes after one heading +x
// with the largest (the key's octant is its bits 30-32, above the 30-bit code); equal keys keep
// the batch's order.
TEST(Sorted, OctantComesFirstThenTheOriginAndTiesKeepTheirOrder) {
    const std::vector<gpu::Ray> rays = {
        ray({0, 0, 0}, {-1, 0, 0}),  // octant 4 (x < 0), code 0
        ray({1, 1, 1}, {1, 0, 0}),   // octant 0, the box's far corner: the largest code
        ray({0, 0, 0}, {1, 0, 0}),   // octant 0, code 0
        ray({0, 0, 0}, {1, 1, 1}),   // the same key as ray 2: after it
        ray({0, 0, 0}, {0, -1, 0}),  // octant 2 (y < 0)
        ray({0, 0, 0}, {0, 0, -1}),  // octant 1 (z < 0)
    };
    EXPECT_EQ(coherentOrder(rays), (std::vector<std::uint32_t>{2, 3, 1, 5, 4, 0}));
}

// The Morton code interleaves z, y, x from the lowest bit: along each axis alone, one cell up
// orders z < y < x; a cell up on every axis is past all three.
TEST(Sorted, TheOriginCodeInterleavesZYX) {
    const glm::vec3 d(1, 1, 1);
    const float cell = 1.0f / 1024.0f;  // the box [0, 1]^3 made by the first and last ray
    const std::vector<gpu::Ray> rays = {ray({0, 0, 0}, d),           ray({1, 1, 1}, d),
                                        ray({1.5f * cell, 0, 0}, d), ray({0, 1.5f * cell, 0}, d),
                                        ray({0, 0, 1.5f * cell}, d), ray({1.5f * cell, 1.5f * cell, 1.5f * cell}, d)};
    EXPECT_EQ(coherentOrder(rays), (std::vector<std::uint32_t>{0, 4, 3, 2, 5, 1}));
}

TEST(Sorted, NoRaysAndOneOriginAreTheirOwnOrder) {
    EXPECT_TRUE(coherentOrder({}).empty());
    const std::vector<gpu::Ray> same(5, ray({2, 3, 4}, {0.5f, 0.5f, 0.5f}));
    EXPECT_EQ(coherentOrder(same), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
}

// Reflection and path rays of scene B over the grid and the BVH: sorted beside branching on the
// same batch. Both are ok (judged against Embree and the exact reference in the batch's order, so
// a hit put back at the wrong ray fails), and every exact column is the same but the lane model's
// and the device's lane utilisation, which the order changes, and the sort's own.
TEST(Sorted, TracesTheBatchAsBranchingDoesInAnotherOrder) {
    TempDir dir;
    const ExperimentResult result = runTestConfig(
        dir, "sorted",
        "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 48\nheight = 32\nposition = [0, 3, 9.5]\n"
        "look_at = [0, 2.5, 0]\n[structure]\ntype = [\"uniform_grid\", \"bvh\"]\n[strategy]\ntype = [\"branching\", \"sorted\"]\n"
        "[rays]\ntype = [\"reflection\", \"path\"]\n");
    ASSERT_EQ(result.rows.size(), 8u);
    const std::set<std::string> byOrder = {"lanes_model_slots", "lanes_model_active", "simd_efficiency", "simd_lane_utilisation",
                                           "sorted_rays_moved"};
    int laneChanges = 0;
    for (std::size_t i = 0; i < 8; i += 4)
        for (std::size_t r = 0; r < 2; ++r) {
            const Row& branching = result.rows[i + r];
            const Row& sorted = result.rows[i + 2 + r];
            SCOPED_TRACE(sorted.at("label"));
            ASSERT_EQ(branching.at("status"), "ok") << branching.at("error");
            ASSERT_EQ(sorted.at("status"), "ok") << sorted.at("error");
            EXPECT_NE(cellText(sorted, "sorted_rays_moved"), "0");
            for (const ColumnSpec& column : runColumnSpecs()) {
                if (column.kind != ColumnKind::Exact || byOrder.count(column.name)) continue;
                EXPECT_EQ(cellText(sorted, column.name), cellText(branching, column.name)) << column.name;
            }
            laneChanges += cellText(sorted, "simd_lane_utilisation") != cellText(branching, "simd_lane_utilisation");
        }
    EXPECT_GT(laneChanges, 0) << "the order changed no subgroup's lanes: is the batch traced sorted?";
}

}  // namespace
}  // namespace rtbench
