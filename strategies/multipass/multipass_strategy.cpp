#include "multipass_strategy.h"

#include <chrono>
#include <cstddef>
#include <cstring>

#include "device/embedded_kernels.h"
#include "methods/cache/cache_replay.h"
#include "schema/column.h"
#include "strategies/stream_batches.h"
#include "multipass_layout.h"
#include "multipass_simulator.h"
#include "core/error.h"

namespace rtbench {

namespace {

// With the control on the device: the oracle's control block and its pass-log ring, one per batch.
constexpr std::uint64_t kPassControlBytes = sizeof(gpu::PassControl) + gpu::kPassLogEntries * sizeof(gpu::PassLogEntry);

struct Pipelines {
    VulkanContext& vk;
    std::array<ComputePipeline, kPassKinds> byKind{};
    ComputePipeline oracle{};  // strategy.control = "device"
    Pipelines(VulkanContext& v, GpuBuffers& buffers, const std::string& prefix, const KernelSpec& spec,
              bool deviceControl)
        : vk(v) {
        static const char* names[kPassKinds] = {"multipass_setup", "multipass_traverse", "multipass_intersect",
                                                "multipass_write"};
        for (int k = 0; k < kPassKinds; ++k) byKind[k] = buffers.createKernel(prefix + "_" + names[k], spec);
        if (deviceControl) oracle = buffers.createKernel(prefix + "_multipass_oracle", spec);
    }
    ~Pipelines() {
        for (ComputePipeline& p : byKind) vk.destroy(p);
        if (oracle.pipeline) vk.destroy(oracle);
    }
};

// Multipass's slots among the strategy's (GpuBuffers::strategyBuffer).
constexpr std::uint32_t kTraversalSlot = gpu::kBindingTraversal - gpu::kBindingStrategy;
constexpr std::uint32_t kPassControlSlot = gpu::kBindingPassControl - gpu::kBindingStrategy;
static_assert(gpu::kBindingStencil == gpu::kBindingStrategy && gpu::kBindingTraversal == gpu::kBindingStencil + 1 &&
                  gpu::kBindingHitState == gpu::kBindingTraversal + 1 &&
                  gpu::kBindingRayCounters == gpu::kBindingHitState + 1 &&
                  gpu::kBindingRayLists == gpu::kBindingRayCounters + 1 &&
                  gpu::kBindingPassControl == gpu::kBindingRayLists + 1,
              "multipassBuffers lists the slots in order");

// A pass's sums from its PassCounters slots (counts: kCountTraversing..kCountStackEntries at least).
PassSums passSums(const std::uint64_t* counts) {
    PassSums sums;
    sums.traversing = counts[gpu::kCountTraversing];
    sums.waiting = counts[gpu::kCountWaiting];
    sums.useful = counts[gpu::kCountUsefulRays];
    sums.stencilWrites = counts[gpu::kCountStencilWrites];
    sums.structureReads = counts[gpu::kCountStructureReads];
    sums.triangleReads = counts[gpu::kCountTriangleReads];
    sums.stackEntries = counts[gpu::kCountStackEntries];
    return sums;
}

// The series multipass's timer makes (harness/timing_rounds.h), each with the column of its median:
// the replay's pass kinds and the oracle as parts of a repetition, and the live loop.
struct MultipassSeries {
    using K = ColumnKind;
    TimedSeries setup{"kernel_setup", Column<double>({"kernel_ms_setup", K::Timing, "ms", "multipass: GPU time of the setup passes, median (with strategy.control = host: in the replay, kernel_ms_replay)"})};
    TimedSeries traverse{"kernel_traverse", Column<double>({"kernel_ms_traverse", K::Timing, "ms", "multipass: GPU time of the traverse passes, median (with strategy.control = host: in the replay, kernel_ms_replay)"})};
    TimedSeries intersect{"kernel_intersect", Column<double>({"kernel_ms_intersect", K::Timing, "ms", "multipass: GPU time of the intersect passes, median (with strategy.control = host: in the replay, kernel_ms_replay)"})};
    TimedSeries write{"kernel_write", Column<double>({"kernel_ms_write", K::Timing, "ms", "multipass: GPU time of the write pass, median (with strategy.control = host: in the replay, kernel_ms_replay)"})};
    TimedSeries stencilPass{"kernel_stencil_pass", Column<double>({"kernel_ms_stencil_pass", K::Timing, "ms", "multipass with strategy.control = host: GPU time of one more traverse pass over the stream when every ray is done (after the write pass, not in kernel_ms): what the ray-state test alone costs a pass, which Christen 2005 §5.5's early-z culling paid a masking pass for (not counted in passes_total: our kernels test the state byte themselves, bytes_stencil), median", 0.0, false, {"strategy.control=host"}, 17})};
    TimedSeries oracle{"kernel_oracle", Column<double>({"kernel_ms_oracle", K::Timing, "ms", "multipass with strategy.control = device: GPU time of the oracle kernel (one invocation after each pass), median", 0.0, false, {"strategy.control=device"}, 13})};
    TimedSeries replay{"kernel_replay", Column<double>({"kernel_ms_replay", K::Timing, "ms", "multipass with strategy.control = host: GPU time of the live loop's pass sequence replayed in one submission without the oracle's read-backs (before results schema 25, the headline kernel_ms), median", 0.0, false, {"strategy.control=host"}, 25})};
    TimedSeries live{"multipass_live", Column<double>({"multipass_live_ms_median", K::Timing, "ms", "multipass: host wall time of the instrumented live pass loop, median of one per round: with strategy.control = host the instrumented passes with the oracle's read-back after each (Christen 2005 §4.3.4's CPU-controlled loop); with device, the instrumented loop in submissions of 341 oracle iterations (the last partly idle), its control block and log read after each, and the log's replay on the host", 0.0, false, {}, 5})};
    std::vector<const TimedSeries*> all() const { return {&setup, &traverse, &intersect, &write, &stencilPass, &oracle, &replay, &live}; }
};

const MultipassSeries& multipassSeries() {
    static const MultipassSeries series;
    return series;
}

// The parts a repetition's GPU time is split into: the pass kinds, and the oracle kernel when it
// runs on the device or, with the host's control, the state-test pass.
constexpr int kOraclePart = kPassKinds;
const TimedSeries& partSeries(int part, bool deviceControl) {
    const MultipassSeries& s = multipassSeries();
    const TimedSeries* parts[kPassKinds + 1] = {&s.setup, &s.traverse, &s.intersect, &s.write,
                                                deviceControl ? &s.oracle : &s.stencilPass};
    return *parts[part];
}

// ---- strategy.control = "device" ----
// The control block and pass log (slot kBindingPassControl) and the two indirect passes.
const Buffer& controlBuffer(const GpuBuffers& buffers) { return buffers.strategyBuffer(kPassControlSlot); }
constexpr VkDeviceSize kTraverseGroupsOffset = offsetof(gpu::PassControl, traverseGroups);
constexpr VkDeviceSize kIntersectGroupsOffset = offsetof(gpu::PassControl, intersectGroups);
// Oracle iterations recorded per submission: three dispatches each (dispatchAll's chunk).
constexpr std::uint64_t kIterationsPerRound = VulkanContext::kDispatchesPerSubmit / 3;

// The device-controlled loop's dispatches, each with its part: the setup pass (which first zeroes
// the control block and the pass counters: the loop's start), then `iterations` times the oracle
// and both indirect passes (the one the oracle did not choose has no workgroups, and after the
// loop's end neither has), then the write pass when `write`.
void deviceLoopCalls(const Pipelines& p, GpuBuffers& b, bool setup, std::uint64_t iterations, bool write,
                     std::vector<VulkanContext::DispatchCall>& calls, std::vector<int>& parts) {
    auto call = [&](const ComputePipeline& pipeline, std::uint64_t invocations, int part) {
        calls.push_back({&pipeline, b.descriptorSet(pipeline), b.pushConstants(), invocations});
        parts.push_back(part);
        return &calls.back();
    };
    if (setup) call(p.byKind[int(PassKind::Setup)], b.rayCount(), int(PassKind::Setup))->zeroFirst = {&controlBuffer(b), &b.passCounterBuffer()};
    for (std::uint64_t i = 0; i < iterations; ++i) {
        call(p.oracle, 1, kOraclePart);
        VulkanContext::DispatchCall* traverse = call(p.byKind[int(PassKind::Traverse)], 0, int(PassKind::Traverse));
        traverse->indirect = &controlBuffer(b), traverse->indirectOffset = kTraverseGroupsOffset;
        VulkanContext::DispatchCall* intersect = call(p.byKind[int(PassKind::Intersect)], 0, int(PassKind::Intersect));
        intersect->indirect = &controlBuffer(b), intersect->indirectOffset = kIntersectGroupsOffset;
    }
    if (write) call(p.byKind[int(PassKind::Write)], b.rayCount(), int(PassKind::Write));
}

gpu::PassControl readControl(VulkanContext& vk, const GpuBuffers& buffers) {
    gpu::PassControl c;
    vk.download(controlBuffer(buffers), &c, sizeof c);
    return c;
}

// The instrumented device-controlled loop: submissions of kIterationsPerRound oracle iterations
// until the oracle has ended the loop, then the write pass. After each submission the host reads
// the control block and the log entries of the passes it ran (the log is a ring of
// kPassLogEntries, more than a submission's passes); at the end it replays the log through
// runPassLoop: each pass the device ran must be the one the host's scheduler chooses on the same
// counts, and the device's ray lists must hold the rays those counts say are active.
MultipassCounts runDeviceLoop(VulkanContext& vk, GpuBuffers& buffers, Pipelines& pipelines,
                              const MultipassOptions& options, std::uint64_t cap) {
    static_assert(kIterationsPerRound < gpu::kPassLogEntries, "a submission's passes must fit the log ring");
    gpu::PassControl control{};
    std::vector<gpu::PassLogEntry> log;
    std::vector<std::uint8_t> bytes(kPassControlBytes);
    for (std::uint64_t iterations = 0; !control.status.y;) {
        if (iterations > cap)
            throw Error("multipass (device): the oracle kernel had not ended the loop after " + std::to_string(iterations) +
                        " iterations, over the pass cap of " + std::to_string(cap));
        std::vector<VulkanContext::DispatchCall> calls;
        std::vector<int> parts;
        deviceLoopCalls(pipelines, buffers, iterations == 0, kIterationsPerRound, false, calls, parts);
        vk.dispatchAll(calls);
        iterations += kIterationsPerRound;
        vk.download(controlBuffer(buffers), bytes.data(), bytes.size());
        std::memcpy(&control, bytes.data(), sizeof control);
        for (std::uint64_t p = log.size(); p < control.current.w; ++p) {
            gpu::PassLogEntry e;
            std::memcpy(&e, bytes.data() + sizeof(gpu::PassControl) + (p % gpu::kPassLogEntries) * sizeof e, sizeof e);
            log.push_back(e);
        }
    }
    if (control.status.w)
        throw Error("multipass (device): a ray list held more rays than the stream's " + std::to_string(buffers.rayCount()) +
                    " after pass " + std::to_string(control.current.w) + " (a kernel filed rays twice)");
    if (control.status.z) {  // the oracle kernel ended the loop at the cap (multipass_oracle.comp)
        const std::uint64_t active = log.empty() ? 0 : std::uint64_t(log.back().kindLists.y) + log.back().kindLists.z;
        throw Error("multipass (device): the oracle kernel stopped the loop at the pass cap of " + std::to_string(cap) +
                    " after " + std::to_string(control.current.w) + " passes, with " + std::to_string(active) +
                    " rays still active");
    }
    vk.dispatch(pipelines.byKind[int(PassKind::Write)], buffers.descriptorSet(pipelines.byKind[int(PassKind::Write)]),
                buffers.pushConstants(), buffers.rayCount());
    const std::uint64_t passes = control.current.w;  // setup included, write not

    std::size_t next = 0;  // the log entry of the pass the replay runs next
    std::uint64_t dispatched = 0;
    const MultipassCounts counts = runPassLoop(
        options, cap, buffers.rayCount(),
        [&](PassKind kind) {
            if (kind == PassKind::Write) return PassSums{};
            if (next == log.size())
                throw Error("multipass (device): the oracle kernel ended the loop after " + std::to_string(passes) +
                            " passes; the host's scheduler on the device's counts runs a " + passKindName(kind) + " pass next");
            const gpu::PassLogEntry& e = log[next++];
            if (e.kindLists.x != std::uint32_t(kind))
                throw Error("multipass (device): pass " + std::to_string(next) + " was a " +
                            passKindName(PassKind(std::min<std::uint32_t>(e.kindLists.x, 3))) +
                            " pass; the host's scheduler on the device's counts chooses " + passKindName(kind));
            if (kind != PassKind::Setup) dispatched += e.kindLists.w;
            return passSums(e.sums);
        },
        [&](std::uint64_t traversing, std::uint64_t waiting) {
            const gpu::PassLogEntry& e = log[next - 1];
            if (e.kindLists.y != traversing || e.kindLists.z != waiting)
                throw Error("multipass (device): after pass " + std::to_string(next) + " the ray lists hold " +
                            std::to_string(e.kindLists.y) + " traversing and " + std::to_string(e.kindLists.z) +
                            " waiting rays; the rays' own counts say " + std::to_string(traversing) + " and " +
                            std::to_string(waiting));
        });
    if (next != log.size())
        throw Error("multipass (device): the oracle kernel ran " + std::to_string(passes) + " passes; the host's scheduler " +
                    std::to_string(next) + " on the same counts");
    if (dispatched != counts.streamSlots)
        throw Error("multipass (device): the passes were dispatched for " + std::to_string(dispatched) +
                    " list entries; their lists held " + std::to_string(counts.streamSlots));
    return counts;
}

// The instrumented run of the pass loop with the control on the host: after each pass the host
// reads the ray-state counts (the oracle's occlusion query) and the event counts.
MultipassCounts runHostLoop(VulkanContext& vk, GpuBuffers& buffers, Pipelines& pipelines, const MultipassOptions& options,
                          std::uint64_t cap) {
    return runPassLoop(options, cap, buffers.rayCount(), [&](PassKind kind) {
        const ComputePipeline& p = pipelines.byKind[static_cast<int>(kind)];
        vk.dispatch(p, buffers.descriptorSet(p), buffers.pushConstants(), buffers.rayCount(), buffers.passCounters());
        return passSums(buffers.readPassCounters().counts);
    });
}

MultipassCounts runLoop(VulkanContext& vk, GpuBuffers& buffers, Pipelines& pipelines, const MultipassOptions& options,
                        std::uint64_t cap) {
    return options.deviceControl ? runDeviceLoop(vk, buffers, pipelines, options, cap)
                                 : runHostLoop(vk, buffers, pipelines, options, cap);
}

// Multipass's own counts, declared once, here, where they are written: the passes by kind
// (Purcell et al. 2002 §4.2), and the check against the branching caster with the batch size.
struct MultipassColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    ColumnGroup passes;
    Column<U64> setup = passes.add<U64>({"passes_setup", K::Exact, "passes", "multipass setup passes"});
    Column<U64> traverse = passes.add<U64>({"passes_traverse", K::Exact, "passes", "multipass traverse passes"});
    Column<U64> intersect = passes.add<U64>({"passes_intersect", K::Exact, "passes", "multipass intersect passes"});
    Column<U64> write = passes.add<U64>({"passes_write", K::Exact, "passes", "multipass write passes"});
    Column<U64> lowerBound = passes.add<U64>({"passes_lower_bound", K::Exact, "passes", "Purcell's lower bound on traverse + intersect passes"});
    ColumnGroup run;
    Column<U64> branchingMismatches = run.add<U64>({"branching_mismatches", K::Exact, "rays", "multipass: rays whose hit record differs from the branching caster's"});
    Column<U64> batchRays = run.add<U64>(
        {"multipass_batch_rays", K::Exact, "rays", "multipass: rays per batch (strategy.batch_rays, 0 made what one binding holds); passes_* add up over the batches", 0.0, false, {}, 12});
};

const MultipassColumns& multipassColumns() {
    static const MultipassColumns columns;
    return columns;
}

StrategyRun runMultipassStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                 const RunConfig& config, const TimingOptions& timing, Row& row) {
    const std::vector<gpu::Ray>& rays = batch.rays;
    const MultipassOptions options = multipassOptions(config);
    MultipassRun kernel = runMultipass(vk, structure, rays, options, timing, batch.query);
    StrategyRun run;
    run.metrics = multipassMetrics(kernel.hits, kernel.counts, options, structure.costs());
    const std::string prefix = structure.kernelPrefix() + "_multipass_";
    run.metrics.instructions = multipassInstructions(
        {embeddedKernel(prefix + "setup"), embeddedKernel(prefix + "traverse"), embeddedKernel(prefix + "intersect"),
         embeddedKernel(prefix + "write")},
        kernelEvents(structure, run.metrics.work), kernel.counts, rays.size());
    const MultipassColumns& c = multipassColumns();
    put(row, c.batchRays, std::min<std::uint64_t>(kernel.batchRays, rays.size()));
    const MultipassResult cpu = simulateMultipass(structure, rays, options, batch.query, kernel.batchRays);
    run.cpuMismatches = recordMismatches(kernel.hits, cpu.hits);
    if (!(cpu.counts == kernel.counts)) run.countsMismatch = "pass sequence or event counts differ";
    // The two architectures must produce identical hit records (and work counters).
    run.branchingMismatches = recordMismatches(kernel.hits, structure.trace(rays, batch.query));
    put(row, c.branchingMismatches, run.branchingMismatches);
    put(row, c.setup, run.metrics.passesSetup);
    put(row, c.traverse, run.metrics.passesTraverse);
    put(row, c.intersect, run.metrics.passesIntersect);
    put(row, c.write, run.metrics.passesWrite);
    put(row, c.lowerBound, run.metrics.passesLowerBound);
    if (const auto cache = cacheConfig(config))
        run.modelMismatch = writeCacheColumns(
            multipassCacheReplay(structure, rays, options, batch.query, kernel.batchRays, *cache), run.metrics.bytes, row);
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
    if (run.has("strategy.oracle_basis")) o.oracleBasis = run.getString("strategy.oracle_basis");
    o.maxPasses = std::uint64_t(run.getInt("strategy.max_passes"));
    o.batchRays = std::uint64_t(run.getInt("strategy.batch_rays"));
    o.deviceControl = run.getString("strategy.control") == "device";
    if (o.deviceControl) o.listPartitions = unsigned(run.getInt("strategy.list_partitions"));
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
        timed_ = std::make_unique<Pipelines>(vk, *buffers_, prefix, spec, options.deviceControl);
    }
    // Device control: the loop as the device runs it, oracle included, in one submission. Host
    // control: the live loop (Christen 2005 §4.3.4's CPU-controlled loop, what a frame costs),
    // with the replay's GPU time as the part kernel_ms_replay and its pass kinds as the others.
    TimedBatch time(int warmups, int repetitions) override {
        TimedBatch batch = replay(warmups, repetitions);
        if (options_.deviceControl) return batch;
        batch.parts.push_back({&multipassSeries().replay, std::move(batch.ms)});
        batch.ms.clear();
        batch.warmupMs = 0.0;
        for (int i = 0; i < warmups; ++i) batch.warmupMs += liveLoopMs();
        for (int i = 0; i < repetitions; ++i) batch.ms.push_back(liveLoopMs());
        return batch;
    }
    TimedBatch replay(int warmups, int repetitions) {
        // One repetition's dispatches. Host control: the oracle's choices depend only on the rays
        // and the structure, so the replay runs the counted sequence. Device control: the oracle
        // kernel chooses again, one iteration per pass the instrumented run ran (setup included:
        // the last ends the loop). Warm-ups and repetitions go in one submission (in chunks), every
        // dispatch timed on its own; the hits must equal the instrumented run's (checkHits).
        // Host control also times, after the write pass, one traverse pass more over the stream
        // whose rays are all done: the ray-state test alone (Christen 2005 §5.5 paid a masking
        // pass before each pass for it); not in the repetition's total.
        std::vector<VulkanContext::DispatchCall> calls;
        std::vector<int> parts;
        if (options_.deviceControl)
            deviceLoopCalls(*timed_, *buffers_, true, counts_.sequence.size() - 1, true, calls, parts);
        else {
            for (PassKind kind : counts_.sequence) {
                const ComputePipeline& p = timed_->byKind[static_cast<int>(kind)];
                calls.push_back({&p, buffers_->descriptorSet(p), buffers_->pushConstants(), buffers_->rayCount()});
                parts.push_back(static_cast<int>(kind));
            }
            const ComputePipeline& traverse = timed_->byKind[static_cast<int>(PassKind::Traverse)];
            calls.push_back({&traverse, buffers_->descriptorSet(traverse), buffers_->pushConstants(), buffers_->rayCount()});
            parts.push_back(kPassKinds);
        }
        const std::size_t perRepetition = calls.size();
        const std::vector<VulkanContext::DispatchCall> one = calls;
        for (int i = 1; i < warmups + repetitions; ++i) calls.insert(calls.end(), one.begin(), one.end());
        const std::vector<double> ms = vk_.dispatchAll(calls);
        if (options_.deviceControl) {
            const gpu::PassControl c = readControl(vk_, *buffers_);
            if (!c.status.y || c.status.z || c.current.w + 1 != counts_.sequence.size())
                throw Error("multipass (device): a timed repetition " + std::string(c.status.y ? "ran " : "had not ended after ") +
                            std::to_string(c.current.w) + " passes (setup included); the instrumented run " +
                            std::to_string(counts_.sequence.size() - 1));
        }
        const int partCount = kPassKinds + 1;  // and the oracle (device control) or the state-test pass (host)
        TimedBatch batch;
        for (std::size_t i = 0; i < std::size_t(warmups) * perRepetition; ++i) batch.warmupMs += ms[i];
        for (int k = 0; k < partCount; ++k)
            batch.parts.push_back({&partSeries(k, options_.deviceControl), {}});
        for (int i = warmups; i < warmups + repetitions; ++i) {
            std::vector<double> byPart(std::size_t(partCount), 0.0);
            for (std::size_t c = 0; c < perRepetition; ++c) byPart[std::size_t(parts[c])] += ms[std::size_t(i) * perRepetition + c];
            double total = 0.0;
            for (int k = 0; k < partCount; ++k) {
                batch.parts[std::size_t(k)].second.push_back(byPart[std::size_t(k)]);
                if (k < kPassKinds || options_.deviceControl) total += byPart[std::size_t(k)];
            }
            batch.ms.push_back(total);
        }
        return batch;
    }
    HostLoopTimes timeHostLoops() override {
        const auto start = std::chrono::steady_clock::now();
        const MultipassCounts live = runLoop(vk_, *buffers_, *counted_, options_, cap_);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (!(live == counts_))
            throw Error("multipass: the live pass loop ran another pass sequence than the first instrumented run "
                        "on the same rays (" + std::to_string(live.sequence.size()) + " passes against " +
                        std::to_string(counts_.sequence.size()) + ")");
        return {{&multipassSeries().live, ms}};
    }
    // Host control: the uninstrumented passes with the oracle's read-back of the ray-state counts
    // after each (they keep those counts: multipass_common.glsl mpReport), host wall time. Its pass
    // sequence must be the instrumented run's.
    double liveLoopMs() {
        const auto start = std::chrono::steady_clock::now();
        const MultipassCounts live = runHostLoop(vk_, *buffers_, *timed_, options_, cap_);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (live.sequence != counts_.sequence)
            throw Error("multipass: the timed live pass loop ran another pass sequence than the instrumented run on the "
                        "same rays (" + std::to_string(live.sequence.size()) + " passes against " +
                        std::to_string(counts_.sequence.size()) + ")");
        return ms;
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

// One batch's instrumented run and its timer. `shared`: the structure on the device for every
// batch (null: this stream's own).
MultipassRun runMultipassBatch(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                               const MultipassOptions& options, const TimingOptions& timing, std::uint32_t query,
                               const std::shared_ptr<const DeviceStructure>& shared) {
    MultipassRun run;
    const std::uint64_t cap = multipassPassCap(structure, options);
    if (options.deviceControl && cap > 0xFFFFFFFFull)
        throw Error("multipass (device): the pass cap " + std::to_string(cap) + " is over 2^32 - 1");
    const std::vector<BufferSize> own =
        multipassBuffers(rays.size(), structure.costs().traversalStateBytes, options.deviceControl, options.listPartitions);
    auto buffers = shared ? std::make_unique<GpuBuffers>(vk, rays, shared, structure.params(), own)
                          : std::make_unique<GpuBuffers>(vk, rays, structure.buffers(), structure.params(), own);
    KernelSpec spec = structureKernelSpec(structure, timing.workgroupSize, query,
                                          {{gpu::kSpecTraverseSteps, options.traverseStepsPerPass},
                                           {gpu::kSpecIntersections, options.intersectionsPerPass},
                                           {gpu::kSpecSuppress, options.suppressFinishedReads ? 1u : 0u}});
    if (options.deviceControl)
        spec.strategyConstants.insert(spec.strategyConstants.end(),
                                      {{gpu::kSpecCompact, 1u},
                                       {gpu::kSpecOracleThreshold, oracleThresholdQ31(options.oracleThreshold)},
                                       {gpu::kSpecNaive, options.scheduling == "naive" ? 1u : 0u},
                                       {gpu::kSpecPassCap, std::uint32_t(cap)},
                                       {gpu::kSpecMaxGroupsX, vk.info().maxWorkGroupCountX},
                                       {gpu::kSpecOracleAllRays, options.oracleBasis == "all" ? 1u : 0u},
                                       {gpu::kSpecListPartitions, options.listPartitions}});
    auto counted = std::make_unique<Pipelines>(vk, *buffers, structure.kernelPrefix(), spec, options.deviceControl);
    run.counts = runLoop(vk, *buffers, *counted, options, cap);
    run.hits = buffers->downloadHits();
    run.traversalStates = downloadTraversalStates(*buffers);
    run.timer = std::make_unique<MultipassTimer>(vk, std::move(buffers), std::move(counted), structure.kernelPrefix(), spec,
                                                 options, cap, run.counts, run.hits);
    return run;
}


}  // namespace

std::uint64_t multipassListBytes(std::uint64_t rays, unsigned partitions) {
    return 4 * std::uint64_t(partitions) * sizeof(std::uint32_t) * rays;
}

std::vector<BufferSize> multipassBuffers(std::uint64_t rays, std::uint64_t traversalStateBytes, bool deviceControl,
                                         unsigned listPartitions, std::uint64_t batches) {
    const std::string n = " (" + std::to_string(rays) + " rays)";
    std::vector<BufferSize> own = {{"ray state" + n, rays},
                                   {"traversal state" + n, rays * traversalStateBytes},
                                   {"hit state" + n, rays * sizeof(gpu::RayHitState)},
                                   {"ray counter" + n, rays * sizeof(gpu::RayCounters)}};
    if (deviceControl)
        own.insert(own.end(),
                   {{"multipass ray lists (4 x " + std::to_string(listPartitions) + " x " + std::to_string(rays) + " rays)",
                     multipassListBytes(rays, listPartitions)},
                    {"multipass oracle control and pass log" +
                         (batches > 1 ? " x " + std::to_string(batches) + " batches" : std::string()),
                     kPassControlBytes * batches}});
    return own;
}

std::vector<std::uint8_t> downloadTraversalStates(GpuBuffers& buffers) {
    return buffers.downloadStrategyBuffer(kTraversalSlot);
}

std::uint64_t multipassBatchRays(const DeviceInfo& device, std::uint64_t traversalStateBytes, std::uint64_t requested,
                                 unsigned workgroupSize, std::uint64_t listBytesPerRay) {
    if (requested) return requested;
    // The largest per-ray record of the batch's bindings (rayBufferSizes): the ray, the hit record,
    // the structure's traversal state (the BVH's: 144 bytes with its stack) or the ray lists.
    return raysPerBinding(
        device, std::max<std::uint64_t>({sizeof(gpu::Ray), sizeof(gpu::HitRecord), traversalStateBytes, listBytesPerRay}),
        workgroupSize);
}

MultipassRun runMultipass(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                          const MultipassOptions& options, const TimingOptions& timing, std::uint32_t query) {
    if (options.traverseStepsPerPass < 1 || options.intersectionsPerPass < 1)
        throw Error("multipass: traverse_steps_per_pass and intersections_per_pass must be at least 1");
    const std::uint64_t batchRays =
        multipassBatchRays(vk.info(), structure.costs().traversalStateBytes, options.batchRays, timing.workgroupSize,
                           options.deviceControl ? multipassListBytes(1, options.listPartitions) : 0);
    MultipassRun run;
    if (batchRays >= rays.size()) {
        run = runMultipassBatch(vk, structure, rays, options, timing, query, nullptr);
    } else {
        // Rays in batches (each its own buffers and pass loop, the oracle's passes per batch): the
        // per-ray records and events are those of one stream; the passes add up over the batches.
        const std::size_t batches = streamBatches(rays.size(), batchRays).size();
        // Every batch's buffers together: the stream's per-ray ones, and an oracle block per batch.
        std::vector<BufferSize> perRay = rayBufferSizes(rays.size());
        const std::vector<BufferSize> own =
            multipassBuffers(rays.size(), structure.costs().traversalStateBytes, options.deviceControl,
                             options.listPartitions, batches);
        perRay.insert(perRay.end(), own.begin(), own.end());
        const auto shared = uploadForBatches(vk, perRay, structure.buffers());
        run.batches = 0;
        run.timer = traceInBatches(
            rays, batchRays,
            [&](const std::vector<gpu::Ray>& part) { return runMultipassBatch(vk, structure, part, options, timing, query, shared); },
            [&](const MultipassRun& b) {
                run.hits.insert(run.hits.end(), b.hits.begin(), b.hits.end());
                run.traversalStates.insert(run.traversalStates.end(), b.traversalStates.begin(), b.traversalStates.end());
                run.counts += b.counts;
                ++run.batches;
            });
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
        StrategyType t;
        t.name = "multipass";
        t.help = "a pass per traverse/intersect step with a ray-state stencil and an oracle (Purcell et al. 2002 §3.2)";
        for (const BufferSize& b : multipassBuffers(1, /*the smallest traversal state, brute force's:*/ 16, false))
            t.ownBytesPerRay += b.bytes;
        t.keys = {
            {"strategy.traverse_steps_per_pass", ValueType::Int, "multipass: traversal steps per traverse pass, K (Purcell 2002: 1 in Table 2 and Figs. 7-8; 4 in his loop-unrolling experiment, §4.2)", std::int64_t(1), false, 1, 64},
            {"strategy.intersections_per_pass", ValueType::Int, "multipass: triangle tests per intersect pass, M (Purcell 2002: 1 in Table 2 and Figs. 7-8; 2 in his loop-unrolling experiment, §4.2)", std::int64_t(1), false, 1, 64},
            {"strategy.suppress_finished_reads", ValueType::Bool, "multipass: rays that finish mid-pass skip the unrolled rest's reads", false},
            {"strategy.scheduling", ValueType::String, "multipass: oracle (threshold on the waiting fraction) or naive, Christen 2005 §5.6's naive sequencing (traverse until none traverses, then intersect until none waits; not Purcell's \"naive algorithm\", which is oracle_threshold = 0)", std::string("oracle"), false, -1e300, 1e300, {"oracle", "naive"}},
            {"strategy.oracle_threshold", ValueType::Float, "multipass: intersect when waiting / active rays >= this (0: as soon as any waits, Purcell 2002's \"naive algorithm\"; 0.2: his \"20% of the rays\", read as 20% of the active rays)", 0.2, false, 0, 1, {}, {"strategy.scheduling=oracle"}},
            {"strategy.oracle_basis", ValueType::String, "multipass: what the oracle's waiting fraction is of: active (traversing + waiting rays, Purcell 2002 §3.2's \"percentage of rays requiring intersection vs. traversal\") or all (every ray of the stream, finished ones included: another reading of his and Christen 2005 §5.5's \"20% of the rays\")", std::string("active"), false, -1e300, 1e300, {"active", "all"}, {"strategy.scheduling=oracle"}},
            {"strategy.max_passes", ValueType::Int, "multipass: pass cap (0: derived from the structure); reaching it fails the run", std::int64_t(0), false, 0, 1e9},
            {"strategy.control", ValueType::String, "multipass: who runs the oracle. host: the CPU reads the ray-state counts back after every pass and each pass walks the whole stream through the stencil (Purcell's and Christen's loop); device: an oracle kernel chooses the next pass and writes its indirect dispatch, and each pass serves a compacted list of its rays, with no host round trip per pass", std::string("host"), false, -1e300, 1e300, {"host", "device"}},
            {"strategy.list_partitions", ValueType::Int, "multipass with strategy.control = device: partitions of each compacted ray list, each with its own length and room for every ray. A pass's workgroups append to them in equal runs (the first 1/n of the dispatch's workgroups to partition 0, and so on), and the next pass reads them in order, so workgroups that run side by side append to different lengths and, pass after pass, serve disjoint sets of rays; lavapipe hands each of its worker threads such a run. 1: one list per state, every append on one atomic", std::int64_t(2), false, 1, double(gpu::kMaxListPartitions), {}, {"strategy.control=device"}},
            {"strategy.batch_rays", ValueType::Int, "multipass: rays per batch, each its own pass loop (0: as many as one binding holds, maxStorageBufferRange over the largest per-ray record)", std::int64_t(0), false, 0, 1e12},
        };
        for (KeySpec& k : t.keys) {
            if (k.name == "strategy.batch_rays") k.since = 12;
            if (k.name == "strategy.control") k.since = 13;
            if (k.name == "strategy.oracle_basis") k.since = 14;
            if (k.name == "strategy.list_partitions") k.since = 20;
        }
        // The pass counts, the timer's series (harness/run_metrics.cpp writes their medians), the checks.
        t.columns = multipassColumns().passes.specs();
        t.series = multipassSeries().all();
        for (const TimedSeries* series : t.series) t.columns.push_back(series->median.spec());
        for (const ColumnSpec& c : multipassColumns().run.specs()) t.columns.push_back(c);
        t.kernelMeasureChanges = {{25, {"strategy.control=host"},
                                   "kernel_ms of multipass with the oracle on the host is its live loop from results schema 25 "
                                   "on, the replayed passes before"}};
        t.trace = runMultipassStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
