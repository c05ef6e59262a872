// Brute force's per-ray work for the generic kernels (kernels/*.comp).
#include "brute_traversal.glsl"
