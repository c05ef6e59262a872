// Reflection iterations (rays.type = "reflection", Christen 2005 §5.2.1 and Fig. 6.11): every
// surface a mirror, and iteration k's rays are the mirror reflections of iteration k - 1's hits
// (iteration 0: the camera rays), closest hit (rays/shading.h mirrorPass; kernels/shading.glsl rtReflectRay). Which rays
// exist does not depend on the reflection coefficients, which only weight colour, so none is
// modelled. The earlier iterations are traced by the run's structure (its CPU reference, bit for
// bit its kernels); a run measures iteration reflection.iteration alone.
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& reflectionRayType();

}  // namespace rtbench
