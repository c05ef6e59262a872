// Ambient occlusion (rays.type = "ao", the any-hit workload Aila & Laine 2009 report): from every
// camera ray's hit, ao.samples cosine-weighted rays (rays/shading.h diffusePass; kernels/
// shading.glsl rtDiffuseRay) of length ao.radius, any hit: a hit within the radius occludes.
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& aoRayType();

}  // namespace rtbench
