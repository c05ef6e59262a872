// GPU-visible layout of the uniform grid (Purcell et al. 2002 Fig. 4): its buffers' binding
// slots, its push-constant parameters and its multipass traversal state. Included by C++ and by
// GLSL after kernels/gpu_layout.h.
#ifndef RTBENCH_GRID_LAYOUT_H
#define RTBENCH_GRID_LAYOUT_H

#include "../../kernels/layout_begin.h"

RTBENCH_CONST kBindingCellOffsets = kBindingStructure + 0u;   // uint[cellCount + 1]: voxel -> list start
RTBENCH_CONST kBindingTriangleList = kBindingStructure + 1u;  // uint[references]: triangle ids by voxel
RTBENCH_CONST kBindingVertices = kBindingStructure + 2u;      // Triangle[triangleCount]
RTBENCH_CONST kGridBindings = 3u;

// Grid box and cells, as push constants after StreamParams (16 + 80 bytes, within 128).
struct GridParams {
    vec4 boundsMin;    // byte 0: xyz grid box min, w unused
    vec4 boundsMax;    // byte 16: xyz grid box max, w unused
    vec4 cellSize;     // byte 32: xyz voxel extent, w unused
    vec4 invCellSize;  // byte 48: xyz 1 / cellSize (computed once on the host), w unused
    uvec4 resolution;  // byte 64: xyz cells per axis, w unused
};

// Multipass per-ray DDA state, saved at the end of a pass and restored at the next.
struct GridTraversalState {
    vec4 tMaxAxisLeave;  // byte 0: xyz DDA tMax per axis, w = distance where the ray leaves the grid
    uvec4 cellList;      // byte 16: xyz current voxel, w = position in its triangle list
};

#ifdef __cplusplus
static_assert(sizeof(GridParams) == 80);
static_assert(sizeof(GridTraversalState) == 32);
#endif
#include "../../kernels/layout_end.h"

#endif  // RTBENCH_GRID_LAYOUT_H
