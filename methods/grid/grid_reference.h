// CPU reference of the uniform grid: the functional simulator of Purcell §4.1. It runs the
// kernels' own source (kernels/ray_math.glsl, kernels/multipass_events.glsl and this folder's
// grid_traversal.glsl and grid_multipass.glsl, compiled as C++ here), so its hits, per-ray
// counters and multipass events must equal the GPU kernels' on the same rays, bit for bit.
#pragma once
#include <vector>

#include "uniform_grid.h"

namespace rtbench {

namespace gridref {
// Opens the shared GLSL source as C++: GLSL types from GLM, `out`/`inout` as references.
using namespace glm;
using namespace rtbench::gpu;
#define RT_OUT(T) T&
#define RT_INOUT(T) T&
#define RT_ON_OUTER() \
    if (loopLog) loopLog->push_back(0);
#define RT_ON_INNER() \
    if (loopLog) ++loopLog->back();
#define precise
struct GridKernels {
    using RtTraversalState = GridTraversalState;
    const std::uint32_t* cellOffsets;
    const std::uint32_t* triangleList;
    const Triangle* triangles;
    GridParams params;
    // Multipass specialization constants.
    std::uint32_t traverseStepsPerPass = 1;
    std::uint32_t intersectionsPerPass = 1;
    std::uint32_t suppressFinishedReads = 0;
    // When set: per outer-loop iteration (voxel) of rtTrace, the triangle-loop trips.
    std::vector<std::uint32_t>* loopLog = nullptr;
#include "../../kernels/ray_math.glsl"
#include "../../kernels/multipass_events.glsl"
#include "grid_traversal.glsl"
#include "grid_multipass.glsl"
};
#undef precise
#undef RT_ON_INNER
#undef RT_ON_OUTER
#undef RT_INOUT
#undef RT_OUT
}  // namespace gridref

gridref::GridKernels gridKernels(const UniformGrid& grid);

// Traces every ray on the CPU through the shared traversal; hits[i] is ray i's record.
std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid, const std::vector<gpu::Ray>& rays);

// The voxels a ray's DDA walk visits, in order (no triangle tests): for tests of the DDA.
std::vector<glm::ivec3> ddaVoxels(const UniformGrid& grid, const gpu::Ray& ray);

}  // namespace rtbench
