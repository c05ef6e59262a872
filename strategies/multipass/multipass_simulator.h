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
#include "structures/structure.h"

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

// One run of the multipass passes over a stream of rays on the CPU: the stream's buffers (the
// stencil, the traversal and hit state, the records) and the passes over them.
template <class Kernels>
class MultipassSimulation {
  public:
    using State = typename Kernels::RtTraversalState;

    MultipassSimulation(Kernels base, const std::vector<gpu::Ray>& rays, const MultipassOptions& options, MemoryTrace* trace)
        : base_(std::move(base)), rays_(rays), trace_(trace), n_(rays.size()), stencil_(n_), traversal_(n_), hitState_(n_),
          counters_(n_, gpu::RayCounters{0, 0, 0, 0}) {
        base_.traverseStepsPerPass = options.traverseStepsPerPass;
        base_.intersectionsPerPass = options.intersectionsPerPass;
        base_.suppressFinishedReads = options.suppressFinishedReads ? 1u : 0u;
        result_.hits.resize(n_);
        if (trace_) {
            kernelReads_.emplace(*trace_);  // the kernels' own reads, through TracedArray
            for (const auto& [data, bytes] : std::initializer_list<std::pair<const void*, std::uint64_t>>{
                     {rays_.data(), n_ * sizeof(gpu::Ray)}, {stencil_.data(), n_}, {traversal_.data(), n_ * sizeof(State)},
                     {hitState_.data(), n_ * sizeof(gpu::RayHitState)}, {result_.hits.data(), n_ * sizeof(gpu::HitRecord)}})
                trace_->place(data, bytes);
        }
    }

    MultipassResult run(const MultipassOptions& options, std::uint64_t cap) {
        result_.counts = runPassLoop(options, cap, n_, [&](PassKind kind) {
            return kind == PassKind::Write ? PassSums{} : runPass(kind);  // the write pass is below
        });
        // The write pass: every ray's hit state to its record.
        Kernels write = base_;
        for (std::size_t i = 0; i < n_; ++i) {
            if (trace_) {
                trace_->read(MemoryKind::State, &hitState_[i], sizeof(gpu::RayHitState));
                trace_->write(MemoryKind::Output, &result_.hits[i], bytes::kOutput);
            }
            result_.hits[i] = write.mpHitRecord(hitState_[i], counters_[i]);
        }
        return std::move(result_);
    }

  private:
    // The traversal state each pass moves whole; a node stack (BVH: its tail) stays in memory, and
    // the kernels' accessors report the entries a pass pushes or pops (bvh_reference.h).
    void moveTraversal(std::size_t i, bool write) {
        const std::uint64_t movedBytes = sizeof(State) - Kernels::kTraversalStackBytes;
        if (write) trace_->write(MemoryKind::State, &traversal_[i], movedBytes);
        else trace_->read(MemoryKind::State, &traversal_[i], movedBytes);
    }

    // The kernel of `kind` on ray i (its stencil matched): the ray's new state.
    std::uint32_t runKernel(Kernels& k, std::size_t i, PassKind kind, typename Kernels::MpEvents& e) {
        if (kind == PassKind::Setup) return k.mpSetup(rays_[i], traversal_[i], hitState_[i], e);
        if (kind == PassKind::Traverse) return k.mpTraverse(rays_[i], traversal_[i], hitState_[i], e);
        return k.mpIntersect(rays_[i], traversal_[i], hitState_[i], e);
    }

    // Ray i's part of a pass of `kind`: rays whose stencil matches it do its work.
    void serve(Kernels& k, std::size_t i, PassKind kind, PassSums& sums) {
        if (trace_ && kind != PassKind::Setup) trace_->read(MemoryKind::Stencil, &stencil_[i], 1);
        const bool setup = kind == PassKind::Setup;
        const bool traverse = kind == PassKind::Traverse && stencil_[i] == gpu::kStateTraversing;
        const bool intersect = kind == PassKind::Intersect && stencil_[i] == gpu::kStateWaiting;
        if (!setup && !traverse && !intersect) return;  // the stencil test: other rays exit at once
        if (trace_) {
            trace_->read(MemoryKind::State, &rays_[i], sizeof(gpu::Ray));
            if (!setup) {
                moveTraversal(i, false);
                trace_->read(MemoryKind::State, &hitState_[i], sizeof(gpu::RayHitState));
            }
        }
        typename Kernels::MpEvents e = k.mpNoEvents();
        const std::uint32_t oldState = setup ? 0xFF : traverse ? gpu::kStateTraversing : gpu::kStateWaiting;
        const std::uint32_t state = runKernel(k, i, kind, e);
        if (trace_) {
            moveTraversal(i, true);
            if (!traverse) trace_->write(MemoryKind::State, &hitState_[i], sizeof(gpu::RayHitState));
            if (state != oldState) trace_->write(MemoryKind::Stencil, &stencil_[i], 1);
        }
        stencil_[i] = static_cast<std::uint8_t>(state);
        sums.traversing += state == gpu::kStateTraversing;
        sums.waiting += state == gpu::kStateWaiting;
        sums.useful += 1;
        sums.stencilWrites += state != oldState;
        sums.structureReads += e.structureReads;
        sums.triangleReads += e.triangleReads;
        sums.stackEntries += e.stackEntries;
        counters_[i].cellsVisited += e.visited;
        counters_[i].trianglesTested += e.tested;
        counters_[i].traversalSteps += e.steps;
    }

    // One pass over the stream: in parallel, or with a trace ray after ray.
    PassSums runPass(PassKind kind) {
        if (trace_) {
            Kernels k = base_;
            PassSums sums;
            for (std::size_t i = 0; i < n_; ++i) serve(k, i, kind, sums);
            trace_->endPass();  // what the pass rendered is the next pass's texture
            return sums;
        }
        return tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, n_, 2048), PassSums{},
            [&](const tbb::blocked_range<std::size_t>& range, PassSums sums) {
                Kernels k = base_;
                for (std::size_t i = range.begin(); i != range.end(); ++i) serve(k, i, kind, sums);
                return sums;
            },
            [](PassSums a, const PassSums& b) { return a += b; });
    }

    Kernels base_;
    const std::vector<gpu::Ray>& rays_;
    MemoryTrace* trace_;
    std::size_t n_;
    std::vector<std::uint8_t> stencil_;
    std::vector<State> traversal_;
    std::vector<gpu::RayHitState> hitState_;
    std::vector<gpu::RayCounters> counters_;
    MultipassResult result_;
    std::optional<MemoryTrace::Scope> kernelReads_;
};

// Throws rtbench::Error when `cap` passes have run with rays still active. With a `trace`, the
// passes run ray after ray on this thread, as "a single pixel wide graphics pipeline" (Purcell et
// al. 2002 §4.1), and every read and write goes to it (the kernels' own through TracedArray,
// the stream's here: the stencil, ray, traversal and hit state of the bandwidth accounting).
template <class Kernels>
MultipassResult simulateMultipassOver(Kernels base, const std::vector<gpu::Ray>& rays,
                                      const MultipassOptions& options, std::uint64_t cap, MemoryTrace* trace = nullptr) {
    return MultipassSimulation<Kernels>(std::move(base), rays, options, trace).run(options, cap);
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
