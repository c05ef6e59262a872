// CPU reference of the uniform grid: the functional simulator of Purcell §4.1. It runs the
// kernels' own source (kernels/ray_math.glsl, kernels/traversal_common.glsl and this folder's
// grid_traversal.glsl and grid_multipass.glsl, compiled as C++ here: structures/shared_kernels.h), so
// its hits, per-ray counters and multipass events must equal the GPU kernels' on the same rays,
// bit for bit.
#pragma once
#include <vector>

#include "structures/shared_kernels.h"
#include "uniform_grid.h"

namespace rtbench {

namespace gridref {
using namespace glm;
using namespace rtbench::gpu;
#include "structures/shared_source_begin.h"
struct GridKernels : KernelConstants {
    using RtTraversalState = GridTraversalState;
    static constexpr std::uint64_t kTraversalStackBytes = 0;  // no node stack
    TracedArray<std::uint32_t, MemoryKind::Cells> cellOffsets;
    TracedArray<std::uint32_t, MemoryKind::TriangleList> triangleList;
    TracedArray<Triangle, MemoryKind::Vertices> triangles;
    TracedArray<std::uint32_t, MemoryKind::Vertices> packedTriangles;
    GridParams params;
#include "../../kernels/ray_math.glsl"
#include "../../kernels/traversal_common.glsl"
#include "grid_traversal.glsl"
#include "grid_multipass.glsl"
};
#include "structures/shared_source_end.h"
}  // namespace gridref

gridref::GridKernels gridKernels(const UniformGrid& grid);

// Traces every ray on the CPU through the shared traversal; hits[i] is ray i's record.
std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid, const std::vector<gpu::Ray>& rays);

// The voxels a ray's DDA walk visits, in order (no triangle tests): for tests of the DDA.
std::vector<glm::ivec3> ddaVoxels(const UniformGrid& grid, const gpu::Ray& ray);

}  // namespace rtbench
