// The cost model (structures/cost_model.h) on hand-computed cases, and structure.type = auto choosing
// by it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "device/vulkan_context.h"
#include "structures/auto/auto_structure.h"
#include "structures/brute_force/brute_structure.h"
#include "structures/cost_model.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "scene/procedural.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;
using ::testing::Not;

gpu::Ray ray(glm::vec3 o, glm::vec3 d) { return {glm::vec4(o, 0.0f), glm::vec4(d, gpu::kNoHitT)}; }

TEST(CostModel, SurfaceAreaAndRaysEnteringABox) {
    EXPECT_DOUBLE_EQ(surfaceArea({0, 0, 0}, {1, 2, 3}), 2.0 * (2 + 6 + 3));
    EXPECT_DOUBLE_EQ(surfaceArea({1, 1, 1}, {0, 0, 0}), 0.0);  // inverted: empty
    const std::vector<gpu::Ray> rays = {
        ray({-1, 0.5f, 0.5f}, {1, 0, 0}),   // through the box
        ray({-1, 2.0f, 0.5f}, {1, 0, 0}),   // beside it
        ray({0.5f, 0.5f, 0.5f}, {0, 0, 1}), // from inside
        ray({2, 0.5f, 0.5f}, {1, 0, 0}),    // away from it
        ray({-1, 1.0f, 0.5f}, {1, 0, 0}),   // along its top face: the closed box is met
    };
    EXPECT_EQ(raysEnteringBox(rays, {0, 0, 0}, {1, 1, 1}), 3u);
}

// A 1x1x1 grid: a line through the box crosses its one voxel (cells x A_cell / A_box = 1) and
// tests every reference; brute force tests every triangle on every ray, hitting the box or not.
TEST(CostModel, PredictionsOfAOneVoxelGridAndOfBruteForce) {
    const TriangleMesh mesh = christenSceneA();  // 36 triangles
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = {1, 1, 1};
    const std::unique_ptr<Structure> grid = gridStructure(buildUniformGrid(mesh, rule));
    const Bounds3 box = mesh.bounds();
    const glm::vec3 centre = 0.5f * (box.min + box.max);
    const std::vector<gpu::Ray> rays = {ray(centre - glm::vec3(0, 0, 100), {0, 0, 1}),
                                        ray(centre + glm::vec3(0, 1000, 0), {1, 0, 0})};  // misses
    EXPECT_NEAR(grid->predictedWork(rays), 1.0 * (1 + 36), 1e-9);
    RunConfig run;
    run.values["structure.max_tests"] = 1e9;
    DeviceInfo device;
    device.maxStorageBufferRange = 1u << 27;
    EXPECT_DOUBLE_EQ(bruteStructureType().build(mesh, rays, run, device)->predictedWork(rays), 2.0 * 36);
}

TEST(AutoStructure, BuildsEveryCandidateAndRunsTheOneWithTheLeastPredictedWork) {
    const TriangleMesh mesh = christenSceneB();
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 2000, 9);
    RunConfig run;
    run.values["baseline.embree_config"] = std::string("");
    DeviceInfo device;
    device.maxStorageBufferRange = 1u << 27;
    const std::unique_ptr<Structure> chosen = autoStructureType().build(mesh, rays, run, device);
    Row row;
    chosen->writeColumns(row);
    // Scene B: 2,004 triangles. Brute force predicts 2,004 tests per ray; the BVH's SAH far less.
    EXPECT_THAT(row.at("auto_predictions"), HasSubstr("brute_force=2004"));
    EXPECT_THAT(row.at("auto_predictions"), Not(HasSubstr("median_bvh"))) << "not a candidate";
    EXPECT_THAT(row.at("auto_predictions"), HasSubstr("uniform_grid="));
    EXPECT_EQ(row.at("auto_choice"), "bvh");
    EXPECT_EQ(chosen->kernelPrefix(), "bvh");
    // Brute force over its limit is refused, and the choice is among the others.
    run.values["structure.max_tests"] = 1.0;  // ignored: auto gives each candidate its default keys
    const std::vector<gpu::Ray> many(2'100'000, rays.front());  // 2.1e6 x 2004 > 4e9 default max_tests
    Row manyRow;
    autoStructureType().build(mesh, many, run, device)->writeColumns(manyRow);
    EXPECT_THAT(manyRow.at("auto_predictions"), HasSubstr("brute_force=refused"));
}

}  // namespace
}  // namespace rtbench
