// The branching strategy (Purcell et al. 2002 §5's branching architecture): one dispatch of
// strategies/branching/branching.comp over the whole ray stream, each invocation running the structure's
// whole traversal.
#pragma once
#include "strategies/branching/lane_counts.h"
#include "schema/column.h"
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& branchingStrategyType();

struct BranchingRun {
    std::vector<gpu::HitRecord> hits;  // from the instrumented run (counters filled)
    std::vector<double> gpuMs;         // total GPU time of each timed repetition `timing` asked for
    std::uint64_t activeLanes = 0, laneSlots = 0;  // subgroup ballots of the instrumented run
    gpu::PassCounters counters{};                  // every counter of the instrumented run
    std::unique_ptr<KernelTimer> timer;            // more timed repetitions, on the same buffers
    std::uint64_t batchRays = 0;                   // rays per dispatch (wholeTraversalBatchRays, or the stream)
    std::uint64_t batches = 1;                     // dispatches the stream ran in
};

// Rays per dispatch of a whole-traversal kernel: what one binding holds of the ray and hit records
// (maxStorageBufferRange / 32 bytes), in whole workgroups. A longer stream runs in batches.
std::uint64_t wholeTraversalBatchRays(const DeviceInfo& device, unsigned workgroupSize);

// A kernel that runs each ray's whole traversal in one invocation (kernels/trace_whole.glsl), as
// one dispatch: the branching kernel by default; persistent threads launch fewer invocations, each
// fetching rays, with constants of their own.
struct TraceLaunch {
    std::string kernel = "branching";  // the kernel file's name; the structure's prefix is added
    std::uint64_t invocations = 0;     // 0: one per ray
    std::vector<SpecializationConstant> constants;  // the strategy's own (KernelSpec::strategyConstants)
    std::uint64_t batchRays = 0;  // rays per dispatch, a multiple of the workgroup size (0: wholeTraversalBatchRays)
    // The kernel reads the pass counters uninstrumented too (persistent threads fetch rays through
    // one): they are zeroed before every timed dispatch and read back after it (outside its timestamps).
    bool countersWhenTimed = false;
};

// The device's subgroup lane counts (active lanes / lane slots of its ballots) against the CPU
// lane model's, which assumes lock-step loops. Where the device runs subgroups in lock step
// (DeviceInfo::lockStepSubgroups) a difference is a wrong count: `mismatch` says what differs and
// fails the run. Elsewhere the model is not the device's measure: `warning` says so (the
// SIMD-efficiency columns are the device's) and the run stands.
struct LaneVerdict {
    std::string mismatch, warning;
};
LaneVerdict judgeLaneCounts(const DeviceInfo& device, std::uint64_t deviceActive, std::uint64_t deviceSlots,
                            std::uint64_t modelActive, std::uint64_t modelSlots);

// Uploads structure and rays, runs one instrumented dispatch for hits and counters (a dispatch per
// batch of wholeTraversalBatchRays when the stream is longer: hits and counters as of one), then the
// warm-ups and timed repetitions `timing` asks for (none: the timer does them later) with
// instrumentation off; checks the timed runs' hits equal the counted ones. `query`: gpu::kQuery*.

// Kernels that share a subgroup's work (ballots, fetches) need whole subgroups in a workgroup:
// throws naming strategy.workgroup_size unless it is a positive multiple of the subgroup size.
void requireWholeSubgroups(const VulkanContext& vk, unsigned workgroupSize);

BranchingRun runBranching(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                          const TimingOptions& timing, std::uint32_t query = gpu::kQueryClosest,
                          const TraceLaunch& launch = {});

// The loop iterations a subgroup may run before the device ends its invocation (DeviceInfo::
// loopIterationLimit), less a margin for the fixed loops around a walk; 0 where none is known.
std::uint64_t loopIterationBudget(const DeviceInfo& device);
// Why a run fails whose subgroups need `iterations` loop iterations, leaving up to `rays` rays unfinished.
std::string loopLimitWhy(const DeviceInfo& device, std::uint64_t iterations, std::uint64_t rays);

// Judges a whole-traversal kernel's instrumented run (branching, persistent threads): its records
// against the structure's rtTrace on the same rays, its subgroup ballots against the lock-step lane
// model (judgeLaneCounts), its subgroups' loop iterations against the device's limit; writes the
// columns of wholeTraversalColumns() to `row`.
StrategyRun judgeWholeTraversal(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                BranchingRun&& kernel, Row& row);
// The branching strategy's trace of `batch` without its cache replay: runBranching judged by
// judgeWholeTraversal, with the kernel's instruction estimate (a variant that traces the same
// kernel over other rays, the sorted one, calls it).
StrategyRun traceBranching(VulkanContext& vk, const Structure& structure, const RayBatch& batch, const TimingOptions& timing,
                           Row& row);
// The same against the counts of another lane model, `model` (a kernel whose lanes each trace
// several rays: the path megakernel, pathLaneCounts); `longLoops` follows loopLimitWhy's text in
// the message of a run cut short.
StrategyRun judgeWholeTraversal(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                BranchingRun&& kernel, const LaneCounts& model, const std::string& longLoops, Row& row);
// What judgeWholeTraversal writes, declared once for every strategy that writes some of them:
// rays_cut_short, the lane model's lanes_model_*, and stream_batches (BranchingRun::batches, for
// every strategy that runs through runBranching). Each strategy lists the ones it writes.
struct WholeTraversalColumns {
    ColumnGroup group;
    Column<std::uint64_t> raysCutShort = group.add<std::uint64_t>(
        {"rays_cut_short", ColumnKind::Exact, "rays",
         "branching, persistent, megakernel, wavefront, path_megakernel: rays in subgroups needing more loop iterations than the device runs (a failed run; llvmpipe: 65,535)"});
    Column<std::uint64_t> lanesModelActive = group.add<std::uint64_t>(
        {"lanes_model_active", ColumnKind::Exact, "lanes",
         "branching, persistent, wavefront (the batch's trace), path_megakernel: active lanes summed over the subgroup ballots "
         "as the CPU lane model counts them (lock-step loops; equal to the device's on llvmpipe, where a difference fails the "
         "run; elsewhere a warning)", 0.0, false, {}, 11});
    Column<std::uint64_t> lanesModelSlots = group.add<std::uint64_t>(
        {"lanes_model_slots", ColumnKind::Exact, "lanes",
         "branching, persistent, wavefront, path_megakernel: subgroup size summed over the same ballots, as the CPU lane model counts them",
         0.0, false, {}, 11});
    Column<std::uint64_t> streamBatches = group.add<std::uint64_t>(
        {"stream_batches", ColumnKind::Exact, "dispatches",
         "branching, plain, persistent, megakernel, ray_query, wavefront, path_megakernel: dispatches the ray stream ran in, each of whole workgroups, one "
         "after another (more than 1 when one binding cannot hold its ray or hit records); records and counts are as of one", 0.0, false, {}, 13});
};
const WholeTraversalColumns& wholeTraversalColumns();

}  // namespace rtbench
