#include "multipass_strategy.h"

#include <chrono>

#include "multipass_simulator.h"
#include "structures/error.h"

namespace rtbench {

namespace {

struct Pipelines {
    VulkanContext& vk;
    std::array<ComputePipeline, kPassKinds> byKind{};
    Pipelines(VulkanContext& v, GpuBuffers& buffers, const std::string& prefix, const KernelSpec& spec) : vk(v) {
        static const char* names[kPassKinds] = {"multipass_setup", "multipass_traverse", "multipass_intersect",
                                                "multipass_write"};
        for (int k = 0; k < kPassKinds; ++k) byKind[k] = buffers.createKernel(prefix + "_" + names[k], spec);
    }
    ~Pipelines() {
        for (ComputePipeline& p : byKind) vk.destroy(p);
    }
};

// The instrumented run of the pass loop: after each pass the host reads the ray-state counts (the
// oracle's occlusion query) and the event counts.
MultipassCounts runPasses(VulkanContext& vk, GpuBuffers& buffers, Pipelines& pipelines, const MultipassOptions& options,
                          std::uint64_t cap) {
    return runPassLoop(options, cap, buffers.rayCount(), [&](PassKind kind) {
        const ComputePipeline& p = pipelines.byKind[static_cast<int>(kind)];
        vk.dispatch(p, buffers.descriptorSet(p), buffers.pushConstants(), buffers.rayCount(), buffers.passCounters());
        const gpu::PassCounters c = buffers.readPassCounters();
        PassSums sums;
        sums.traversing = c.counts[gpu::kCountTraversing];
        sums.waiting = c.counts[gpu::kCountWaiting];
        sums.useful = c.counts[gpu::kCountUsefulRays];
        sums.stencilWrites = c.counts[gpu::kCountStencilWrites];
        sums.structureReads = c.counts[gpu::kCountStructureReads];
        sums.triangleReads = c.counts[gpu::kCountTriangleReads];
        return sums;
    });
}

StrategyRun runMultipassStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                 const RunConfig& config, const TimingOptions& timing, Row& row) {
    const std::vector<gpu::Ray>& rays = batch.rays;
    const MultipassOptions options = multipassOptions(config);
    MultipassRun kernel = runMultipass(vk, structure, rays, options, timing, batch.query);
    StrategyRun run;
    run.metrics = multipassMetrics(kernel.hits, kernel.counts, options, structure.costs());
    row["multipass_batch_rays"] = std::to_string(std::min<std::uint64_t>(kernel.batchRays, rays.size()));
    const MultipassResult cpu = simulateMultipass(structure, rays, options, batch.query, kernel.batchRays);
    run.cpuMismatches = recordMismatches(kernel.hits, cpu.hits);
    if (!(cpu.counts == kernel.counts)) run.countsMismatch = "pass sequence or event counts differ";
    // The two architectures must produce identical hit records (and work counters).
    run.branchingMismatches = recordMismatches(kernel.hits, structure.trace(rays, batch.query));
    row["branching_mismatches"] = std::to_string(run.branchingMismatches);
    row["passes_setup"] = std::to_string(run.metrics.passesSetup);
    row["passes_traverse"] = std::to_string(run.metrics.passesTraverse);
    row["passes_intersect"] = std::to_string(run.metrics.passesIntersect);
    row["passes_write"] = std::to_string(run.metrics.passesWrite);
    row["passes_lower_bound"] = std::to_string(run.metrics.passesLowerBound);
    run.hits = std::move(kernel.hits);
    run.timer = std::move(kernel.timer);
    return run;
}

}  // namespace

MultipassOptions multipassOptions(const RunConfig& run) {
    MultipassOptions o;
    o.traverseStepsPerPass = unsigned(run.getInt("strategy.traverse_steps_per_pass"));
    o.intersectionsPerPass = unsigned(run.getInt("strategy.intersections_per_pass"));
    o.suppressFinishedReads = run.getBool("strategy.suppress_finished_reads");
    o.scheduling = run.getString("strategy.scheduling");
    if (run.has("strategy.oracle_threshold")) o.oracleThreshold = run.getFloat("strategy.oracle_threshold");
    o.maxPasses = std::uint64_t(run.getInt("strategy.max_passes"));
    o.batchRays = std::uint64_t(run.getInt("strategy.batch_rays"));
    return o;
}

namespace {

// The instrumented run's pass sequence replayed without instrumentation, on its buffers; and the
// live loop, the instrumented passes with the oracle's read-back after each, timed on the host.
class MultipassTimer : public KernelTimer {
public:
    MultipassTimer(VulkanContext& vk, std::unique_ptr<GpuBuffers> buffers, std::unique_ptr<Pipelines> counted,
                   const std::string& prefix, KernelSpec spec, const MultipassOptions& options, std::uint64_t cap,
                   const MultipassCounts& counts, std::vector<gpu::HitRecord> hits)
        : vk_(vk), buffers_(std::move(buffers)), counted_(std::move(counted)), options_(options), cap_(cap),
          counts_(counts), hits_(std::move(hits)) {
        spec.instrument = false;
        timed_ = std::make_unique<Pipelines>(vk, *buffers_, prefix, spec);
    }
    TimedBatch time(int warmups, int repetitions) override {
        // The oracle's choices depend only on the rays and the structure: the replay runs the
        // counted sequence, warm-ups and repetitions in one submission, every pass timed on its
        // own. Its hits must equal the instrumented run's (checkHits), so a replay that strayed
        // would be caught.
        std::vector<VulkanContext::DispatchCall> calls;
        for (int i = 0; i < warmups + repetitions; ++i)
            for (PassKind kind : counts_.sequence) {
                const ComputePipeline& p = timed_->byKind[static_cast<int>(kind)];
                calls.push_back({&p, buffers_->descriptorSet(p), buffers_->pushConstants(), buffers_->rayCount()});
            }
        const std::vector<double> ms = vk_.dispatchAll(calls);
        const std::size_t passes = counts_.sequence.size();
        static const char* names[kPassKinds] = {"setup", "traverse", "intersect", "write"};
        TimedBatch batch;
        for (std::size_t i = 0; i < std::size_t(warmups) * passes; ++i) batch.warmupMs += ms[i];
        for (int k = 0; k < kPassKinds; ++k) batch.parts.push_back({names[k], {}});
        for (int i = warmups; i < warmups + repetitions; ++i) {
            std::array<double, kPassKinds> byKind{};
            for (std::size_t p = 0; p < passes; ++p)
                byKind[static_cast<int>(counts_.sequence[p])] += ms[std::size_t(i) * passes + p];
            for (int k = 0; k < kPassKinds; ++k) batch.parts[std::size_t(k)].second.push_back(byKind[std::size_t(k)]);
            batch.ms.push_back(byKind[0] + byKind[1] + byKind[2] + byKind[3]);
        }
        return batch;
    }
    std::vector<std::pair<std::string, double>> timeHostLoops() override {
        const auto start = std::chrono::steady_clock::now();
        const MultipassCounts live = runPasses(vk_, *buffers_, *counted_, options_, cap_);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (!(live == counts_))
            throw Error("multipass: the live pass loop ran another pass sequence than the first instrumented run "
                        "on the same rays (" + std::to_string(live.sequence.size()) + " passes against " +
                        std::to_string(counts_.sequence.size()) + ")");
        return {{"multipass_live", ms}};
    }
    void checkHits() override { expectSameHits(buffers_->downloadHits(), hits_, "multipass kernels"); }

private:
    VulkanContext& vk_;
    std::unique_ptr<GpuBuffers> buffers_;
    std::unique_ptr<Pipelines> counted_, timed_;
    MultipassOptions options_;
    std::uint64_t cap_;
    MultipassCounts counts_;
    std::vector<gpu::HitRecord> hits_;
};

}  // namespace

namespace {

// One batch's instrumented run and its timer.
MultipassRun runMultipassBatch(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                               const MultipassOptions& options, const TimingOptions& timing, std::uint32_t query) {
    MultipassRun run;
    auto buffers = std::make_unique<GpuBuffers>(vk, rays, structure.costs().traversalStateBytes, structure.buffers(),
                                                structure.params());
    const std::uint64_t cap = multipassPassCap(structure, options);
    KernelSpec spec;
    spec.workgroupSize = timing.workgroupSize;
    spec.triangleTest = structure.triangleTest();
    spec.vertexLattice = structure.vertexLattice();
    spec.strategyConstants = {{gpu::kSpecTraverseSteps, options.traverseStepsPerPass},
                              {gpu::kSpecIntersections, options.intersectionsPerPass},
                              {gpu::kSpecSuppress, options.suppressFinishedReads ? 1u : 0u}};
    spec.query = query;
    auto counted = std::make_unique<Pipelines>(vk, *buffers, structure.kernelPrefix(), spec);
    run.counts = runPasses(vk, *buffers, *counted, options, cap);
    run.hits = buffers->downloadHits();
    run.traversalStates = buffers->downloadTraversalStates();
    run.timer = std::make_unique<MultipassTimer>(vk, std::move(buffers), std::move(counted), structure.kernelPrefix(), spec,
                                                 options, cap, run.counts, run.hits);
    return run;
}

// The timers of a stream's batches as one: a repetition is every batch's, one after another.
class BatchedTimer : public KernelTimer {
public:
    explicit BatchedTimer(std::vector<std::unique_ptr<KernelTimer>> batches) : batches_(std::move(batches)) {}
    TimedBatch time(int warmups, int repetitions) override {
        TimedBatch all;
        for (const auto& batch : batches_) {
            const TimedBatch b = batch->time(warmups, repetitions);
            all.warmupMs += b.warmupMs;
            if (all.ms.empty()) {
                all.ms = b.ms;
                all.parts = b.parts;
                continue;
            }
            for (std::size_t i = 0; i < all.ms.size(); ++i) all.ms[i] += b.ms[i];
            for (std::size_t p = 0; p < all.parts.size(); ++p)
                for (std::size_t i = 0; i < all.parts[p].second.size(); ++i) all.parts[p].second[i] += b.parts[p].second[i];
        }
        return all;
    }
    std::vector<std::pair<std::string, double>> timeHostLoops() override {
        std::vector<std::pair<std::string, double>> all;
        for (const auto& batch : batches_) {
            const auto loops = batch->timeHostLoops();
            if (all.empty()) all = loops;
            else
                for (std::size_t i = 0; i < all.size(); ++i) all[i].second += loops[i].second;
        }
        return all;
    }
    void checkHits() override {
        for (const auto& batch : batches_) batch->checkHits();
    }

private:
    std::vector<std::unique_ptr<KernelTimer>> batches_;
};

}  // namespace

std::uint64_t multipassBatchRays(const DeviceInfo& device, std::uint64_t traversalStateBytes, std::uint64_t requested,
                                 unsigned workgroupSize) {
    if (requested) return requested;
    // The largest per-ray record of the batch's bindings (rayBufferSizes): the ray, the hit record,
    // or the structure's traversal state (the BVH's: 144 bytes with its stack).
    const std::uint64_t perRay = std::max<std::uint64_t>({sizeof(gpu::Ray), sizeof(gpu::HitRecord), traversalStateBytes});
    const std::uint64_t fit = device.maxStorageBufferRange / perRay;
    return std::max<std::uint64_t>(fit / workgroupSize * workgroupSize, workgroupSize);
}

MultipassRun runMultipass(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                          const MultipassOptions& options, const TimingOptions& timing, std::uint32_t query) {
    if (options.traverseStepsPerPass < 1 || options.intersectionsPerPass < 1)
        throw Error("multipass: traverse_steps_per_pass and intersections_per_pass must be at least 1");
    const std::uint64_t batchRays =
        multipassBatchRays(vk.info(), structure.costs().traversalStateBytes, options.batchRays, timing.workgroupSize);
    MultipassRun run;
    if (batchRays >= rays.size()) {
        run = runMultipassBatch(vk, structure, rays, options, timing, query);
    } else {
        // Rays in batches (each its own buffers and pass loop, the oracle's passes per batch): the
        // per-ray records and events are those of one stream; the passes add up over the batches.
        std::vector<std::unique_ptr<KernelTimer>> timers;
        run.batches = 0;
        for (std::size_t first = 0; first < rays.size(); first += batchRays) {
            const std::vector<gpu::Ray> part(rays.begin() + std::ptrdiff_t(first),
                                             rays.begin() + std::ptrdiff_t(std::min<std::size_t>(first + batchRays, rays.size())));
            MultipassRun b = runMultipassBatch(vk, structure, part, options, timing, query);
            run.hits.insert(run.hits.end(), b.hits.begin(), b.hits.end());
            run.traversalStates.insert(run.traversalStates.end(), b.traversalStates.begin(), b.traversalStates.end());
            run.counts += b.counts;
            timers.push_back(std::move(b.timer));
            ++run.batches;
        }
        run.timer = std::make_unique<BatchedTimer>(std::move(timers));
    }
    run.batchRays = batchRays;
    if (timing.warmups + timing.repetitions > 0) {
        run.gpuMs = run.timer->time(timing.warmups, timing.repetitions).ms;
        run.timer->checkHits();
    }
    return run;
}

const StrategyType& multipassStrategyType() {
    static const StrategyType type = [] {
        using K = ColumnKind;
        StrategyType t;
        t.name = "multipass";
        t.help = "a pass per traverse/intersect step with a ray-state stencil and an oracle (Purcell et al. 2002 §3.2)";
        t.perRayState = true;
        t.keys = {
            {"strategy.traverse_steps_per_pass", ValueType::Int, "multipass: traversal steps per traverse pass (loop unrolling; Purcell used 4)", std::int64_t(1), false, 1, 64},
            {"strategy.intersections_per_pass", ValueType::Int, "multipass: triangle tests per intersect pass (Purcell used 2)", std::int64_t(1), false, 1, 64},
            {"strategy.suppress_finished_reads", ValueType::Bool, "multipass: rays that finish mid-pass skip the unrolled rest's reads", false},
            {"strategy.scheduling", ValueType::String, "multipass: oracle (threshold on the waiting fraction) or naive (traverse until none traverses, then intersect until none waits)", std::string("oracle"), false, -1e300, 1e300, {"oracle", "naive"}},
            {"strategy.oracle_threshold", ValueType::Float, "multipass: intersect when waiting / active rays >= this (0: as soon as any waits; Purcell: 0.2)", 0.2, false, 0, 1, {}, {"strategy.scheduling=oracle"}},
            {"strategy.max_passes", ValueType::Int, "multipass: pass cap (0: derived from the structure); reaching it fails the run", std::int64_t(0), false, 0, 1e9},
            {"strategy.batch_rays", ValueType::Int, "multipass: rays per batch, each its own pass loop (0: as many as one binding holds, maxStorageBufferRange over the largest per-ray record)", std::int64_t(0), false, 0, 1e12},
        };
        t.keys.back().since = 12;
        t.columns = {
            {"passes_setup", K::Count, "passes", "multipass setup passes"},
            {"passes_traverse", K::Count, "passes", "multipass traverse passes"},
            {"passes_intersect", K::Count, "passes", "multipass intersect passes"},
            {"passes_write", K::Count, "passes", "multipass write passes"},
            {"passes_lower_bound", K::Count, "passes", "Purcell's lower bound on traverse + intersect passes"},
            {"kernel_ms_setup", K::Timing, "ms", "multipass: GPU time of the setup passes, median"},
            {"kernel_ms_traverse", K::Timing, "ms", "multipass: GPU time of the traverse passes, median"},
            {"kernel_ms_intersect", K::Timing, "ms", "multipass: GPU time of the intersect passes, median"},
            {"kernel_ms_write", K::Timing, "ms", "multipass: GPU time of the write pass, median"},
            {"multipass_live_ms_median", K::Timing, "ms", "multipass: host wall time of the live pass loop (instrumented passes, the oracle's read-back after each: Christen 2005 §4.3.4's CPU-controlled loop), median of one per round", 0.0, false, {}, 5},
            {"branching_mismatches", K::Count, "rays", "multipass: rays whose hit record differs from the branching caster's"},
            {"multipass_batch_rays", K::Count, "rays", "multipass: rays per batch (strategy.batch_rays, 0 made what one binding holds); passes_* add up over the batches", 0.0, false, {}, 12},
        };
        t.run = runMultipassStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
