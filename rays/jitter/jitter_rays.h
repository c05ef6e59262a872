// Jittered camera rays (rays.type = jitter; issue 46's example of a new ray type): one closest-hit
// ray per pixel, as the camera's, but through a random point of the pixel instead of its centre,
// the stratified sample a renderer's first generation takes for antialiasing. Ray i is still
// pixel i, so the images, checks and whole-path strategies read the batch as camera rays; it is
// not the camera frame's lattice, so a strategy that makes the camera rays itself (the control)
// refuses it.
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& jitterRayType();

// The ray of pixel (x, y) through the point (0.5 + jx, 0.5 + jy) of the pixel, jx and jy in
// [-0.5, 0.5): rtRandom (kernels/shading.glsl) of key (seed, pixel y * width + x, 0), draws 0 and 1.
gpu::Ray jitteredRay(const CameraFrame& frame, unsigned x, unsigned y, std::uint32_t seed);

}  // namespace rtbench
