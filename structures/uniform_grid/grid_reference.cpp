#include "grid_reference.h"

namespace rtbench {

gridref::GridKernels gridKernels(const UniformGrid& grid) {
    gridref::GridKernels k{};
    k.cellOffsets = grid.cellOffsets.data();
    k.triangleList = grid.triangleList.data();
    k.triangles = grid.triangles.data();
    k.packedTriangles = nullptr;  // float vertices; GridStructure binds its packed store
    k.params = grid.params;
    return k;
}

std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid, const std::vector<gpu::Ray>& rays) {
    return traceAll(gridKernels(grid), rays);
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
