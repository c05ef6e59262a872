// The control (strategies/control): a plain grid ray caster that makes its own camera rays. What
// can disagree with it: a scene whose answers are derived by hand, the branching kernel and the
// CPU reference on the same rays (separate source: the control shares no GLSL with them), the
// host's camera rays (its rays are made on the device), and hand-made records for its helpers.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "scene/camera.h"
#include "scene/procedural.h"
#include "strategies/control/control_strategy.h"
#include "harness/writers.h"
#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/harness/test_experiment.h"
#include "tests/methods/hand_scenes.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {

using ::testing::HasSubstr;

TEST(Control, HitPointMismatchesComparesDistanceAndTriangleOnly) {
    gpu::HitRecord a{};
    a.t = 1.0f;
    a.primitive = 3;
    std::vector<gpu::HitRecord> left(4, a), right(4, a);
    right[0].u = 0.5f;  // the control writes no barycentrics: not a difference
    right[0].cellsVisited = 9;
    right[1].t = std::nextafter(1.0f, 2.0f);
    right[2].primitive = 4;
    right[3].t = 0.5f;
    right[3].primitive = 1;
    EXPECT_EQ(hitPointMismatches(left, right), 3u);
    EXPECT_THROW(hitPointMismatches(left, std::vector<gpu::HitRecord>(3, a)), Error);
}

// A 12 x 9 image is 2 x 2 tiles (the right and bottom ones partial); each record's voxels and
// tests add to its tile's bound.
TEST(Control, LoopBoundSumsEachTilesWork) {
    std::vector<gpu::HitRecord> records(12 * 9, gpu::HitRecord{});
    records[0].cellsVisited = 5;                 // (0, 0): tile 0
    records[7].trianglesTested = 6;              // (7, 0): tile 0
    records[8].cellsVisited = 20;                // (8, 0): tile 1
    records[8 * 12 + 11].trianglesTested = 30;   // (11, 8): tile 3
    records[8 * 12 + 11].cellsVisited = 2;
    EXPECT_EQ(controlLoopBound(records, 12, 9), 32u);
    records[7 * 12 + 7].cellsVisited = 22;       // (7, 7): tile 0 now 33
    EXPECT_EQ(controlLoopBound(records, 12, 9), 33u);
    EXPECT_THROW(controlLoopBound(records, 12, 8), Error);
}

// The camera frame makes the rays generatePrimaryRays made before it existed: checked against
// the pinhole's formula written out here (tests/scene/test_camera.cpp has the hand's values).
TEST(Control, CameraFrameMakesThePinholesRays) {
    PinholeCamera camera;
    camera.position = glm::vec3(1.0f, 2.0f, 3.0f);
    camera.lookAt = glm::vec3(0.5f, -1.0f, -4.0f);
    const CameraFrame frame = cameraFrame(camera, 7, 5);
    const std::vector<gpu::Ray> rays = generatePrimaryRays(camera, 7, 5);
    const glm::vec3 w = glm::normalize(camera.lookAt - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(w, camera.up));
    const float halfHeight = std::tan(glm::radians(22.5f)), halfWidth = halfHeight * 7.0f / 5.0f;
    for (unsigned y = 0; y < 5; ++y)
        for (unsigned x = 0; x < 7; ++x) {
            const float sx = (2.0f * (float(x) + 0.5f) / 7.0f - 1.0f) * halfWidth;
            const float sy = (2.0f * (float(y) + 0.5f) / 5.0f - 1.0f) * halfHeight;
            const glm::vec3 d = w + sx * right + sy * glm::cross(w, right);
            EXPECT_EQ(glm::vec3(rays[y * 7 + x].directionTMax), d) << x << ", " << y;
            EXPECT_EQ(glm::vec4(rays[y * 7 + x].originTMin), glm::vec4(camera.position, 0.0f));
        }
    EXPECT_EQ(frame.width(), 7u);
    EXPECT_EQ(frame.height(), 5u);
}

class ControlKernel : public VulkanTest {
protected:
    // The control over `grid` on a width x height image of `camera`, and the same camera rays.
    StrategyRun run(const Structure& grid, const PinholeCamera& camera, unsigned width, unsigned height, Row& row,
                    unsigned workgroupSize = 64) {
        batch_ = RayBatch{generatePrimaryRays(camera, width, height)};
        batch_.camera = std::make_shared<const CameraFrame>(cameraFrame(camera, width, height));
        return batchTracer(controlStrategyType())(*vk_, grid, batch_, RunConfig{}, {workgroupSize, 0, 1}, row);
    }
    RayBatch batch_;
};

// Looking down -z from the origin, 90 degrees, 16 x 16: ray (x, y) has direction
// (sx, -sy, -1) with sx, sy in +-{1, 3, ..., 15} / 16. Triangle 0 at z = -2 covers the whole view
// (its edges pass X = -+4 at Y = 2); triangle 1 behind it at z = -3; triangles 2 and 3 at z = -1
// make the rectangle X in [-10, 0], their diagonal outside the view, so the left half (sx < 0,
// x < 8) hits triangle 2 at t = 1, the right half triangle 0 at t = 2.
TEST_F(ControlKernel, HandSceneHitsTheNearestTriangleOfEachPixel) {
    const TriangleMesh mesh = hand::meshOf({{glm::vec3(-10, -10, -2), glm::vec3(10, -10, -2), glm::vec3(0, 10, -2)},
                                            {glm::vec3(-10, -10, -3), glm::vec3(10, -10, -3), glm::vec3(0, 10, -3)},
                                            {glm::vec3(-10, -10, -1), glm::vec3(0, -10, -1), glm::vec3(0, 10, -1)},
                                            {glm::vec3(-10, -10, -1), glm::vec3(0, 10, -1), glm::vec3(-10, 10, -1)}});
    PinholeCamera camera;
    camera.position = glm::vec3(0.0f);
    camera.lookAt = glm::vec3(0.0f, 0.0f, -1.0f);
    camera.verticalFovDegrees = 90.0f;
    const std::vector<std::array<unsigned, 3>> resolutions = {{1, 1, 1}, {4, 4, 3}, {9, 7, 5}};
    for (const std::array<unsigned, 3>& resolution : resolutions) {
        SCOPED_TRACE(resolution[0]);
        const std::unique_ptr<Structure> grid = gridStructure(hand::gridOf(mesh, resolution));
        Row row;
        const StrategyRun control = run(*grid, camera, 16, 16, row);
        ASSERT_EQ(control.hits.size(), 256u);
        for (unsigned y = 0; y < 16; ++y)
            for (unsigned x = 0; x < 16; ++x) {
                const gpu::HitRecord& h = control.hits[y * 16 + x];
                EXPECT_EQ(h.primitive, x < 8 ? 2u : 0u) << x << ", " << y;
                EXPECT_NEAR(h.t, x < 8 ? 1.0f : 2.0f, 1e-6f) << x << ", " << y;
            }
        EXPECT_EQ(row.at("control_cpu_differing"), "0");
        EXPECT_EQ(control.metrics.work.hits, 256u);
    }
}

// Scene B (inside and outside its grid's box) and scene A on an image that is no whole number of
// tiles: the control's (t, triangle) are the branching kernel's and the CPU reference's, ray for
// ray, where the device divides as IEEE does (llvmpipe); and the same again on a second dispatch.
TEST_F(ControlKernel, TracesTheBranchingKernelsHitsOnTheSameRays) {
    if (vk_->info().name.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "the device's division is its own";
    for (const char* scene : {"christen_a", "christen_b"}) {
        const TriangleMesh mesh = proceduralScene(scene);
        const std::optional<PinholeCamera> inside = proceduralCamera(scene, 45.0f);
        for (const PinholeCamera& camera : {fitCamera(mesh.bounds()), inside.value_or(fitCamera(mesh.bounds()))})
            for (unsigned minDim : {4u, 16u}) {
                SCOPED_TRACE(std::string(scene) + " min_dim " + std::to_string(minDim));
                GridResolutionRule rule;
                rule.minDim = minDim;
                const std::unique_ptr<Structure> grid = gridStructure(buildUniformGrid(mesh, rule));
                Row row;
                const StrategyRun control = run(*grid, camera, 37, 21, row);
                const std::vector<gpu::HitRecord> branching = runBranching(*vk_, *grid, batch_.rays, {64, 0, 1}).hits;
                EXPECT_EQ(hitPointMismatches(control.hits, branching), 0u);
                EXPECT_EQ(row.at("control_cpu_differing"), "0");
                EXPECT_GT(control.metrics.work.hits, 0u);
                EXPECT_NO_THROW(control.timer->time(0, 1));
                EXPECT_NO_THROW(control.timer->checkHits());
            }
    }
}

TEST_F(ControlKernel, RefusesWhatItDoesNotTrace) {
    const TriangleMesh mesh = proceduralScene("christen_a");
    const std::unique_ptr<Structure> grid = gridStructure(hand::gridOf(mesh, {4, 4, 4}));
    const PinholeCamera camera = fitCamera(mesh.bounds());
    Row row;
    EXPECT_THAT(errorOf([&] { run(*grid, camera, 16, 16, row, 32); }), HasSubstr("strategy.workgroup_size = 32"));
    RayBatch notCamera{generatePrimaryRays(camera, 16, 16)};  // no frame: other rays, or tiles
    EXPECT_THAT(errorOf([&] { batchTracer(controlStrategyType())(*vk_, *grid, notCamera, RunConfig{}, {64, 0, 1}, row); }),
                HasSubstr("rays.type = primary, without camera.tile"));
    RayBatch any = notCamera;
    any.camera = std::make_shared<const CameraFrame>(cameraFrame(camera, 16, 16));
    any.query = gpu::kQueryAny;
    EXPECT_THAT(errorOf([&] { batchTracer(controlStrategyType())(*vk_, *grid, any, RunConfig{}, {64, 0, 1}, row); }),
                HasSubstr("closest-hit queries only"));
    RayBatch other = notCamera;
    other.camera = std::make_shared<const CameraFrame>(cameraFrame(camera, 16, 16));
    other.rays[5].directionTMax.x += 1.0f;  // not the frame's ray
    EXPECT_THAT(errorOf([&] { batchTracer(controlStrategyType())(*vk_, *grid, other, RunConfig{}, {64, 0, 1}, row); }),
                HasSubstr("does not make the batch's rays"));
    grid->setTriangleTest(gpu::kTriangleTestWatertight);
    EXPECT_THAT(errorOf([&] { run(*grid, camera, 16, 16, row); }), HasSubstr("Moller-Trumbore only"));
}

// Through the runner: a sweep of branching and the control on the camera rays of scene B, both
// ok; the control's shadow-ray run fails naming why.
TEST(ControlRuns, RunBesideBranchingThroughTheRunner) {
    TempDir dir;
    const ExperimentResult result = runTestConfig(
        dir, "control", "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 40\nheight = 30\n"
                        "[structure]\nmin_dim = 8\n[strategy]\ntype = [\"branching\", \"control\"]\n"
                        "[rays]\ntype = [\"primary\", \"shadow\"]\n");
    ASSERT_EQ(result.rows.size(), 4u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        const bool control = row.at("label").find("control") != std::string::npos;
        const bool shadow = row.at("label").find("shadow") != std::string::npos;
        if (control && shadow) {
            EXPECT_EQ(row.at("status"), "failed");
            EXPECT_THAT(row.at("error"), HasSubstr("makes the camera rays itself"));
            continue;
        }
        EXPECT_EQ(row.at("status"), "ok") << row.at("error");
        if (control) {
            EXPECT_EQ(cellText(row, "cpu_reference_mismatches"), "");
        }
    }
}

}  // namespace
}  // namespace rtbench
