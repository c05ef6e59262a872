#include "grid_reference.h"

namespace rtbench {

gridref::GridTraversal gridTraversal(const UniformGrid& grid) {
    return {grid.cellOffsets.data(), grid.triangleList.data(), grid.triangles.data(), grid.params};
}

std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid,
                                               const std::vector<gpu::Ray>& rays) {
    gridref::GridTraversal traversal = gridTraversal(grid);
    std::vector<gpu::HitRecord> hits(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = traversal.rtTraceGrid(rays[i]);
    return hits;
}

std::vector<glm::ivec3> ddaVoxels(const UniformGrid& grid, const gpu::Ray& ray) {
    gridref::GridTraversal t = gridTraversal(grid);
    const glm::vec3 o(ray.originTMin), d(ray.directionTMax);
    const glm::vec3 invD = t.rtInverseDirection(d);
    float tEnter = 0.0f, tLeave = 0.0f;
    std::vector<glm::ivec3> voxels;
    if (!t.rtClipToBox(o, d, invD, ray.originTMin.w, ray.directionTMax.w,
                       glm::vec3(grid.params.boundsMin), glm::vec3(grid.params.boundsMax), tEnter,
                       tLeave))
        return voxels;
    gridref::GridTraversal::RtDda s = t.rtDdaSetup(o, d, invD, tEnter, tLeave);
    do voxels.push_back(s.cell);
    while (t.rtDdaStep(s));
    return voxels;
}

}  // namespace rtbench
