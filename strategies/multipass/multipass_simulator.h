// CPU functional simulator of the multipass ray caster (Purcell §4.1) for any structure: runs the
// kernels' per-ray source (the structure's structure.glsl, compiled as C++: Structure::cpuKernels)
// pass by pass with the strategy's scheduler, so its hits, per-ray counters, pass sequence and
// event counts must equal the GPU's exactly. Each structure's kernels provide mpSetup /
// mpTraverse / mpIntersect / mpNoEvents / mpHitRecord and the type RtTraversalState.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <utility>
#include <vector>

#include "methods/accounting.h"
#include "methods/cache/memory_trace.h"
#include "strategies/multipass/multipass_schedule.h"
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

// Throws rtbench::Error when `cap` passes have run with rays still active. With a `trace`, the
// passes run ray after ray on this thread, as "a single pixel wide graphics pipeline" (Purcell et
// al. 2002 §4.1), and every read and write goes to it (the kernels' own through TracedArray,
// the stream's here: the stencil, ray, traversal and hit state of the bandwidth accounting).
template <class Kernels>
MultipassResult simulateMultipassOver(Kernels base, const std::vector<gpu::Ray>& rays,
                                      const MultipassOptions& options, std::uint64_t cap, MemoryTrace* trace = nullptr) {
    base.traverseStepsPerPass = options.traverseStepsPerPass;
    base.intersectionsPerPass = options.intersectionsPerPass;
    base.suppressFinishedReads = options.suppressFinishedReads ? 1u : 0u;
    using State = typename Kernels::RtTraversalState;
    const std::size_t n = rays.size();
    std::vector<std::uint8_t> stencil(n);
    std::vector<State> traversal(n);
    std::vector<gpu::RayHitState> hitState(n);
    std::vector<gpu::RayCounters> counters(n, gpu::RayCounters{0, 0, 0, 0});
    MultipassResult result;
    result.hits.resize(n);
    // The traversal state each pass moves whole; a node stack (BVH: its tail) stays in memory, and
    // the kernels' accessors report the entries a pass pushes or pops (bvh_reference.h).
    const std::uint64_t movedBytes = sizeof(State) - Kernels::kTraversalStackBytes;
    auto moveTraversal = [&](std::size_t i, bool write) {
        if (write) trace->write(MemoryKind::State, &traversal[i], movedBytes);
        else trace->read(MemoryKind::State, &traversal[i], movedBytes);
    };
    std::optional<MemoryTrace::Scope> kernelReads;  // the kernels' own, through TracedArray
    if (trace) {
        kernelReads.emplace(*trace);
        for (const auto& [data, bytes] : std::initializer_list<std::pair<const void*, std::uint64_t>>{
                 {rays.data(), n * sizeof(gpu::Ray)}, {stencil.data(), n}, {traversal.data(), n * sizeof(State)},
                 {hitState.data(), n * sizeof(gpu::RayHitState)}, {result.hits.data(), n * sizeof(gpu::HitRecord)}})
            trace->place(data, bytes);
    }

    // Ray i's part of a pass of `kind`: rays whose stencil matches it do its work.
    auto serve = [&](Kernels& k, std::size_t i, PassKind kind, PassSums& sums) {
        if (trace && kind != PassKind::Setup) trace->read(MemoryKind::Stencil, &stencil[i], 1);
        const bool setup = kind == PassKind::Setup;
        const bool traverse = kind == PassKind::Traverse && stencil[i] == gpu::kStateTraversing;
        const bool intersect = kind == PassKind::Intersect && stencil[i] == gpu::kStateWaiting;
        if (!setup && !traverse && !intersect) return;  // the stencil test: other rays exit at once
        if (trace) {
            trace->read(MemoryKind::State, &rays[i], sizeof(gpu::Ray));
            if (!setup) {
                moveTraversal(i, false);
                trace->read(MemoryKind::State, &hitState[i], sizeof(gpu::RayHitState));
            }
        }
        typename Kernels::MpEvents e = k.mpNoEvents();
        std::uint32_t oldState = 0xFF, state = 0;
        if (setup) {
            state = k.mpSetup(rays[i], traversal[i], hitState[i], e);
        } else if (traverse) {
            oldState = gpu::kStateTraversing;
            state = k.mpTraverse(rays[i], traversal[i], hitState[i], e);
        } else {
            oldState = gpu::kStateWaiting;
            state = k.mpIntersect(rays[i], traversal[i], hitState[i], e);
        }
        if (trace) {
            moveTraversal(i, true);
            if (!traverse) trace->write(MemoryKind::State, &hitState[i], sizeof(gpu::RayHitState));
            if (state != oldState) trace->write(MemoryKind::Stencil, &stencil[i], 1);
        }
        stencil[i] = static_cast<std::uint8_t>(state);
        sums.traversing += state == gpu::kStateTraversing;
        sums.waiting += state == gpu::kStateWaiting;
        sums.useful += 1;
        sums.stencilWrites += state != oldState;
        sums.structureReads += e.structureReads;
        sums.triangleReads += e.triangleReads;
        sums.stackEntries += e.stackEntries;
        counters[i].cellsVisited += e.visited;
        counters[i].trianglesTested += e.tested;
        counters[i].traversalSteps += e.steps;
    };
    // One pass over the stream: in parallel, or with a trace ray after ray.
    auto runPass = [&](PassKind kind) {
        if (trace) {
            Kernels k = base;
            PassSums sums;
            for (std::size_t i = 0; i < n; ++i) serve(k, i, kind, sums);
            trace->endPass();  // what the pass rendered is the next pass's texture
            return sums;
        }
        return tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, n, 2048), PassSums{},
            [&](const tbb::blocked_range<std::size_t>& range, PassSums sums) {
                Kernels k = base;
                for (std::size_t i = range.begin(); i != range.end(); ++i) serve(k, i, kind, sums);
                return sums;
            },
            [](PassSums a, const PassSums& b) { return a += b; });
    };
    result.counts = runPassLoop(options, cap, n, [&](PassKind kind) {
        return kind == PassKind::Write ? PassSums{} : runPass(kind);  // the write pass is below
    });
    // The write pass: every ray's hit state to its record.
    Kernels write = base;
    for (std::size_t i = 0; i < n; ++i) {
        if (trace) {
            trace->read(MemoryKind::State, &hitState[i], sizeof(gpu::RayHitState));
            trace->write(MemoryKind::Output, &result.hits[i], bytes::kOutput);
        }
        result.hits[i] = write.mpHitRecord(hitState[i], counters[i]);
    }
    return result;
}

// The multipass passes on the CPU for a structure and a query (gpu::kQuery*), capped as the
// device's run is; in batches of `batchRays` consecutive rays (0: one stream), each its own pass
// loop, as the device runs them (runMultipass).
// With a `trace`, the batches run one after another on this thread, each through its own buffers.
inline MultipassResult simulateMultipass(const Structure& structure, const std::vector<gpu::Ray>& rays,
                                         const MultipassOptions& options, std::uint32_t query = gpu::kQueryClosest,
                                         std::uint64_t batchRays = 0, MemoryTrace* trace = nullptr) {
    return std::visit(
        [&](auto kernels) {
            kernels.query = query;
            const std::uint64_t cap = multipassPassCap(structure, options);
            if (batchRays == 0 || batchRays >= rays.size()) return simulateMultipassOver(kernels, rays, options, cap, trace);
            MultipassResult all;
            for (std::size_t first = 0; first < rays.size(); first += batchRays) {
                const std::vector<gpu::Ray> batch(rays.begin() + std::ptrdiff_t(first),
                                                  rays.begin() + std::ptrdiff_t(std::min<std::size_t>(first + batchRays, rays.size())));
                MultipassResult part = simulateMultipassOver(kernels, batch, options, cap, trace);
                all.hits.insert(all.hits.end(), part.hits.begin(), part.hits.end());
                all.counts += part.counts;
            }
            return all;
        },
        structure.cpuKernels());
}

}  // namespace rtbench
