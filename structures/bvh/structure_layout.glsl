// The BVH's buffers and parameters as the generic kernels (kernels/*.comp) see them (see
// structures/uniform_grid/structure_layout.glsl for the contract).
#include "bvh_layout.h"
#define RtParams BvhParams
#define RtTraversalState BvhTraversalState
layout(std430, set = 0, binding = kBindingBvhNodes) readonly buffer BvhNodeBuffer { BvhNode nodes[]; };
layout(std430, set = 0, binding = kBindingBvhTriangleList) readonly buffer TriangleListBuffer { uint triangleList[]; };
layout(std430, set = 0, binding = kBindingBvhVertices) readonly buffer TriangleBuffer { Triangle triangles[]; };
// The same binding when the vertices are packed (vertexBits != 0, kernels/gpu_layout.h).
layout(std430, set = 0, binding = kBindingBvhVertices) readonly buffer PackedTriangleBuffer { uint packedTriangles[]; };
