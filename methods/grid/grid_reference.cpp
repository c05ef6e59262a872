#include "grid_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rtbench {

gridref::GridKernels gridKernels(const UniformGrid& grid) {
    gridref::GridKernels k{};
    k.cellOffsets = grid.cellOffsets.data();
    k.triangleList = grid.triangleList.data();
    k.triangles = grid.triangles.data();
    k.params = grid.params;
    return k;
}

std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid, const std::vector<gpu::Ray>& rays) {
    std::vector<gpu::HitRecord> hits(rays.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 4096), [&](const auto& range) {
        gridref::GridKernels kernels = gridKernels(grid);
        for (std::size_t i = range.begin(); i != range.end(); ++i) hits[i] = kernels.rtTrace(rays[i]);
    });
    return hits;
}

std::vector<glm::ivec3> ddaVoxels(const UniformGrid& grid, const gpu::Ray& ray) {
    gridref::GridKernels k = gridKernels(grid);
    std::vector<glm::ivec3> voxels;
    gridref::GridKernels::RtDda s;
    if (!k.rtEnterGrid(ray, s)) return voxels;
    do voxels.push_back(s.cell);
    while (k.rtDdaStep(s));
    return voxels;
}

}  // namespace rtbench
