// Shadow rays (rays.type = "shadow", Purcell et al. 2002 Table 3's shadow casting; OptiX's
// shadow ray type): from every camera ray's hit toward a point light, an any-hit query ending at
// the light (kernels/shading.glsl: rtShadowRay). The hits they start from are the camera rays'
// as the run's structure finds them.
#pragma once
#include "workloads/workload.h"

namespace rtbench {

const RayType& shadowRayType();

// The shadow rays of camera rays `rays` with hits `hits` on `scene` toward `light`; pixels[i] is
// the camera ray shadow ray i leaves from. Hits whose light lies behind their surface get none
// (`unlit` counts them).
struct ShadowRays {
    std::vector<gpu::Ray> rays;
    std::vector<std::uint32_t> pixels;
    std::uint64_t unlit = 0;
};
ShadowRays makeShadowRays(const TriangleMesh& scene, const std::vector<gpu::Ray>& rays,
                          const std::vector<gpu::HitRecord>& hits, glm::vec3 light);

// Where the light is when light.position is not given: above the scene box's centre along the
// camera's up vector, one box diagonal away.
glm::vec3 defaultLight(const Bounds3& box, glm::vec3 up);

}  // namespace rtbench
