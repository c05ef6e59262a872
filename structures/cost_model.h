// The cost model every structure predicts its work with before a ray is traced (issue: "no more
// structure than a scene needs"). The unit is one operation: a cell or node visited or a
// ray-triangle test, each counted as 1 (the SAH's traversal and intersection costs, 1 and 1).
// For a structure over a box, a ray that enters the box is modelled as a random line through it:
// by Cauchy's formula such a line meets a convex part of the box with probability (the part's
// surface area) / (the box's), so the expected work per entering ray is
//   sum over cells or nodes of A / A_box  +  sum over leaves or cells of (triangles in it) x A / A_box,
// the surface area heuristic (MacDonald & Booth 1990; Purcell §3.2's voxels and triangles per
// ray for a grid, whose cells all have the same area). Rays are not stopped by a hit (the model
// ignores early termination), so it over-predicts closed scenes; the measured work is in the row
// beside it (work_per_ray_mean).
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/gpu_layout.h"
#include "scene/mesh.h"

namespace rtbench {

// Surface area of a box (0 for an empty or inverted one).
double surfaceArea(glm::vec3 lo, glm::vec3 hi);

// The rays whose [tMin, tMax] segment meets the closed box (a slab test in double precision).
std::uint64_t raysEnteringBox(const std::vector<gpu::Ray>& rays, glm::vec3 lo, glm::vec3 hi);

}  // namespace rtbench
