// What the megakernel's subgroups do (strategies/megakernel/megakernel.comp), modelled on the CPU for
// any structure: rays in subgroups of `subgroupSize` consecutive ray indices run the structure's
// multipass state machine (mpSetup, mpTraverse, mpIntersect: its GLSL compiled as C++) one step at
// a time, the subgroup choosing the states it runs each iteration by the schedule. The choice is
// made by subgroup ballots over every lane, so the counts are the device's on any device.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "structures/structure.h"

namespace rtbench {

// gpu::kSchedule* of a strategy.schedule value (switch, intersect_first, traverse_first, majority).
std::uint32_t megakernelSchedule(const std::string& name);

struct MegakernelCounts {
    std::uint64_t runsTraverse = 0, runsIntersect = 0;  // subgroup executions of each state
    std::uint64_t activeLanes = 0;  // lanes that took a step, summed over the executions
    std::uint64_t laneSlots = 0;    // subgroup size summed over the executions
    // The most loop iterations one subgroup runs (its state loop and the steps' own loops): what a
    // device's loop-iteration limit applies to; and the rays of subgroups over `iterationLimit`.
    std::uint64_t maxSubgroupIterations = 0;
    std::uint64_t raysInLongSubgroups = 0;
    MegakernelCounts& operator+=(const MegakernelCounts& o);
};

MegakernelCounts megakernelCounts(const Structure& structure, const std::vector<gpu::Ray>& rays, unsigned subgroupSize,
                                  std::uint32_t schedule, std::uint32_t query = gpu::kQueryClosest,
                                  std::uint64_t iterationLimit = 0);

}  // namespace rtbench
