#include "branching_strategy.h"

#include <cmath>

#include "lane_counts.h"
#include "device/embedded_kernels.h"
#include "methods/cache/cache_replay.h"
#include "strategies/stream_batches.h"
#include "core/error.h"
#include "scene/scene_limits.h"
#include "schema/warnings.h"

namespace rtbench {

void expectSameHits(const std::vector<gpu::HitRecord>& timed, const std::vector<gpu::HitRecord>& counted,
                    const char* strategy) {
    std::uint64_t differing = 0;
    std::size_t first = 0;
    for (std::size_t i = 0; i < timed.size(); ++i) {
        if (std::isnan(timed[i].t) || std::isnan(counted[i].t))
            throw Error(std::string(strategy) + ": ray " + std::to_string(i) +
                        " has a NaN hit distance: its ray-triangle arithmetic overflowed, so the scene or the ray "
                        "lies outside the range the kernels handle (" + rayRangeText() + ")");
        if ((timed[i].primitive != counted[i].primitive || timed[i].t != counted[i].t) && differing++ == 0) first = i;
    }
    if (differing)
        throw Error(std::string(strategy) + ": the timed run's hits differ from the instrumented run's on " +
                    std::to_string(differing) + " of " + std::to_string(timed.size()) + " rays (first: ray " +
                    std::to_string(first) + ", t " + std::to_string(timed[first].t) + " vs " +
                    std::to_string(counted[first].t) + "): the kernel gives different results on the same input");
}

namespace {

// The uninstrumented kernel on the instrumented run's buffers. With `counters` (TraceLaunch::
// countersWhenTimed) the pass counters are zeroed before each dispatch and read back after it.
class BranchingTimer : public KernelTimer {
public:
    BranchingTimer(VulkanContext& vk, std::unique_ptr<GpuBuffers> buffers, const std::string& kernel, KernelSpec spec,
                   std::uint64_t invocations, std::vector<gpu::HitRecord> counted, std::string name, bool counters)
        : vk_(vk), buffers_(std::move(buffers)), invocations_(invocations), counted_(std::move(counted)),
          name_(std::move(name)), counters_(counters) {
        spec.instrument = false;
        timed_ = buffers_->createKernel(kernel, spec);
    }
    ~BranchingTimer() override { vk_.destroy(timed_); }
    TimedBatch time(int warmups, int repetitions) override {
        // Warm-ups and timed repetitions recorded into one submission, each timed on its own.
        const std::vector<VulkanContext::DispatchCall> calls(
            std::size_t(warmups + repetitions),
            {&timed_, buffers_->descriptorSet(timed_), buffers_->pushConstants(), invocations_,
             counters_ ? buffers_->passCounters() : nullptr});
        return splitWarmups(vk_.dispatchAll(calls), warmups);
    }
    void checkHits() override { expectSameHits(buffers_->downloadHits(), counted_, name_.c_str()); }

private:
    VulkanContext& vk_;
    std::unique_ptr<GpuBuffers> buffers_;
    std::uint64_t invocations_;
    std::vector<gpu::HitRecord> counted_;
    std::string name_;  // the kernel, as errors name it
    bool counters_;
    ComputePipeline timed_{};
};

}  // namespace

namespace {

// One dispatch's worth of rays: uploads, and runs the instrumented dispatch; the timer keeps the
// buffers. `shared`: the structure on the device for every batch (null: this stream's own).
BranchingRun runBranchingBatch(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                               const TimingOptions& timing, std::uint32_t query, const TraceLaunch& launch,
                               const std::shared_ptr<const DeviceStructure>& shared) {
    BranchingRun run;
    auto buffers = shared ? std::make_unique<GpuBuffers>(vk, rays, shared, structure.params())
                          : std::make_unique<GpuBuffers>(vk, rays, structure.buffers(), structure.params());
    const std::string kernel = structure.kernelPrefix() + "_" + launch.kernel;
    const std::uint64_t invocations = launch.invocations ? launch.invocations : rays.size();
    const KernelSpec spec = structureKernelSpec(structure, timing.workgroupSize, query, launch.constants);
    {
        ComputePipeline counted = buffers->createKernel(kernel, spec);
        vk.dispatch(counted, buffers->descriptorSet(counted), buffers->pushConstants(), invocations, buffers->passCounters());
        vk.destroy(counted);
        run.hits = buffers->downloadHits();
        run.counters = buffers->readPassCounters();
    }
    run.timer = std::make_unique<BranchingTimer>(vk, std::move(buffers), kernel, spec, invocations, run.hits,
                                                 launch.kernel + " kernel", launch.countersWhenTimed);
    return run;
}

}  // namespace

std::uint64_t wholeTraversalBatchRays(const DeviceInfo& device, unsigned workgroupSize) {
    return raysPerBinding(device, std::max(sizeof(gpu::Ray), sizeof(gpu::HitRecord)), workgroupSize);
}

void requireWholeSubgroups(const VulkanContext& vk, unsigned workgroupSize) {
    const unsigned subgroup = vk.info().subgroupSize;
    if (workgroupSize == 0 || subgroup == 0 || workgroupSize % subgroup)
        throw Error("strategy.workgroup_size " + std::to_string(workgroupSize) + " is not a multiple of the subgroup size " +
                    std::to_string(subgroup) + " of " + vk.info().name + " (" + std::to_string(subgroup) + ", " +
                    std::to_string(2 * subgroup) + ", ...)");
}

BranchingRun runBranching(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                          const TimingOptions& timing, std::uint32_t query, const TraceLaunch& launch) {
    requireWholeSubgroups(vk, timing.workgroupSize);
    const std::uint64_t batchRays = launch.batchRays ? launch.batchRays : wholeTraversalBatchRays(vk.info(), timing.workgroupSize);
    if (batchRays % timing.workgroupSize)
        throw Error("rays per batch " + std::to_string(batchRays) + " is not a multiple of the workgroup size " +
                    std::to_string(timing.workgroupSize));
    BranchingRun run;
    if (rays.size() <= batchRays) {
        run = runBranchingBatch(vk, structure, rays, timing, query, launch, nullptr);
    } else {
        // Batches of whole workgroups, one after another: the records and every counter are those
        // of one dispatch over the stream (each subgroup has the same lanes); the time adds up.
        const auto shared = uploadForBatches(vk, rayBufferSizes(rays.size()), structure.buffers());
        run.batches = 0;
        run.timer = traceInBatches(
            rays, batchRays,
            [&](const std::vector<gpu::Ray>& part) { return runBranchingBatch(vk, structure, part, timing, query, launch, shared); },
            [&](const BranchingRun& b) {
                run.hits.insert(run.hits.end(), b.hits.begin(), b.hits.end());
                for (std::uint32_t c = 0; c < gpu::kCountSlots; ++c) run.counters.counts[c] += b.counters.counts[c];
                ++run.batches;
            });
    }
    run.batchRays = std::min<std::uint64_t>(batchRays, rays.size());
    run.activeLanes = run.counters.counts[gpu::kCountActiveLanes];
    run.laneSlots = run.counters.counts[gpu::kCountLaneSlots];
    if (timing.warmups + timing.repetitions > 0) {
        run.gpuMs = run.timer->time(timing.warmups, timing.repetitions).ms;
        run.timer->checkHits();
    }
    return run;
}

LaneVerdict judgeLaneCounts(const DeviceInfo& device, std::uint64_t deviceActive, std::uint64_t deviceSlots,
                            std::uint64_t modelActive, std::uint64_t modelSlots) {
    if (deviceActive == modelActive && deviceSlots == modelSlots) return {};
    const std::string counts = std::to_string(deviceActive) + "/" + std::to_string(deviceSlots) + " on the device, " +
                               std::to_string(modelActive) + "/" + std::to_string(modelSlots) + " in the CPU model";
    if (device.lockStepSubgroups) return {"subgroup lane counts differ (" + counts + ")", ""};
    return {"", "subgroup lane counts differ from the lock-step model (" + counts + "): " + device.name +
                    " need not run a subgroup's loops in lock step; the SIMD-efficiency columns are its own ballots'"};
}

std::uint64_t loopIterationBudget(const DeviceInfo& device) {
    // A small margin covers the fixed loops around a walk's (the slab test's 3 axes...).
    const std::uint64_t margin = 64;
    return device.loopIterationLimit ? device.loopIterationLimit - margin : 0;
}

std::string loopLimitWhy(const DeviceInfo& device, std::uint64_t iterations, std::uint64_t rays) {
    return "a subgroup of this run needs " + std::to_string(iterations) + " loop iterations and " + device.name +
           " ends a kernel invocation after " + std::to_string(device.loopIterationLimit) +
           " (Mesa's LP_MAX_TGSI_LOOP_ITERATIONS, all loops together), leaving up to " + std::to_string(rays) +
           " rays unfinished";
}

StrategyRun judgeWholeTraversal(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                BranchingRun&& kernel, Row& row) {
    // A device that ends long loops (llvmpipe) leaves the rays of such a subgroup unfinished, their
    // records wrong without a sign: the lane model knows each subgroup's loop iterations exactly.
    const LaneCounts lanes =
        branchingLaneCounts(structure, batch.rays, vk.info().subgroupSize, loopIterationBudget(vk.info()), batch.query);
    return judgeWholeTraversal(vk, structure, batch, std::move(kernel), lanes,
                               "; multipass (a few iterations per pass), a finer grid or the BVH stay within it", row);
}

StrategyRun judgeWholeTraversal(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                BranchingRun&& kernel, const LaneCounts& lanes, const std::string& longLoops, Row& row) {
    StrategyRun run;
    run.metrics = branchingMetrics(kernel.hits, kernel.activeLanes, kernel.laneSlots, structure.costs());
    run.cpuMismatches = recordMismatches(kernel.hits, structure.trace(batch.rays, batch.query));
    const WholeTraversalColumns& c = wholeTraversalColumns();
    put(row, c.lanesModelActive, lanes.activeLanes);
    put(row, c.lanesModelSlots, lanes.laneSlots);
    const LaneVerdict verdict =
        judgeLaneCounts(vk.info(), kernel.activeLanes, kernel.laneSlots, lanes.activeLanes, lanes.laneSlots);
    run.countsMismatch = verdict.mismatch;
    run.countsCompared = vk.info().lockStepSubgroups;
    if (!verdict.warning.empty()) addWarning(row, verdict.warning);
    run.truncatedRays = lanes.raysInLongSubgroups;
    put(row, c.raysCutShort, run.truncatedRays);
    put(row, c.streamBatches, kernel.batches);
    if (run.truncatedRays)
        run.truncatedWhy = loopLimitWhy(vk.info(), lanes.maxSubgroupIterations, run.truncatedRays) + longLoops;
    run.hits = std::move(kernel.hits);
    run.timer = std::move(kernel.timer);
    return run;
}

const WholeTraversalColumns& wholeTraversalColumns() {
    static const WholeTraversalColumns columns;
    return columns;
}

StrategyRun traceBranching(VulkanContext& vk, const Structure& structure, const RayBatch& batch, const TimingOptions& timing,
                           Row& row) {
    StrategyRun run =
        judgeWholeTraversal(vk, structure, batch, runBranching(vk, structure, batch.rays, timing, batch.query), row);
    run.metrics.instructions = wholeTraversalInstructions(embeddedKernel(structure.kernelPrefix() + "_branching"),
                                                          kernelEvents(structure, run.metrics.work), batch.rays.size());
    return run;
}

namespace {

StrategyRun runBranchingStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                 const RunConfig& config, const TimingOptions& timing, Row& row) {
    StrategyRun run = traceBranching(vk, structure, batch, timing, row);
    if (const auto cache = cacheConfig(config))
        run.modelMismatch =
            writeCacheColumns(branchingCacheReplay(structure, batch.rays, batch.query, *cache), run.metrics.bytes, row);
    return run;
}

}  // namespace

const StrategyType& branchingStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "branching";
        t.help = "one kernel per ray stream (Purcell's branching architecture)";
        t.columns = wholeTraversalColumns().group.specs();
        t.trace = runBranchingStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
