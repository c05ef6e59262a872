// What the branching kernel's subgroup ballots count (Aila & Laine 2009), modelled on the CPU for
// any structure: rays run in subgroups of `subgroupSize` consecutive ray indices whose lanes step
// through the traversal's outer loop (voxels, nodes) and each iteration's triangle loop together;
// a ballot at every iteration of either loop counts the lanes still in it.
#pragma once
#include <cstdint>
#include <vector>

#include "strategies/ray_batch.h"
#include "structures/structure.h"

namespace rtbench {

struct LaneCounts {
    std::uint64_t activeLanes = 0;  // sum of active lanes over ballots
    std::uint64_t laneSlots = 0;    // sum of subgroup size over ballots
    // The most loop iterations one subgroup runs (outer and triangle loops together): what a
    // device's loop-iteration limit applies to (DeviceInfo::loopIterationLimit).
    std::uint64_t maxSubgroupIterations = 0;
    // Rays in subgroups that run more loop iterations than the `iterationLimit` asked about.
    std::uint64_t raysInLongSubgroups = 0;
};

// A sum of counts (the parallel reduction's join).
LaneCounts operator+(const LaneCounts& a, const LaneCounts& b);

// Runs the structure's shared rtTrace (Structure::cpuKernels) with the loop log on: per ray, the
// triangle-loop trips of each outer-loop iteration, for the query (gpu::kQuery*).
// iterationLimit (0: none) counts the rays of subgroups that run more loop iterations.
LaneCounts branchingLaneCounts(const Structure& structure, const std::vector<gpu::Ray>& rays,
                               unsigned subgroupSize, std::uint64_t iterationLimit = 0,
                               std::uint32_t query = gpu::kQueryClosest);

// The path megakernel's ballots (methods/path_megakernel): a lane per camera ray of `path`, tracing
// its camera ray, then each path its hit starts (the first pass's slots in turn) generation by
// generation until the path ends, at one rtTrace call site; the batch's rays ask `batchQuery`.
// The path's generations must be in the order of their paths (as the CPU makes them).
LaneCounts pathLaneCounts(const Structure& structure, const BatchPath& path, std::uint32_t batchQuery,
                          unsigned subgroupSize, std::uint64_t iterationLimit = 0);

}  // namespace rtbench
