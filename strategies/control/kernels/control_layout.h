// GPU-visible layout of the control kernel (strategies/control/kernels/control_grid.comp): its
// binding slots, its camera buffer and its push constants. Included by C++ and by GLSL.
#ifndef RTBENCH_CONTROL_LAYOUT_H
#define RTBENCH_CONTROL_LAYOUT_H

#include "../../../kernels/layout_begin.h"

RTBENCH_CONST kControlBindingCells = 0u;      // uvec2[cells]: each voxel's (first, count) in the list
RTBENCH_CONST kControlBindingList = 1u;       // uint[references]: triangle ids, voxel by voxel
RTBENCH_CONST kControlBindingTriangles = 2u;  // Triangle[triangles]: three vec4 each
RTBENCH_CONST kControlBindingCamera = 3u;     // ControlCamera, then float[width + height]: column, then row offsets
RTBENCH_CONST kControlBindingHits = 4u;       // uvec2[width * height]: (t bits, triangle), pixel by pixel, row by row
RTBENCH_CONST kControlBindings = 5u;
RTBENCH_CONST kControlTile = 8u;              // a workgroup makes and traces one tile of 8 x 8 pixels

// The camera frame (scene/camera.h CameraFrame), w unused.
struct ControlCamera {
    vec4 eye;      // byte 0
    vec4 forward;  // byte 16
    vec4 right;    // byte 32
    vec4 down;     // byte 48
};

// The grid as the walk needs it and the image, as push constants (96 bytes, within 128).
struct ControlParams {
    vec4 boundsMin;    // byte 0: xyz grid box min
    vec4 gridExtent;   // byte 16: xyz boundsMax - boundsMin in float: the box in the grid's own frame
    vec4 cellSize;     // byte 32
    vec4 invCellSize;  // byte 48
    uvec4 resolution;  // byte 64: xyz cells per axis
    uvec4 image;       // byte 80: x width, y height, z tiles per row
};

#ifdef __cplusplus
static_assert(sizeof(ControlCamera) == 64);
static_assert(sizeof(ControlParams) == 96);
#endif
#include "../../../kernels/layout_end.h"

#endif  // RTBENCH_CONTROL_LAYOUT_H
