// Every structure's CPU reference kernels (its GLSL compiled as C++), as one type: what a
// strategy's CPU model runs over (std::visit), instantiated once per structure here. Adding a
// structure adds its XKernels to this list; adding a strategy touches no structure.
#pragma once
#include <variant>

#include "structures/brute_force/brute_reference.h"
#include "structures/bvh/bvh_reference.h"
#include "structures/uniform_grid/grid_reference.h"

namespace rtbench {

using StructureKernels = std::variant<gridref::GridKernels, bvhref::BvhKernels, bruteref::BruteKernels>;

}  // namespace rtbench
