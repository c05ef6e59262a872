#include "megakernel_model.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>

#include "core/error.h"
#include "megakernel_layout.h"

namespace rtbench {

std::uint32_t megakernelSchedule(const std::string& name) {
    if (name == "switch") return gpu::kScheduleSwitch;
    if (name == "intersect_first") return gpu::kScheduleIntersectFirst;
    if (name == "traverse_first") return gpu::kScheduleTraverseFirst;
    if (name == "majority") return gpu::kScheduleMajority;
    throw Error("unknown megakernel schedule '" + name + "' (known: switch, intersect_first, traverse_first, majority)");
}

MegakernelCounts& MegakernelCounts::operator+=(const MegakernelCounts& o) {
    runsTraverse += o.runsTraverse, runsIntersect += o.runsIntersect;
    activeLanes += o.activeLanes, laneSlots += o.laneSlots;
    maxSubgroupIterations = std::max(maxSubgroupIterations, o.maxSubgroupIterations);
    raysInLongSubgroups += o.raysInLongSubgroups;
    return *this;
}

namespace {

template <class Kernels>
MegakernelCounts countsOver(Kernels k, const std::vector<gpu::Ray>& rays, unsigned subgroupSize, std::uint32_t schedule,
                            std::uint64_t iterationLimit) {
    k.traverseStepsPerPass = 1;  // one traversal step or one triangle test per state execution
    k.intersectionsPerPass = 1;
    k.suppressFinishedReads = 0;
    using State = typename Kernels::RtTraversalState;
    const std::size_t subgroups = (rays.size() + subgroupSize - 1) / subgroupSize;
    auto count = [&](const tbb::blocked_range<std::size_t>& range, MegakernelCounts sum) {
        std::vector<State> ts(subgroupSize);
        std::vector<gpu::RayHitState> hit(subgroupSize);
        std::vector<std::uint32_t> state(subgroupSize);
        for (std::size_t g = range.begin(); g != range.end(); ++g) {
            std::uint64_t live = 0;
            for (unsigned l = 0; l < subgroupSize; ++l) {
                const std::size_t ray = g * subgroupSize + l;
                state[l] = gpu::kStateLeftStructure;  // lanes past the stream: done from the start
                if (ray >= rays.size()) continue;
                ++live;
                typename Kernels::MpEvents e = k.mpNoEvents();
                state[l] = k.mpSetup(rays[ray], ts[l], hit[l], e);
            }
            std::uint64_t iterations = 0;
            for (;;) {
                std::uint32_t nTraverse = 0, nIntersect = 0;
                for (unsigned l = 0; l < subgroupSize; ++l)
                    nTraverse += state[l] == gpu::kStateTraversing, nIntersect += state[l] == gpu::kStateWaiting;
                if (nTraverse + nIntersect == 0) break;
                ++iterations;
                bool runTraverse = false, runIntersect = false;
                switch (schedule) {
                    case gpu::kScheduleSwitch: runTraverse = nTraverse > 0, runIntersect = nIntersect > 0; break;
                    case gpu::kScheduleTraverseFirst: runTraverse = nTraverse > 0, runIntersect = !runTraverse; break;
                    case gpu::kScheduleMajority: runIntersect = nIntersect >= nTraverse, runTraverse = !runIntersect; break;
                    default: runIntersect = nIntersect > 0, runTraverse = !runIntersect; break;
                }
                const std::vector<std::uint32_t> before = state;  // a lane runs at most one step an iteration
                for (unsigned l = 0; l < subgroupSize; ++l) {
                    const std::size_t ray = g * subgroupSize + l;
                    typename Kernels::MpEvents e = k.mpNoEvents();
                    if (runTraverse && before[l] == gpu::kStateTraversing) state[l] = k.mpTraverse(rays[ray], ts[l], hit[l], e);
                    if (runIntersect && before[l] == gpu::kStateWaiting) state[l] = k.mpIntersect(rays[ray], ts[l], hit[l], e);
                }
                if (runTraverse) ++sum.runsTraverse, sum.activeLanes += nTraverse, sum.laneSlots += subgroupSize, ++iterations;
                if (runIntersect) ++sum.runsIntersect, sum.activeLanes += nIntersect, sum.laneSlots += subgroupSize, ++iterations;
            }
            sum.maxSubgroupIterations = std::max(sum.maxSubgroupIterations, iterations);
            if (iterationLimit && iterations > iterationLimit) sum.raysInLongSubgroups += live;
        }
        return sum;
    };
    return tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, subgroups, 256), MegakernelCounts{}, count,
                                [](MegakernelCounts a, const MegakernelCounts& b) { return a += b; });
}

}  // namespace

MegakernelCounts megakernelCounts(const Structure& structure, const std::vector<gpu::Ray>& rays, unsigned subgroupSize,
                                  std::uint32_t schedule, std::uint32_t query, std::uint64_t iterationLimit) {
    return std::visit(
        [&](auto kernels) {
            kernels.query = query;
            return countsOver(kernels, rays, subgroupSize, schedule, iterationLimit);
        },
        structure.cpuKernels());
}

}  // namespace rtbench
