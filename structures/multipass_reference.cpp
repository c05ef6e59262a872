#include "multipass_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>


namespace rtbench {

MultipassResult simulateMultipass(const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                                  const MultipassOptions& options) {
    gridref::MultipassSteps base;
    static_cast<gridref::GridTraversal&>(base) = gridTraversal(grid);
    base.traverseStepsPerPass = options.traverseStepsPerPass;
    base.intersectionsPerPass = options.intersectionsPerPass;
    base.suppressFinishedReads = options.suppressFinishedReads ? 1u : 0u;

    const std::size_t n = rays.size();
    std::vector<std::uint8_t> stencil(n);
    std::vector<gpu::RayTraversalState> traversal(n);
    std::vector<gpu::RayHitState> hitState(n);
    std::vector<gpu::RayCounters> counters(n, gpu::RayCounters{0, 0, 0, 0});

    MultipassResult result;
    const std::uint64_t cap = options.maxPasses ? options.maxPasses
                                                : multipassPassCap(&grid.stats.resolution[0], grid.stats.maxReferencesInCell, options);
    // One pass over the stream: rays whose stencil matches `kind` do its work.
    auto runPass = [&](PassKind kind) {
        return tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, n, 2048), PassSums{},
            [&](const tbb::blocked_range<std::size_t>& range, PassSums sums) {
                gridref::MultipassSteps steps = base;
                for (std::size_t i = range.begin(); i != range.end(); ++i) {
                    gridref::MultipassSteps::MpEvents e = steps.mpNoEvents();
                    std::uint32_t oldState = 0xFF, state = 0;
                    if (kind == PassKind::Setup) {
                        state = steps.mpSetup(rays[i], traversal[i], hitState[i], e);
                    } else if (kind == PassKind::Traverse && stencil[i] == gpu::kStateTraversing) {
                        oldState = gpu::kStateTraversing;
                        state = steps.mpTraverse(rays[i], traversal[i], hitState[i], e);
                    } else if (kind == PassKind::Intersect && stencil[i] == gpu::kStateWaiting) {
                        oldState = gpu::kStateWaiting;
                        state = steps.mpIntersect(rays[i], traversal[i], hitState[i], e);
                    } else {
                        continue;  // the stencil test: other rays exit at once
                    }
                    stencil[i] = static_cast<std::uint8_t>(state);
                    sums.traversing += state == gpu::kStateTraversing;
                    sums.waiting += state == gpu::kStateWaiting;
                    sums.useful += 1;
                    sums.stencilWrites += state != oldState;
                    sums.offsetReads += e.offsetReads;
                    sums.triangleReads += e.triangleReads;
                    counters[i].voxelsVisited += e.visited;
                    counters[i].trianglesTested += e.tested;
                    counters[i].traversalSteps += e.steps;
                }
                return sums;
            },
            [](PassSums a, const PassSums& b) { return a += b; });
    };
    result.counts = runPassLoop(options, cap, [&](PassKind kind) {
        return kind == PassKind::Write ? PassSums{} : runPass(kind);  // the write pass is below
    });
    result.hits.resize(n);
    for (std::size_t i = 0; i < n; ++i) result.hits[i] = base.mpHitRecord(hitState[i], counters[i]);
    return result;
}

}  // namespace rtbench
