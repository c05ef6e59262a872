// CPU reference traversal of the uniform grid: the functional simulator of Purcell §4.1. It runs
// kernels/grid_traversal.glsl itself (compiled as C++ here), so its hits and per-ray counters
// must equal the GPU kernels' on the same rays, bit for bit.
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
#define precise
struct GridTraversal {
    const std::uint32_t* cellOffsets;
    const std::uint32_t* triangleList;
    const Triangle* triangles;
    GridParams params;
#include "../kernels/grid_traversal.glsl"
};
#undef precise
#undef RT_INOUT
#undef RT_OUT
}  // namespace gridref

// Traces every ray on the CPU through the shared traversal; hits[i] is ray i's record.
std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid,
                                               const std::vector<gpu::Ray>& rays);

// The voxels a ray's DDA walk visits, in order (no triangle tests): for tests of the DDA.
std::vector<glm::ivec3> ddaVoxels(const UniformGrid& grid, const gpu::Ray& ray);

gridref::GridTraversal gridTraversal(const UniformGrid& grid);

}  // namespace rtbench
