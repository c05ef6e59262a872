// The pinhole camera's rays against hand-computed directions: a 90-degree vertical field of view
// (half height tan 45 = 1) on a 4 x 2 image, whose half width is the aspect ratio times that, 2.
#include <gtest/gtest.h>

#include "scene/camera.h"

namespace rtbench {
namespace {

TEST(Camera, RaysOfANonSquareImageSpanItsAspectRatio) {
    PinholeCamera camera;
    camera.position = glm::vec3(0.0f);
    camera.lookAt = glm::vec3(0.0f, 0.0f, -1.0f);
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.verticalFovDegrees = 90.0f;
    const std::vector<gpu::Ray> rays = generatePrimaryRays(camera, 4, 2);
    ASSERT_EQ(rays.size(), 8u);
    // Pixel (x, y) centre: sx = (2 (x + 0.5) / 4 - 1) * 2, sy = (2 (y + 0.5) / 2 - 1) * 1;
    // direction = forward (0, 0, -1) + sx right (1, 0, 0) + sy down (0, -1, 0).
    const float expected[8][2] = {{-1.5f, 0.5f}, {-0.5f, 0.5f}, {0.5f, 0.5f}, {1.5f, 0.5f},
                                  {-1.5f, -0.5f}, {-0.5f, -0.5f}, {0.5f, -0.5f}, {1.5f, -0.5f}};
    for (std::size_t i = 0; i < rays.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_NEAR(rays[i].directionTMax.x, expected[i][0], 1e-6f);
        EXPECT_NEAR(rays[i].directionTMax.y, expected[i][1], 1e-6f);
        EXPECT_FLOAT_EQ(rays[i].directionTMax.z, -1.0f);
        EXPECT_EQ(rays[i].originTMin, glm::vec4(0.0f));
    }
}

}  // namespace
}  // namespace rtbench
