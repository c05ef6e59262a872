// Scenes and rays outside the range every method handles (scene/scene_limits.h) are
// refused with that range named, before a grid, a camera fit or Embree sees them.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/camera.h"
#include "scene/procedural.h"
#include "scene/scene_limits.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "tests/error_of.h"

namespace rtbench {
namespace {

TriangleMesh tetrahedron(float scale) {
    TriangleMesh m;
    m.name = "tetrahedron";
    m.vertices = {glm::vec3(0, 0, 0) * scale, glm::vec3(1, 0, 0) * scale, glm::vec3(0, 1, 0) * scale,
                  glm::vec3(0, 0, 1) * scale};
    m.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    return m;
}

TEST(SceneLimits, AHugeSceneIsRefusedWithTheRangeNamed) {
    const std::string e = errorOf([] { validateSceneRange(tetrahedron(1e18f)); });
    EXPECT_NE(e.find("scene tetrahedron: vertex (1e+18, 0, 0) is out of range: the methods handle vertex coordinates "
                     "within +-2.749e+11 (2^38)"),
              std::string::npos)
        << e;
    validateSceneRange(tetrahedron(1e11f));  // inside the range
}

TEST(SceneLimits, ATinyTetrahedronIsAnErrorNotAHang) {
    GridResolutionRule rule;
    const std::string e = errorOf([&] { buildUniformGrid(tetrahedron(1e-40f), rule); });
    EXPECT_NE(e.find("its box is 1e-40 x 1e-40 x 1e-40, too small"), std::string::npos) << e;
    EXPECT_NE(e.find("largest extent is at least 1.49e-08 (2^-26)"), std::string::npos) << e;
    buildUniformGrid(tetrahedron(1e-7f), rule);  // inside the range
}

TEST(SceneLimits, NonFiniteVerticesAreRefused) {
    TriangleMesh m = tetrahedron(1.0f);
    m.vertices[2].y = std::nanf("");
    EXPECT_NE(errorOf([&] { validateSceneRange(m); }).find("is out of range"), std::string::npos);
}

TEST(SceneLimits, ACameraBeyondTheRayRangeIsRefusedBeforeAnyRayIsTraced) {
    PinholeCamera camera = fitCamera(christenSceneA().bounds());
    camera.position = {1e19f, 1.0f, 1.0f};  // past Embree's 1.844e18 bound on ray origins
    const std::string e = errorOf([&] { generatePrimaryRays(camera, 4, 4); });
    EXPECT_NE(e.find("camera: position (1e+19, 1, 1) or look_at"), std::string::npos) << e;
    EXPECT_NE(e.find("ray origins within +-1.1e+12 (2^40)"), std::string::npos) << e;
    camera.position = {1e30f, 1.0f, 1.0f};  // the view direction would overflow: not an `up` problem
    EXPECT_EQ(errorOf([&] { generatePrimaryRays(camera, 4, 4); }).find("parallel"), std::string::npos);
}

TEST(SceneLimits, RaysOutsideTheRangeAreNamed) {
    std::vector<gpu::Ray> rays(3, gpu::Ray{glm::vec4(0, 0, 0, 0), glm::vec4(0, 0, 1, gpu::kNoHitT)});
    validateRays(rays);
    rays[1].directionTMax.x = 1e-40f;  // subnormal: 1 / d overflows, a flushing device reads 0
    EXPECT_NE(errorOf([&] { validateRays(rays); }).find("ray 1 (origin 0, 0, 0, direction 1e-40, 0, 1"),
              std::string::npos);
    rays[1].directionTMax.x = 0.0f;
    rays[2].originTMin.w = std::nanf("");
    EXPECT_NE(errorOf([&] { validateRays(rays); }).find("ray 2"), std::string::npos);
}

TEST(SceneLimits, AFittedCameraSeesATinySceneWithinTheRange) {
    // No clamp on the fitted radius: a scene of extent 1e-7 fills the view as one of extent 1 does.
    const PinholeCamera camera = fitCamera(tetrahedron(1e-7f).bounds());
    EXPECT_LT(glm::length(camera.position - camera.lookAt), 1e-6f);
    EXPECT_GT(glm::length(camera.position - camera.lookAt), 1e-8f);
}

}  // namespace
}  // namespace rtbench
