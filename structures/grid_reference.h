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
#define RT_ON_VOXEL(cell) \
    if (voxelLog) voxelLog->push_back(rtCellIndex(cell));
#define precise
struct GridTraversal {
    const std::uint32_t* cellOffsets;
    const std::uint32_t* triangleList;
    const Triangle* triangles;
    GridParams params;
    std::vector<std::uint32_t>* voxelLog = nullptr;  // when set: the voxels rtTraceGrid visits
#include "../kernels/grid_traversal.glsl"
};
#undef precise
#undef RT_ON_VOXEL
#undef RT_INOUT
#undef RT_OUT
}  // namespace gridref

gridref::GridTraversal gridTraversal(const UniformGrid& grid);

// Traces every ray on the CPU through the shared traversal; hits[i] is ray i's record.
std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid, const std::vector<gpu::Ray>& rays);

// The voxels a ray's DDA walk visits, in order (no triangle tests): for tests of the DDA.
std::vector<glm::ivec3> ddaVoxels(const UniformGrid& grid, const gpu::Ray& ray);

// What the branching kernel's subgroup ballots count (Aila & Laine 2009), modelled on the CPU:
// rays run in subgroups of `subgroupSize` consecutive ray indices whose lanes step through the
// voxel loop and each voxel's triangle loop together; a ballot at every iteration of either loop
// counts the lanes still in it.
struct LaneCounts {
    std::uint64_t activeLanes = 0;  // sum of active lanes over ballots
    std::uint64_t laneSlots = 0;    // sum of subgroup size over ballots
};
LaneCounts branchingLaneCounts(const UniformGrid& grid, const std::vector<gpu::Ray>& rays, unsigned subgroupSize);

}  // namespace rtbench
