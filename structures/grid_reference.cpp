#include "grid_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

namespace rtbench {

gridref::GridTraversal gridTraversal(const UniformGrid& grid) {
    return {grid.cellOffsets.data(), grid.triangleList.data(), grid.triangles.data(), grid.params};
}

std::vector<gpu::HitRecord> traceGridReference(const UniformGrid& grid,
                                               const std::vector<gpu::Ray>& rays) {
    std::vector<gpu::HitRecord> hits(rays.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 4096), [&](const auto& range) {
        gridref::GridTraversal traversal = gridTraversal(grid);
        for (std::size_t i = range.begin(); i != range.end(); ++i) hits[i] = traversal.rtTraceGrid(rays[i]);
    });
    return hits;
}

std::vector<glm::ivec3> ddaVoxels(const UniformGrid& grid, const gpu::Ray& ray) {
    gridref::GridTraversal t = gridTraversal(grid);
    std::vector<glm::ivec3> voxels;
    gridref::GridTraversal::RtDda s;
    if (!t.rtEnterGrid(ray, s)) return voxels;
    do voxels.push_back(s.cell);
    while (t.rtDdaStep(s));
    return voxels;
}

LaneCounts branchingLaneCounts(const UniformGrid& grid, const std::vector<gpu::Ray>& rays, unsigned subgroupSize) {
    const std::size_t subgroups = (rays.size() + subgroupSize - 1) / subgroupSize;
    auto count = [&](const tbb::blocked_range<std::size_t>& range, LaneCounts sum) {
        gridref::GridTraversal traversal = gridTraversal(grid);
        std::vector<std::vector<std::uint32_t>> lanes(subgroupSize);  // triangles per visited voxel
        for (std::size_t g = range.begin(); g != range.end(); ++g) {
            std::size_t longest = 0;
            for (unsigned l = 0; l < subgroupSize; ++l) {
                lanes[l].clear();
                const std::size_t ray = g * subgroupSize + l;
                if (ray >= rays.size()) continue;  // lanes past the stream return at once
                std::vector<std::uint32_t> voxels;
                traversal.voxelLog = &voxels;
                traversal.rtTraceGrid(rays[ray]);
                for (std::uint32_t c : voxels) lanes[l].push_back(grid.cellOffsets[c + 1] - grid.cellOffsets[c]);
                longest = std::max(longest, lanes[l].size());
            }
            for (std::size_t j = 0; j < longest; ++j) {  // voxel-loop iteration j
                std::uint32_t inVoxelLoop = 0, mostTriangles = 0;
                for (const auto& lane : lanes)
                    if (lane.size() > j) ++inVoxelLoop, mostTriangles = std::max(mostTriangles, lane[j]);
                sum.activeLanes += inVoxelLoop;
                sum.laneSlots += subgroupSize;
                for (std::uint32_t i = 0; i < mostTriangles; ++i) {  // its triangle loop
                    for (const auto& lane : lanes) sum.activeLanes += lane.size() > j && lane[j] > i;
                    sum.laneSlots += subgroupSize;
                }
            }
        }
        return sum;
    };
    return tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, subgroups, 256), LaneCounts{}, count,
                                [](LaneCounts a, LaneCounts b) {
                                    return LaneCounts{a.activeLanes + b.activeLanes, a.laneSlots + b.laneSlots};
                                });
}

}  // namespace rtbench
