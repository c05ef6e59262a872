// CPU functional simulator of the multipass ray caster (Purcell §4.1) for any structure: runs the
// kernels' per-ray source (the structure's structure.glsl, compiled as C++: Structure::cpuKernels)
// pass by pass with the strategy's scheduler, so its hits, per-ray counters, pass sequence and
// event counts must equal the GPU's exactly. Each structure's kernels provide mpSetup /
// mpTraverse / mpIntersect / mpNoEvents / mpHitRecord and the type RtTraversalState.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cstdint>
#include <vector>

#include "methods/multipass/multipass_schedule.h"
#include "methods/structure.h"

namespace rtbench {

// The CPU reference's multipass run: hit records with per-ray counters, and the pass counts.
struct MultipassResult {
    std::vector<gpu::HitRecord> hits;
    MultipassCounts counts;
};

// The pass cap of a structure's runs: strategy.max_passes, else multipassPassCap of its walk bounds.
inline std::uint64_t multipassPassCap(const Structure& structure, const MultipassOptions& options) {
    if (options.maxPasses) return options.maxPasses;
    const WalkBounds b = structure.walkBounds();
    return multipassPassCap(b.maxCellsPerRay, b.maxTrianglesPerCell, options);
}

// Throws rtbench::Error when `cap` passes have run with rays still active.
template <class Kernels>
MultipassResult simulateMultipassOver(Kernels base, const std::vector<gpu::Ray>& rays,
                                      const MultipassOptions& options, std::uint64_t cap) {
    base.traverseStepsPerPass = options.traverseStepsPerPass;
    base.intersectionsPerPass = options.intersectionsPerPass;
    base.suppressFinishedReads = options.suppressFinishedReads ? 1u : 0u;
    const std::size_t n = rays.size();
    std::vector<std::uint8_t> stencil(n);
    std::vector<typename Kernels::RtTraversalState> traversal(n);
    std::vector<gpu::RayHitState> hitState(n);
    std::vector<gpu::RayCounters> counters(n, gpu::RayCounters{0, 0, 0, 0});

    // One pass over the stream: rays whose stencil matches `kind` do its work.
    auto runPass = [&](PassKind kind) {
        return tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, n, 2048), PassSums{},
            [&](const tbb::blocked_range<std::size_t>& range, PassSums sums) {
                Kernels k = base;
                for (std::size_t i = range.begin(); i != range.end(); ++i) {
                    typename Kernels::MpEvents e = k.mpNoEvents();
                    std::uint32_t oldState = 0xFF, state = 0;
                    if (kind == PassKind::Setup) {
                        state = k.mpSetup(rays[i], traversal[i], hitState[i], e);
                    } else if (kind == PassKind::Traverse && stencil[i] == gpu::kStateTraversing) {
                        oldState = gpu::kStateTraversing;
                        state = k.mpTraverse(rays[i], traversal[i], hitState[i], e);
                    } else if (kind == PassKind::Intersect && stencil[i] == gpu::kStateWaiting) {
                        oldState = gpu::kStateWaiting;
                        state = k.mpIntersect(rays[i], traversal[i], hitState[i], e);
                    } else {
                        continue;  // the stencil test: other rays exit at once
                    }
                    stencil[i] = static_cast<std::uint8_t>(state);
                    sums.traversing += state == gpu::kStateTraversing;
                    sums.waiting += state == gpu::kStateWaiting;
                    sums.useful += 1;
                    sums.stencilWrites += state != oldState;
                    sums.structureReads += e.structureReads;
                    sums.triangleReads += e.triangleReads;
                    counters[i].cellsVisited += e.visited;
                    counters[i].trianglesTested += e.tested;
                    counters[i].traversalSteps += e.steps;
                }
                return sums;
            },
            [](PassSums a, const PassSums& b) { return a += b; });
    };
    MultipassResult result;
    result.counts = runPassLoop(options, cap, n, [&](PassKind kind) {
        return kind == PassKind::Write ? PassSums{} : runPass(kind);  // the write pass is below
    });
    result.hits.resize(n);
    Kernels write = base;
    for (std::size_t i = 0; i < n; ++i) result.hits[i] = write.mpHitRecord(hitState[i], counters[i]);
    return result;
}

// The multipass passes on the CPU for a structure and a query (gpu::kQuery*), capped as the
// device's run is; in batches of `batchRays` consecutive rays (0: one stream), each its own pass
// loop, as the device runs them (runMultipass).
inline MultipassResult simulateMultipass(const Structure& structure, const std::vector<gpu::Ray>& rays,
                                         const MultipassOptions& options, std::uint32_t query = gpu::kQueryClosest,
                                         std::uint64_t batchRays = 0) {
    return std::visit(
        [&](auto kernels) {
            kernels.query = query;
            const std::uint64_t cap = multipassPassCap(structure, options);
            if (batchRays == 0 || batchRays >= rays.size()) return simulateMultipassOver(kernels, rays, options, cap);
            MultipassResult all;
            for (std::size_t first = 0; first < rays.size(); first += batchRays) {
                const std::vector<gpu::Ray> batch(rays.begin() + std::ptrdiff_t(first),
                                                  rays.begin() + std::ptrdiff_t(std::min<std::size_t>(first + batchRays, rays.size())));
                MultipassResult part = simulateMultipassOver(kernels, batch, options, cap);
                all.hits.insert(all.hits.end(), part.hits.begin(), part.hits.end());
                all.counts += part.counts;
            }
            return all;
        },
        structure.cpuKernels());
}

}  // namespace rtbench
