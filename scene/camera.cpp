#include "camera.h"

#include <cmath>

#include "core/error.h"
#include "scene_limits.h"

namespace rtbench {

PinholeCamera fitCamera(const Bounds3& bounds, float verticalFovDegrees) {
    PinholeCamera camera;
    camera.verticalFovDegrees = verticalFovDegrees;
    const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
    const float radius = 0.5f * glm::length(bounds.extent());  // > 0 for a box within scene_limits.h
    const float halfFov = glm::radians(0.5f * verticalFovDegrees);
    const float distance = radius / std::sin(halfFov);
    const glm::vec3 view = glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f));
    camera.lookAt = centre;
    camera.position = centre + distance * view;
    return camera;
}

CameraFrame cameraFrame(const PinholeCamera& camera, unsigned width, unsigned height) {
    // Range first: beyond it the view direction itself overflows (and would read as a bad `up`).
    auto inRange = [](glm::vec3 p) { return glm::all(glm::lessThanEqual(glm::abs(p), glm::vec3(kMaxRayOrigin))); };
    if (!inRange(camera.position) || !inRange(camera.lookAt))
        throw Error("camera: position (" + formatFloat(camera.position.x) + ", " + formatFloat(camera.position.y) + ", " +
                    formatFloat(camera.position.z) + ") or look_at (" + formatFloat(camera.lookAt.x) + ", " +
                    formatFloat(camera.lookAt.y) + ", " + formatFloat(camera.lookAt.z) + ") is out of range: " +
                    rayRangeText());
    if (!std::isfinite(glm::length(camera.up)) || glm::length(camera.up) == 0.0f)
        throw Error("camera: up must be a finite, non-zero vector");
    const glm::vec3 view = camera.lookAt - camera.position;
    if (glm::length(view) == 0.0f) throw Error("camera: position equals look_at");
    CameraFrame frame;
    frame.eye = camera.position;
    frame.forward = glm::normalize(view);
    const glm::vec3 u = glm::cross(frame.forward, camera.up);
    if (glm::length(u) == 0.0f) throw Error("camera: up is parallel to the view direction");
    frame.right = glm::normalize(u);
    frame.down = glm::cross(frame.forward, frame.right);  // image rows grow downwards
    const float halfHeight = std::tan(glm::radians(0.5f * camera.verticalFovDegrees));
    const float halfWidth = halfHeight * static_cast<float>(width) / static_cast<float>(height);
    for (unsigned x = 0; x < width; ++x)
        frame.columnOffsets.push_back((2.0f * (static_cast<float>(x) + 0.5f) / width - 1.0f) * halfWidth);
    for (unsigned y = 0; y < height; ++y)
        frame.rowOffsets.push_back((2.0f * (static_cast<float>(y) + 0.5f) / height - 1.0f) * halfHeight);
    return frame;
}

gpu::Ray primaryRay(const CameraFrame& frame, unsigned x, unsigned y) {
    const glm::vec3 d = frame.forward + frame.columnOffsets[x] * frame.right + frame.rowOffsets[y] * frame.down;
    gpu::Ray ray;
    ray.originTMin = glm::vec4(frame.eye, 0.0f);
    ray.directionTMax = glm::vec4(d, gpu::kNoHitT);
    return ray;
}

std::vector<gpu::Ray> generatePrimaryRays(const CameraFrame& frame) {
    std::vector<gpu::Ray> rays;
    rays.reserve(static_cast<std::size_t>(frame.width()) * frame.height());
    for (unsigned y = 0; y < frame.height(); ++y)
        for (unsigned x = 0; x < frame.width(); ++x) rays.push_back(primaryRay(frame, x, y));
    return rays;
}

std::vector<gpu::Ray> generatePrimaryRays(const PinholeCamera& camera, unsigned width, unsigned height) {
    return generatePrimaryRays(cameraFrame(camera, width, height));
}

}  // namespace rtbench
