#include "primary_rays.h"

namespace rtbench {

namespace {

Workload cameraRays(const WorkloadInputs& in, Row&) {
    Workload w;
    w.batch.rays = in.cameraRays;
    w.batch.query = gpu::kQueryClosest;
    w.batch.camera = in.cameraFrame;  // the camera's rays in their order: a kernel may make them itself
    return w;
}

}  // namespace

const RayType& cameraRayType() {
    static const RayType type = [] {
        RayType t;
        t.name = "primary";
        t.help = "one closest-hit ray from the camera through each pixel (ray casting)";
        t.planned = PlannedRays::OnePerCameraRay;
        t.make = cameraRays;
        return t;
    }();
    return type;
}

}  // namespace rtbench
