// Jittered camera rays (rays/jitter): each ray inside its pixel's footprint, worked out by hand
// for a 90-degree 2 x 2 camera; the same seed the same rays, another seed others; and whole runs
// judged against Embree and the exact reference, where the control (which makes the camera
// frame's rays itself) must refuse them rather than trace the lattice.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rays/jitter/jitter_rays.h"
#include "tests/harness/test_experiment.h"

namespace rtbench {
namespace {

using ::testing::HasSubstr;

// Eye at the origin looking down -z, up +y, 90 degrees: the image plane at distance 1 spans
// [-1, 1] on both axes, right = +x, down = -y, pixels 1 x 1. Pixel (x, y)'s ray has direction
// (dx, dy, -1) with dx in [x - 1, x] and dy in [-y, 1 - y] (row 0 is the top).
TEST(JitterRays, EachRayPassesThroughItsOwnPixel) {
    PinholeCamera camera;
    camera.position = glm::vec3(0.0f);
    camera.lookAt = glm::vec3(0.0f, 0.0f, -1.0f);
    camera.verticalFovDegrees = 90.0f;
    const CameraFrame frame = cameraFrame(camera, 2, 2);
    const float eps = 1e-6f;
    int leftOfCentre = 0, rightOfCentre = 0;
    for (std::uint32_t seed = 0; seed < 50; ++seed)
        for (unsigned y = 0; y < 2; ++y)
            for (unsigned x = 0; x < 2; ++x) {
                const gpu::Ray ray = jitteredRay(frame, x, y, seed);
                const glm::vec3 d(ray.directionTMax);
                EXPECT_EQ(glm::vec3(ray.originTMin), glm::vec3(0.0f));
                EXPECT_NEAR(d.z, -1.0f, eps);
                EXPECT_GE(d.x, float(x) - 1.0f - eps);
                EXPECT_LE(d.x, float(x) + eps);
                EXPECT_GE(d.y, -float(y) - eps);
                EXPECT_LE(d.y, 1.0f - float(y) + eps);
                const float centreX = float(x) - 0.5f;
                leftOfCentre += d.x < centreX;
                rightOfCentre += d.x > centreX;
            }
    // 200 draws: both halves of the pixels are sampled, none stays at the centre.
    EXPECT_GT(leftOfCentre, 60);
    EXPECT_GT(rightOfCentre, 60);
}

TEST(JitterRays, TheSeedChoosesTheRays) {
    const CameraFrame frame = cameraFrame(PinholeCamera{}, 8, 6);
    for (unsigned y = 0; y < 6; ++y)
        for (unsigned x = 0; x < 8; ++x) {
            const gpu::Ray a = jitteredRay(frame, x, y, 7), b = jitteredRay(frame, x, y, 7), c = jitteredRay(frame, x, y, 8);
            EXPECT_EQ(glm::vec3(a.directionTMax), glm::vec3(b.directionTMax));
            EXPECT_NE(glm::vec3(a.directionTMax), glm::vec3(c.directionTMax));
            EXPECT_NE(glm::vec3(a.directionTMax), glm::vec3(primaryRay(frame, x, y).directionTMax));
        }
}

// Scene B over the grid: jittered rays traced by branching and by the wavefront (which reads the
// batch as the camera generation of a path) agree with Embree and the exact reference; the control
// fails the run naming why, as it must not trace the frame's centre rays in their place.
TEST(JitterRays, RunsAreJudgedAndTheControlRefusesThem) {
    TempDir dir;
    const ExperimentResult result = runTestConfig(
        dir, "jitter",
        "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 24\nheight = 16\nposition = [0, 3, 9.5]\n"
        "look_at = [0, 2.5, 0]\n[structure]\ntype = \"uniform_grid\"\n[strategy]\ntype = [\"branching\", \"wavefront\", \"control\"]\n"
        "[rays]\ntype = \"jitter\"\n[jitter]\nseed = 3\n");
    ASSERT_EQ(result.rows.size(), 3u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        if (row.at("strategy_type") == "control") {
            EXPECT_EQ(row.at("status"), "failed");
            EXPECT_THAT(row.at("error"), HasSubstr("makes the camera rays itself"));
            continue;
        }
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        EXPECT_EQ(row.at("rays"), "384");
        EXPECT_EQ(row.at("exact_false_misses"), "0");
        EXPECT_EQ(row.at("exact_false_hits"), "0");
        EXPECT_EQ(row.at("exact_wrong_primitive"), "0");
        EXPECT_EQ(row.at("jitter_seed"), "3");
    }
}

}  // namespace
}  // namespace rtbench
