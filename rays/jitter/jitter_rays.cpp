#include "jitter_rays.h"

#include "core/error.h"
#include "rays/shading_reference.h"

namespace rtbench {

gpu::Ray jitteredRay(const CameraFrame& frame, unsigned x, unsigned y, std::uint32_t seed) {
    shadingref::ShadingKernels shading{};
    const glm::uvec3 key(seed, y * frame.width() + x, 0u);
    const float jx = shading.rtRandom(key, 0u) - 0.5f;  // exact: a multiple of 2^-24 less a half
    const float jy = shading.rtRandom(key, 1u) - 0.5f;
    const float across = frame.columnOffsets[x] + jx * frame.pixelSize.x;
    const float along = frame.rowOffsets[y] + jy * frame.pixelSize.y;
    gpu::Ray ray;
    ray.originTMin = glm::vec4(frame.eye, 0.0f);
    ray.directionTMax = glm::vec4(frame.forward + across * frame.right + along * frame.down, gpu::kNoHitT);
    return ray;
}

namespace {

Workload jitterRays(const WorkloadInputs& in, Row&) {
    if (!in.cameraFrame) throw Error("rays.type = jitter: no camera frame to jitter the camera rays in");
    const CameraFrame& frame = *in.cameraFrame;
    const auto seed = std::uint32_t(in.run.getInt("jitter.seed"));
    Workload w;
    w.batch.rays.reserve(std::size_t(frame.width()) * frame.height());
    for (unsigned y = 0; y < frame.height(); ++y)
        for (unsigned x = 0; x < frame.width(); ++x) w.batch.rays.push_back(jitteredRay(frame, x, y, seed));
    w.batch.query = gpu::kQueryClosest;  // batch.camera stays empty: these are not the frame's rays
    return w;
}

}  // namespace

const RayType& jitterRayType() {
    static const RayType type = [] {
        RayType t;
        t.name = "jitter";
        t.help = "one closest-hit ray from the camera through a random point of each pixel (jittered camera rays)";
        t.planned = PlannedRays::OnePerCameraRay;
        t.keys = {randomSeedKey("jitter.seed", "jittered camera rays")};
        t.make = jitterRays;
        setSince(t, 29);
        return t;
    }();
    return type;
}

}  // namespace rtbench
