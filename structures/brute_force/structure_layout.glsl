// Brute force's buffers and parameters as the generic kernels (kernels/*.comp) see them (see
// structures/uniform_grid/structure_layout.glsl for the contract).
#include "brute_layout.h"
#define RtParams BruteParams
#define RtTraversalState BruteTraversalState
layout(std430, set = 0, binding = kBindingBruteTriangles) readonly buffer TriangleBuffer { Triangle triangles[]; };
// The same binding when the vertices are packed (vertexBits != 0, kernels/gpu_layout.h).
layout(std430, set = 0, binding = kBindingBruteTriangles) readonly buffer PackedTriangleBuffer { uint packedTriangles[]; };
