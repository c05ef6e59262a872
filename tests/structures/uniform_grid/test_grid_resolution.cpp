#include <gtest/gtest.h>

#include "core/error.h"
#include "structures/uniform_grid/uniform_grid.h"

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

TEST(GridResolution, MinDimRoundsToNearestNotDown) {
    GridResolutionRule rule;
    rule.minDim = 10;
    // 1.26 / 1 * 10 = 12.6: 13 cells (rounding down would give 12); 1.24 * 10 = 12.4: 12.
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {1.26f, 1.0f, 1.24f}), 1, rule), (Res{13, 10, 12}));
}

TEST(GridResolution, FlatAxisGetsOneCellAndMinDimAppliesToTheSmallestNonZeroExtent) {
    GridResolutionRule rule;
    rule.minDim = 4;
    // All triangles in the plane y = 0 (a 2 x 1 floor): y gets 1 cell, z (1) gets 4, x 8.
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {2, 0, 1}), 2, rule), (Res{8, 1, 4}));
    // Two zero extents: a segment along z.
    EXPECT_EQ(chooseGridResolution(box({1, 1, 0}, {1, 1, 3}), 2, rule), (Res{1, 1, 4}));
    // The grid box still gets a positive extent on the flat axis: 1e-4 of the largest.
    const Bounds3 flat = gridBounds(box({0, 0, 0}, {2, 0, 1}));
    EXPECT_NEAR(flat.extent().y, 2e-4f, 1e-6f);
}

TEST(GridResolution, DensityRuleUsesTheAreaOfAFlatBoxAndTheLengthOfALine) {
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Density;
    rule.cellsPerTriangle = 1.0;
    // 128 triangles on a 16 x 8 plane (z = 0): 128 square cells of side 1, not 93 per triangle.
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {16, 8, 0}), 128, rule), (Res{16, 8, 1}));
    // 50 triangles along a 10-long line in x: 50 cells of length 0.2.
    EXPECT_EQ(chooseGridResolution(box({0, 0, 0}, {10, 0, 0}), 50, rule), (Res{50, 1, 1}));
}

TEST(GridResolution, AResolutionTheKernelsCannotIndexIsAnErrorNamingIt) {
    GridResolutionRule rule;
    rule.minDim = 2048;
    // A sliver 2^21 times longer than it is wide: 2^32 cells along x would wrap to 0.
    try {
        chooseGridResolution(box({0, 0, 0}, {2097152.0f, 1.0f, 1.0f}), 1, rule);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("resolution 4294967296x2048x2048 has more than 2147483647 cells along x"),
                  std::string::npos)
            << e.what();
    }
}

TEST(GridResolution, ASinglePointOrASubnormalBoxIsAClearError) {
    GridResolutionRule rule;
    EXPECT_THROW(chooseGridResolution(box({1, 2, 3}, {1, 2, 3}), 1, rule), Error);
    try {
        gridBounds(box({0, 0, 0}, {1e-40f, 1e-40f, 1e-40f}));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("largest extent is at least 1.49e-08 (2^-26)"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace rtbench
