// The BVH's per-ray work for the generic kernels (kernels/*.comp).
#include "bvh_traversal.glsl"
