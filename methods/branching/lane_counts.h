// What the branching kernel's subgroup ballots count (Aila & Laine 2009), modelled on the CPU for
// any structure: rays run in subgroups of `subgroupSize` consecutive ray indices whose lanes step
// through the traversal's outer loop (voxels, nodes) and each iteration's triangle loop together;
// a ballot at every iteration of either loop counts the lanes still in it.
#pragma once
#include <cstdint>
#include <vector>

#include "methods/structure.h"

namespace rtbench {

struct LaneCounts {
    std::uint64_t activeLanes = 0;  // sum of active lanes over ballots
    std::uint64_t laneSlots = 0;    // sum of subgroup size over ballots
};

// Uses Structure::traceLoops: per ray, the triangle-loop trips of each outer-loop iteration.
LaneCounts branchingLaneCounts(const Structure& structure, const std::vector<gpu::Ray>& rays,
                               unsigned subgroupSize);

}  // namespace rtbench
