#include "wavefront_strategy.h"

#include <algorithm>
#include <cstring>

#include "strategies/branching/branching_strategy.h"
#include "strategies/branching/lane_counts.h"
#include "methods/metrics.h"
#include "strategies/whole_path.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {

namespace {

// The strategy's buffers in the kBindingPath* slots, as GpuBuffers numbers them.
constexpr std::uint32_t kControl = gpu::kBindingPathControl - gpu::kBindingStrategy;
constexpr std::uint32_t kQueue = gpu::kBindingPathQueue - gpu::kBindingStrategy;

// One pipeline per stage; two traces when the batch asks another query than the generations before.
struct Stages {
    ComputePipeline setup, trace, traceBatch, shade, scan, compact;
};

class WavefrontRun {
public:
    WavefrontRun(VulkanContext& vk, const Structure& structure, const BatchPath& path, std::uint32_t query,
                 unsigned workgroupSize)
        : vk_(vk), structure_(structure), path_(path), query_(query), workgroupSize_(workgroupSize) {
        capacity_ = wholePathCapacity(path);
        // The shading grid's workgroups at its largest (wavefront_common.glsl wfGroupsFor).
        const auto [groupsX, groupsY] = workgroupGrid((std::max<std::uint64_t>(capacity_.slots, 1) + workgroupSize - 1) / workgroupSize,
                                                      vk.info().maxWorkGroupCountX);
        buffers_ = uploadWholePath(vk, structure, path, capacity_.queue, {groupsX * groupsY, capacity_.queue, capacity_.slots},
                                   std::uint32_t(capacity_.queue), std::uint32_t(capacity_.slots));
    }
    ~WavefrontRun() {
        for (Stages* s : {&counted_, &timed_})
            for (ComputePipeline* p : {&s->setup, &s->trace, &s->traceBatch, &s->shade, &s->scan, &s->compact})
                if (p->pipeline) vk_.destroy(*p);
    }

    Stages& stages(bool instrumented) {
        Stages& s = instrumented ? counted_ : timed_;
        if (s.setup.pipeline) return s;
        auto make = [&](const char* stage, std::uint32_t query) {
            KernelSpec spec = structureKernelSpec(structure_, workgroupSize_, query,
                                                  {{gpu::kSpecMaxGroupsX, vk_.info().maxWorkGroupCountX}});
            spec.instrument = instrumented;
            return buffers_->createKernel(structure_.kernelPrefix() + "_wavefront_" + stage, spec);
        };
        s.setup = make("setup", gpu::kQueryClosest);
        s.trace = make("trace", gpu::kQueryClosest);
        s.traceBatch = query_ == gpu::kQueryClosest ? ComputePipeline{} : make("trace", query_);
        s.shade = make("shade", gpu::kQueryClosest);
        s.scan = make("scan", gpu::kQueryClosest);
        s.compact = make("compact", gpu::kQueryClosest);
        return s;
    }

    // The dispatches of generation g (0: the setup, then the camera rays' trace; g > 0: the pass
    // that makes generation g from g - 1, then its trace). `counters`: on the batch's trace.
    std::vector<VulkanContext::DispatchCall> generationCalls(Stages& s, std::size_t g, bool counters) {
        const VkDescriptorSet set = buffers_->descriptorSet(s.setup);
        const void* push = buffers_->pushConstants();
        const Buffer* control = &buffers_->strategyBuffer(kControl);
        std::vector<VulkanContext::DispatchCall> calls;
        if (g == 0) {
            calls.push_back({&s.setup, set, push, path_.generations.front().rays->size()});
        } else {
            calls.push_back({&s.shade, set, push, 0, nullptr, control, offsetof(gpu::WholePathControl, slotGroups)});
            calls.push_back({&s.scan, set, push, workgroupSize_});  // one workgroup
            calls.push_back({&s.compact, set, push, 0, nullptr, control, offsetof(gpu::WholePathControl, compactGroups)});
        }
        const bool last = g + 1 == path_.generations.size();
        const ComputePipeline* trace = last && s.traceBatch.pipeline ? &s.traceBatch : &s.trace;
        calls.push_back({trace, set, push, 0, last && counters ? buffers_->passCounters() : nullptr, control,
                         offsetof(gpu::WholePathControl, traceGroups)});
        return calls;
    }

    // What the device holds of the generation it last traced: its length, its rays, parents,
    // paths, weights and hits (the first `rays` of each).
    struct Queue {
        gpu::WholePathControl control{};
        std::vector<gpu::Ray> rays;
        std::vector<gpu::HitRecord> hits;
        std::vector<std::uint32_t> parents, paths, weightBits;
    };
    Queue download() {
        Queue q;
        const std::vector<std::uint8_t> control = buffers_->downloadStrategyBuffer(kControl);
        std::memcpy(&q.control, control.data(), sizeof q.control);
        const std::uint32_t n = std::min<std::uint32_t>(q.control.queue.x, std::uint32_t(capacity_.queue));
        q.rays = buffers_->downloadRays();
        q.rays.resize(n);
        q.hits = buffers_->downloadHits();
        q.hits.resize(n);
        const std::vector<std::uint8_t> queue = buffers_->downloadStrategyBuffer(kQueue);
        for (std::uint32_t i = 0; i < n; ++i) {
            std::uint32_t entry[4];
            std::memcpy(entry, queue.data() + 16 * std::size_t(i), 16);
            q.parents.push_back(entry[0]);
            q.paths.push_back(entry[1]);
            q.weightBits.push_back(entry[2]);
        }
        return q;
    }

    GpuBuffers& buffers() { return *buffers_; }
    const BatchPath& path() const { return path_; }
    std::uint64_t queueCapacity() const { return capacity_.queue; }

private:
    VulkanContext& vk_;
    const Structure& structure_;
    const BatchPath& path_;
    std::uint32_t query_;
    unsigned workgroupSize_;
    WholePathCapacity capacity_;
    std::unique_ptr<GpuBuffers> buffers_;
    Stages counted_{}, timed_{};
};

// How the device's generation g differs from the CPU's ("" when it does not): its length, then each
// ray's bits, parent, path, weight and (before the batch) hit record.
std::string generationMismatch(const WavefrontRun::Queue& q, const PathGeneration& cpu, std::size_t g) {
    const std::string which = "generation " + std::to_string(g);
    if (q.control.limits.w) return which + ": a generation outgrew the wavefront's queue or slots (a kernel bug)";
    if (q.rays.size() != cpu.rays->size())
        return which + " has " + std::to_string(q.rays.size()) + " rays on the device and " +
               std::to_string(cpu.rays->size()) + " on the CPU";
    std::uint64_t differing = 0;
    std::string first;
    for (std::uint32_t i = 0; i < q.rays.size(); ++i) {
        const std::uint32_t parent = cpu.parents ? (*cpu.parents)[i] : i;
        const std::uint32_t path = cpu.paths ? (*cpu.paths)[i] : i;
        float weight = cpu.weights ? (*cpu.weights)[i] : 1.0f;
        std::uint32_t weightBits;
        std::memcpy(&weightBits, &weight, 4);
        const char* what = std::memcmp(&q.rays[i], &(*cpu.rays)[i], sizeof(gpu::Ray)) ? "ray"
                           : q.parents[i] != parent                               ? "parent"
                           : q.paths[i] != path                                   ? "path"
                           : q.weightBits[i] != weightBits                        ? "weight"
                           : cpu.hits && recordMismatches({q.hits[i]}, {(*cpu.hits)[i]}) ? "hit record"
                                                                                  : nullptr;
        if (what && differing++ == 0) first = "ray " + std::to_string(i) + "'s " + what;
    }
    if (!differing) return "";
    return which + " (" + std::to_string(differing) + " of " + std::to_string(q.rays.size()) + " rays; first: " + first + ")";
}

// The parts of a repetition the wavefront's timer makes (TimedBatch::parts), each with the column
// of its median.
struct WavefrontStages {
    using K = ColumnKind;
    TimedSeries trace{"kernel_trace", Column<double>({"kernel_ms_trace", K::Timing, "ms", "wavefront: median GPU time of its trace stages per repetition"})};
    TimedSeries shade{"kernel_shade", Column<double>({"kernel_ms_shade", K::Timing, "ms", "wavefront: median GPU time of its shading stages per repetition"})};
    TimedSeries queue{"kernel_queue", Column<double>({"kernel_ms_queue", K::Timing, "ms", "wavefront: median GPU time of its setup, scans and compactions per repetition"})};
};

const WavefrontStages& wavefrontStages() {
    static const WavefrontStages stages;
    return stages;
}

class WavefrontTimer : public KernelTimer {
public:
    WavefrontTimer(VulkanContext& vk, std::unique_ptr<WavefrontRun> run, std::vector<gpu::HitRecord> counted)
        : vk_(vk), run_(std::move(run)), counted_(std::move(counted)) {}
    TimedBatch time(int warmups, int repetitions) override {
        // Repetitions of the whole path recorded into one submission; each dispatch timed on its own.
        Stages& s = run_->stages(false);
        std::vector<VulkanContext::DispatchCall> calls;
        std::vector<int> part;  // each call's part: 0 trace, 1 shade, 2 queue (setup, scan, compaction)
        for (int r = 0; r < warmups + repetitions; ++r)
            for (std::size_t g = 0; g < run_->path().generations.size(); ++g)
                for (const VulkanContext::DispatchCall& c : run_->generationCalls(s, g, false)) {
                    calls.push_back(c);
                    part.push_back(c.pipeline == &s.trace || c.pipeline == &s.traceBatch ? 0 : c.pipeline == &s.shade ? 1 : 2);
                }
        const std::vector<double> ms = vk_.dispatchAll(calls);
        const std::size_t perRepetition = calls.size() / std::size_t(warmups + repetitions);
        TimedBatch batch;
        const WavefrontStages& stages = wavefrontStages();
        batch.parts = {{&stages.trace, {}}, {&stages.shade, {}}, {&stages.queue, {}}};
        for (int r = 0; r < warmups + repetitions; ++r) {
            double total = 0.0, parts[3] = {0.0, 0.0, 0.0};
            for (std::size_t i = r * perRepetition; i < (r + 1) * perRepetition; ++i) {
                total += ms[i];
                parts[part[i]] += ms[i];
            }
            if (r < warmups) {
                batch.warmupMs += total;
                continue;
            }
            batch.ms.push_back(total);
            for (int p = 0; p < 3; ++p) batch.parts[std::size_t(p)].second.push_back(parts[p]);
        }
        return batch;
    }
    void checkHits() override {
        WavefrontRun::Queue q = run_->download();
        expectSameHits(q.hits, counted_, "wavefront");
    }

private:
    VulkanContext& vk_;
    std::unique_ptr<WavefrontRun> run_;
    std::vector<gpu::HitRecord> counted_;
};

// The wavefront's queue size (results schema 19).
const Column<std::uint64_t>& queueCapacityColumn() {
    static const Column<std::uint64_t> column(
        {"wavefront_queue_capacity", ColumnKind::Exact, "rays", "wavefront: rays its queue holds (the camera rays times the passes' fan-outs)", 0.0,
         false, {}, 19});
    return column;
}

StrategyRun runWavefrontStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                 const BatchPath& path, const RunConfig&, const TimingOptions& timing, Row& row) {
    requireTraceablePath(path, "wavefront");
    const unsigned subgroup = vk.info().subgroupSize;
    if (timing.workgroupSize % subgroup || timing.workgroupSize / subgroup > 256)
        throw Error("strategy.workgroup_size " + std::to_string(timing.workgroupSize) +
                    ": the wavefront needs a multiple of the subgroup size " + std::to_string(subgroup) +
                    " and at most 256 subgroups per workgroup");
    auto wavefront = std::make_unique<WavefrontRun>(vk, structure, path, batch.query, timing.workgroupSize);

    // The instrumented run, a generation at a time, each checked against the CPU's before the next.
    StrategyRun run;
    Stages& counted = wavefront->stages(true);
    std::string mismatch;
    WavefrontRun::Queue last;
    for (std::size_t g = 0; g < path.generations.size(); ++g) {
        vk.dispatchAll(wavefront->generationCalls(counted, g, true));
        last = wavefront->download();
        if (mismatch.empty()) mismatch = generationMismatch(last, path.generations[g], g);
    }
    const gpu::PassCounters counters = wavefront->buffers().readPassCounters();
    writeWholePathColumns(path, row);
    put(row, queueCapacityColumn(), wavefront->queueCapacity());

    // The batch's trace is the branching kernel over the batch in its order: judged as branching's.
    BranchingRun kernel;
    kernel.hits = last.hits;
    kernel.hits.resize(batch.rays.size());  // a short queue has failed its check already
    kernel.activeLanes = counters.counts[gpu::kCountActiveLanes];
    kernel.laneSlots = counters.counts[gpu::kCountLaneSlots];
    kernel.timer = std::make_unique<WavefrontTimer>(vk, std::move(wavefront), last.hits);
    run = judgeWholeTraversal(vk, structure, batch, std::move(kernel), row);
    // The generations before the batch ran in subgroups of their own: their loops are checked too.
    for (std::size_t g = 0; g + 1 < path.generations.size(); ++g) {
        const LaneCounts lanes = branchingLaneCounts(structure, *path.generations[g].rays, subgroup,
                                                     loopIterationBudget(vk.info()));
        if (lanes.raysInLongSubgroups && run.truncatedWhy.empty())
            run.truncatedWhy = "generation " + std::to_string(g) + ": " +
                               loopLimitWhy(vk.info(), lanes.maxSubgroupIterations, lanes.raysInLongSubgroups);
        run.truncatedRays += lanes.raysInLongSubgroups;
    }
    put(row, wholeTraversalColumns().raysCutShort, run.truncatedRays);
    if (!mismatch.empty() && run.countsMismatch.empty()) run.countsMismatch = mismatch + " differs";
    return run;
}

}  // namespace

const StrategyType& wavefrontStrategyType() {
    static const StrategyType type = [] {
        const WavefrontStages& stages = wavefrontStages();
        StrategyType t;
        t.name = "wavefront";
        t.help = "the whole path on the device, stage by stage over compacted queues: trace, shade, compact (Laine, Karras & Aila 2013)";
        // The camera rays' copy, a queue entry, a made ray and its flags (fan-out 1).
        t.ownBytesPerRay = sizeof(gpu::Ray) + 16 + sizeof(gpu::Ray) + 16;
        t.series = {&stages.trace, &stages.shade, &stages.queue};
        t.columns = wholePathStrategyColumns({queueCapacityColumn().spec(), stages.trace.median.spec(),
                                              stages.shade.median.spec(), stages.queue.median.spec()});
        t.trace = runWavefrontStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
