// The median-split BVH as a method's structure (structures/structure.h): median_bvh_build.h's
// tree in the BVH's layout, traced by the BVH's kernels and CPU reference.
#pragma once
#include "structures/structure.h"

namespace rtbench {

const StructureType& medianBvhStructureType();

}  // namespace rtbench
