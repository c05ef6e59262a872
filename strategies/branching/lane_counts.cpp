#include "lane_counts.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

#include "core/error.h"

namespace rtbench {

LaneCounts operator+(const LaneCounts& a, const LaneCounts& b) {
    return {a.activeLanes + b.activeLanes, a.laneSlots + b.laneSlots,
            std::max(a.maxSubgroupIterations, b.maxSubgroupIterations), a.raysInLongSubgroups + b.raysInLongSubgroups};
}

namespace {

// One trace of a lane: its ray and the query it asks.
struct LaneTrace {
    const gpu::Ray* ray;
    std::uint32_t query;
};

// Lanes in subgroups of consecutive lanes, each tracing `tracesOf(lane, out)`'s rays one after
// another at one call site of rtTrace: the subgroup's k-th trace runs the k-th ray of every lane
// that has one, its lanes in lock step through the outer loop and each iteration's triangle loop.
template <class Kernels, class TracesOf>
LaneCounts laneCounts(const Kernels& kernels, std::size_t lanes, unsigned subgroupSize, std::uint64_t iterationLimit,
                      const TracesOf& tracesOf) {
    const std::size_t subgroups = (lanes + subgroupSize - 1) / subgroupSize;
    auto count = [&](const tbb::blocked_range<std::size_t>& range, LaneCounts sum) {
        // Per lane, per trace: triangle-loop trips per outer iteration.
        std::vector<std::vector<std::vector<std::uint32_t>>> logs(subgroupSize);
        std::vector<LaneTrace> traces;
        for (std::size_t g = range.begin(); g != range.end(); ++g) {
            std::size_t mostTraces = 0;
            std::uint64_t tracedRays = 0;
            for (unsigned l = 0; l < subgroupSize; ++l) {
                logs[l].clear();
                const std::size_t lane = g * subgroupSize + l;
                if (lane >= lanes) continue;  // lanes past the stream return at once
                traces.clear();
                tracesOf(lane, traces);
                logs[l].resize(traces.size());
                for (std::size_t t = 0; t < traces.size(); ++t) {
                    Kernels k = kernels;
                    k.query = traces[t].query;
                    k.loopLog = &logs[l][t];
                    k.rtTrace(*traces[t].ray);
                }
                mostTraces = std::max(mostTraces, traces.size());
                tracedRays += traces.size();
            }
            std::uint64_t iterations = mostTraces > 1 ? mostTraces : 0;  // a loop of traces runs once per trace
            for (std::size_t t = 0; t < mostTraces; ++t) {
                std::size_t longest = 0;
                for (const auto& lane : logs)
                    if (lane.size() > t) longest = std::max(longest, lane[t].size());
                for (std::size_t j = 0; j < longest; ++j) {  // outer-loop iteration j
                    std::uint32_t inOuterLoop = 0, mostTriangles = 0;
                    for (const auto& lane : logs)
                        if (lane.size() > t && lane[t].size() > j) ++inOuterLoop, mostTriangles = std::max(mostTriangles, lane[t][j]);
                    sum.activeLanes += inOuterLoop;
                    sum.laneSlots += subgroupSize;
                    iterations += 1 + mostTriangles;
                    for (std::uint32_t i = 0; i < mostTriangles; ++i) {  // its triangle loop
                        for (const auto& lane : logs) sum.activeLanes += lane.size() > t && lane[t].size() > j && lane[t][j] > i;
                        sum.laneSlots += subgroupSize;
                    }
                }
            }
            sum.maxSubgroupIterations = std::max(sum.maxSubgroupIterations, iterations);
            if (iterationLimit && iterations > iterationLimit) sum.raysInLongSubgroups += tracedRays;
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
        [&](const auto& kernels) {
            return laneCounts(kernels, rays.size(), subgroupSize, iterationLimit,
                              [&](std::size_t lane, std::vector<LaneTrace>& out) { out.push_back({&rays[lane], query}); });
        },
        structure.cpuKernels());
}

LaneCounts pathLaneCounts(const Structure& structure, const BatchPath& path, std::uint32_t batchQuery,
                          unsigned subgroupSize, std::uint64_t iterationLimit) {
    const std::vector<PathGeneration>& gens = path.generations;
    for (std::size_t g = 1; g < gens.size(); ++g)
        if (!std::is_sorted(gens[g].paths->begin(), gens[g].paths->end()))
            throw Error("pathLaneCounts: generation " + std::to_string(g) + "'s rays are not in the order of their paths");
    const std::uint32_t slots = path.passes.empty() ? 1 : path.passes.front().pass.z;
    auto queryOf = [&](std::size_t g) { return g + 1 == gens.size() ? batchQuery : gpu::kQueryClosest; };
    return std::visit(
        [&](const auto& kernels) {
            return laneCounts(kernels, gens.front().rays->size(), subgroupSize, iterationLimit,
                              [&](std::size_t camera, std::vector<LaneTrace>& out) {
                                  out.push_back({&(*gens.front().rays)[camera], queryOf(0)});
                                  for (std::uint32_t s = 0; s < slots && gens.size() > 1; ++s) {
                                      const std::uint32_t p = std::uint32_t(camera) * slots + s;
                                      for (std::size_t g = 1; g < gens.size(); ++g) {  // the path's rays until it ends
                                          const std::vector<std::uint32_t>& paths = *gens[g].paths;
                                          const auto it = std::lower_bound(paths.begin(), paths.end(), p);
                                          if (it == paths.end() || *it != p) break;
                                          out.push_back({&(*gens[g].rays)[std::size_t(it - paths.begin())], queryOf(g)});
                                      }
                                  }
                              });
        },
        structure.cpuKernels());
}

}  // namespace rtbench
