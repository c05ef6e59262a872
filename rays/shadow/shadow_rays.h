// Shadow rays (rays.type = "shadow", Purcell et al. 2002 Table 3's shadow casting; OptiX's
// shadow ray type): from every camera ray's hit toward a point light, an any-hit query ending at
// the light (rays/shading.h shadowPass; kernels/shading.glsl rtShadowRay). The hits they
// start from are the camera rays' as the run's structure finds them; a hit whose light lies
// behind its surface gets none (shadow_unlit).
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& shadowRayType();

// light.position, the point light of shadow rays and of Whitted rays' shadow rays (results schema 7).
KeySpec lightPositionKey();

// Where the light is when light.position is not given: above the scene box's centre along the
// camera's up vector, one box diagonal away.
glm::vec3 defaultLight(const Bounds3& box, glm::vec3 up);

// A shadow ray's direction is light - point, unnormalised (it ends at the light, t = 1): each
// component within kMaxDirectionComponent (scene/scene_limits.h) for every point of the
// scene's box, else rtbench::Error naming the light (`what`: "light.position", "[[light]] 2 of
// the scene description") and the axis, before any ray is made.
glm::vec3 reachableLight(glm::vec3 light, const Bounds3& box, const std::string& what);

}  // namespace rtbench
