// The one header of GPU-visible layouts, binding slots and specialization-constant ids.
// Included by C++ (harness, tests) and by GLSL (kernels/*.comp). Never retype these in a shader.
// All structs use vec4/uvec4 or 4-byte scalars so that std430 and C++ agree byte for byte.
#ifndef RTBENCH_GPU_LAYOUT_H
#define RTBENCH_GPU_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace rtbench::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
#define RTBENCH_CONST constexpr uint
#else
#define RTBENCH_CONST const uint
#endif

// ---- descriptor set 0 binding slots (all storage buffers) ----
RTBENCH_CONST kBindingRays = 0;         // Ray[rayCount]
RTBENCH_CONST kBindingCellOffsets = 1;  // uint[cellCount + 1]: Purcell Fig. 4 voxel -> list start
RTBENCH_CONST kBindingTriangleList = 2; // uint[references]: triangle ids, grouped by voxel
RTBENCH_CONST kBindingVertices = 3;     // Triangle[triangleCount]
RTBENCH_CONST kBindingHits = 4;         // HitRecord[rayCount]
RTBENCH_CONST kBindingCount = 5;

// ---- specialization-constant ids ----
RTBENCH_CONST kSpecWorkgroupSize = 0;  // local_size_x of every kernel (default 64)
RTBENCH_CONST kSpecInstrument = 1;     // 1: write per-ray work counters; 0: timing runs

// A ray as generated once on the host and traced by every method (Embree included).
struct Ray {
    vec4 originTMin;     // byte 0: xyz origin, w = tMin
    vec4 directionTMax;  // byte 16: xyz direction (not normalised), w = tMax
};

// One triangle's vertices (Purcell Fig. 4 "triangle vertices"), w unused (0).
struct Triangle {
    vec4 v0;  // byte 0
    vec4 v1;  // byte 16
    vec4 v2;  // byte 32
};

// Nearest hit of one ray plus the work it took.
struct HitRecord {
    float t;              // byte 0: hit distance along direction; kNoHitT when none
    uint primitive;       // byte 4: triangle id, kNoHit when none
    float u;              // byte 8: barycentric of v1
    float v;              // byte 12: barycentric of v2
    uint voxelsVisited;   // byte 16: DDA steps taken (voxels entered), 0 if the box is missed
    uint trianglesTested; // byte 20: ray-triangle tests executed
    uint pad0;            // byte 24
    uint pad1;            // byte 28
};

// Uniform grid and stream parameters, as push constants (80 bytes, within the 128-byte minimum).
struct GridParams {
    vec4 boundsMin;    // byte 0: xyz grid box min, w unused
    vec4 boundsMax;    // byte 16: xyz grid box max, w unused
    vec4 cellSize;     // byte 32: xyz voxel extent, w unused
    vec4 invCellSize;  // byte 48: xyz 1 / cellSize (computed once on the host), w unused
    uvec4 resolution;  // byte 64: xyz cells per axis, w = ray count
};

RTBENCH_CONST kNoHit = 0xFFFFFFFFu;

#ifdef __cplusplus
constexpr float kNoHitT = 3.402823466e38f;  // FLT_MAX
static_assert(sizeof(Ray) == 32);
static_assert(sizeof(Triangle) == 48);
static_assert(sizeof(HitRecord) == 32);
static_assert(sizeof(GridParams) == 80);
}  // namespace rtbench::gpu
#else
const float kNoHitT = 3.402823466e38;
#endif
#undef RTBENCH_CONST

#endif  // RTBENCH_GPU_LAYOUT_H
