// The uniform grid's per-ray work for the generic kernels (kernels/*.comp): rtTrace for the
// branching kernel, mpSetup / mpTraverse / mpIntersect for the multipass passes.
#include "grid_traversal.glsl"
#include "grid_multipass.glsl"
