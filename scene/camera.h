// Pinhole camera and the one ray generator every method traces (GPU kernels and Embree alike).
#pragma once
#include <vector>

#include "../kernels/gpu_layout.h"
#include "mesh.h"

namespace rtbench {

struct PinholeCamera {
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    glm::vec3 lookAt{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float verticalFovDegrees = 45.0f;
};

// Looks at the box centre from the +z side (slightly raised), far enough that the bounding
// sphere fits the vertical field of view.
PinholeCamera fitCamera(const Bounds3& bounds, float verticalFovDegrees = 45.0f);

// Primary rays through pixel centres, row-major from the top-left pixel; tMin 0, tMax FLT_MAX.
// Directions are not normalised, so distances are in units of |direction|. Throws rtbench::Error
// for a position or look_at outside the ray range of scene/scene_limits.h.
std::vector<gpu::Ray> generatePrimaryRays(const PinholeCamera& camera, unsigned width,
                                          unsigned height);

}  // namespace rtbench
