#include "lane_counts.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

namespace rtbench {

LaneCounts operator+(const LaneCounts& a, const LaneCounts& b) {
    return {a.activeLanes + b.activeLanes, a.laneSlots + b.laneSlots,
            std::max(a.maxSubgroupIterations, b.maxSubgroupIterations), a.raysInLongSubgroups + b.raysInLongSubgroups};
}

namespace {

template <class Kernels>
LaneCounts laneCounts(const Kernels& kernels, const std::vector<gpu::Ray>& rays, unsigned subgroupSize,
                      std::uint64_t iterationLimit) {
    const std::size_t subgroups = (rays.size() + subgroupSize - 1) / subgroupSize;
    auto count = [&](const tbb::blocked_range<std::size_t>& range, LaneCounts sum) {
        std::vector<std::vector<std::uint32_t>> lanes(subgroupSize);  // triangle-loop trips per outer iteration
        for (std::size_t g = range.begin(); g != range.end(); ++g) {
            std::size_t longest = 0;
            for (unsigned l = 0; l < subgroupSize; ++l) {
                lanes[l].clear();
                const std::size_t ray = g * subgroupSize + l;
                if (ray >= rays.size()) continue;  // lanes past the stream return at once
                Kernels k = kernels;
                k.loopLog = &lanes[l];
                k.rtTrace(rays[ray]);
                longest = std::max(longest, lanes[l].size());
            }
            std::uint64_t iterations = 0;
            for (std::size_t j = 0; j < longest; ++j) {  // outer-loop iteration j
                std::uint32_t inOuterLoop = 0, mostTriangles = 0;
                for (const auto& lane : lanes)
                    if (lane.size() > j) ++inOuterLoop, mostTriangles = std::max(mostTriangles, lane[j]);
                sum.activeLanes += inOuterLoop;
                sum.laneSlots += subgroupSize;
                iterations += 1 + mostTriangles;
                for (std::uint32_t i = 0; i < mostTriangles; ++i) {  // its triangle loop
                    for (const auto& lane : lanes) sum.activeLanes += lane.size() > j && lane[j] > i;
                    sum.laneSlots += subgroupSize;
                }
            }
            sum.maxSubgroupIterations = std::max(sum.maxSubgroupIterations, iterations);
            if (iterationLimit && iterations > iterationLimit)
                for (const auto& lane : lanes) sum.raysInLongSubgroups += !lane.empty();
        }
        return sum;
    };
    return tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, subgroups, 256), LaneCounts{}, count,
                                [](const LaneCounts& a, const LaneCounts& b) { return a + b; });
}

}  // namespace

LaneCounts branchingLaneCounts(const Structure& structure, const std::vector<gpu::Ray>& rays,
                               unsigned subgroupSize, std::uint64_t iterationLimit, std::uint32_t query) {
    return std::visit(
        [&](auto kernels) {
            kernels.query = query;
            return laneCounts(kernels, rays, subgroupSize, iterationLimit);
        },
        structure.cpuKernels());
}

}  // namespace rtbench
