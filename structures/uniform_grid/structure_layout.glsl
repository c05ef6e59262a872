// The uniform grid's buffers and parameters as the generic kernels (kernels/*.comp) see them:
// CMake compiles each kernel once per structure with -I structures/<structure>, so this file
// supplies RtParams (the push constants after StreamParams), RtTraversalState (the multipass
// state) and the structure's own storage buffers.
#include "grid_layout.h"
#define RtParams GridParams
#define RtTraversalState GridTraversalState
layout(std430, set = 0, binding = kBindingCellOffsets) readonly buffer CellOffsetBuffer { uint cellOffsets[]; };
layout(std430, set = 0, binding = kBindingTriangleList) readonly buffer TriangleListBuffer { uint triangleList[]; };
layout(std430, set = 0, binding = kBindingVertices) readonly buffer TriangleBuffer { Triangle triangles[]; };
// The same binding when the vertices are packed (vertexBits != 0, kernels/gpu_layout.h).
layout(std430, set = 0, binding = kBindingVertices) readonly buffer PackedTriangleBuffer { uint packedTriangles[]; };
