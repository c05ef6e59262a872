// Diffuse path tracing (rays.type = "path", Purcell et al. 2002 Table 3's path tracing): every
// surface diffuse, and bounce k's rays leave bounce k - 1's hits (bounce 0: the camera rays) in
// cosine-weighted directions (rays/shading.h diffusePass; kernels/shading.glsl rtDiffuseRay),
// closest hit. Each camera hit starts path.samples paths; the random numbers are a hash of
// (path.seed, path, bounce), so every method, Embree and the exact reference trace the same rays.
// Which rays exist does not depend on the surfaces' colours, so none is modelled, nor is Russian
// roulette (every path goes on until it misses). The earlier bounces are traced by the run's
// structure; a run measures bounce path.bounce alone.
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& pathRayType();

}  // namespace rtbench
