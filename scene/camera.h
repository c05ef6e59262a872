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

// What the camera rays of a width x height image are made of: the eye, the unit view direction,
// the image plane's unit axes (rows grow downwards) and each column's and row's offset along them.
// Ray (x, y): origin `eye`, direction forward + columnOffsets[x] * right + rowOffsets[y] * down,
// in that order of operations (a kernel that makes the rays itself makes the same bits).
struct CameraFrame {
    glm::vec3 eye{0.0f}, forward{0.0f}, right{0.0f}, down{0.0f};
    std::vector<float> columnOffsets, rowOffsets;
    unsigned width() const { return unsigned(columnOffsets.size()); }
    unsigned height() const { return unsigned(rowOffsets.size()); }
};

// The frame of the camera's image. Throws rtbench::Error for a position or look_at outside the ray
// range of scene/scene_limits.h, or a degenerate view (position at look_at, up along the view).
CameraFrame cameraFrame(const PinholeCamera& camera, unsigned width, unsigned height);

// Primary rays through pixel centres, row-major from the top-left pixel; tMin 0, tMax FLT_MAX.
// Directions are not normalised, so distances are in units of |direction|.
std::vector<gpu::Ray> generatePrimaryRays(const CameraFrame& frame);
// The one of pixel (x, y).
gpu::Ray primaryRay(const CameraFrame& frame, unsigned x, unsigned y);
// The same from the camera (cameraFrame's errors).
std::vector<gpu::Ray> generatePrimaryRays(const PinholeCamera& camera, unsigned width, unsigned height);

}  // namespace rtbench
