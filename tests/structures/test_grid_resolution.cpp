#include <gtest/gtest.h>

#include "structures/uniform_grid.h"

namespace rtbench {
namespace {

Bounds3 box(glm::vec3 lo, glm::vec3 hi) {
    Bounds3 b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

using Res = std::array<unsigned, 3>;

TEST(GridResolution, MinDimGivesSmallestExtentThatManyCellsAndScalesTheOthers) {
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::MinDim;
    rule.minDim = 8;
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {1, 2, 4}), 100, rule), (Res{8, 16, 32}));
    rule.minDim = 10;
    // 1.5 / 1 * 10 = 15; 3.33 / 1 * 10 = 33.3 -> 33 (rounded, voxels stay near cubic)
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {1.5f, 1.0f, 3.33f}), 100, rule), (Res{15, 10, 33}));
    // The smallest extent may be on any axis.
    EXPECT_EQ(chooseGridResolution(box({-2, -1, 5}, {2, 7, 5.5f}), 1, rule), (Res{80, 160, 10}));
}

TEST(GridResolution, EveryAxisGetsAtLeastOneCell) {
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Density;
    rule.cellsPerTriangle = 0.001;
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {1, 1, 1}), 10, rule), (Res{1, 1, 1}));
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = {0, 3, 0};
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {1, 1, 1}), 10, rule), (Res{1, 3, 1}));
}

TEST(GridResolution, DensityRuleUsesTheCubeRootOfVolumePerCell) {
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Density;
    rule.cellsPerTriangle = 1.0;
    // 1000 cells in a 2x2x2 box: cell size cbrt(8 / 1000) = 0.2 -> 10 per axis.
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {2, 2, 2}), 1000, rule), (Res{10, 10, 10}));
    // 2 cells per triangle, 4000 triangles in a 1x2x4 box: cell size cbrt(8 / 8000) = 0.1.
    rule.cellsPerTriangle = 2.0;
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {1, 2, 4}), 4000, rule), (Res{10, 20, 40}));
}

TEST(GridResolution, FlatSceneBoxIsWidenedSoEveryAxisHasExtent) {
    const Bounds3 flat = gridBounds(box({0, 0, 0}, {2, 0, 1}));
    EXPECT_GT(flat.extent().y, 0.0f);
    EXPECT_NEAR(flat.extent().y, 2e-4f, 1e-6f);
    GridResolutionRule rule;
    rule.minDim = 4;
    const Res res = chooseGridResolution(flat, 2, rule);
    EXPECT_EQ(res[1], 4u);  // the flat axis is the smallest extent
    EXPECT_EQ(res[0], 40000u);
}

}  // namespace
}  // namespace rtbench
