// Refraction iterations (rays.type = "refraction", the transmitted half of Whitted 1980's rays,
// which Christen 2005 §5.2 leaves out): every surface glass of index refraction.ior against 1
// outside (the triangle's winding says which side is out), and iteration k's rays are the
// refractions of iteration k - 1's hits (iteration 0: the camera rays), closest hit; a ray past
// the critical angle is reflected instead (total internal reflection; rays/shading.h
// refractPass, kernels/shading.glsl rtRefractRay). The earlier iterations are traced by the run's
// structure; a run measures iteration refraction.iteration alone.
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& refractionRayType();

// Of the batch rays of `workload`, those reflected (total internal reflection) rather than
// transmitted: their direction stays on the side of their parent's hit triangle the parent came from.
std::uint64_t countTotalInternalReflections(const TriangleMesh& scene, const std::vector<gpu::Ray>& cameraRays,
                                            const Workload& workload);

}  // namespace rtbench
