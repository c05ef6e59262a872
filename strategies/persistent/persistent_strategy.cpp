#include "persistent_strategy.h"

#include "persistent_layout.h"

#include "strategies/branching/branching_strategy.h"
#include "strategies/branching/lane_counts.h"
#include "schema/column.h"
#include "strategies/stream_batches.h"
#include "core/error.h"

namespace rtbench {

PersistentCounts persistentCounts(const PersistentOptions& options, std::uint64_t rays, unsigned workgroupSize,
                                  unsigned subgroupSize) {
    PersistentCounts c;
    if (subgroupSize == 0 || workgroupSize < subgroupSize)
        throw Error("strategy.workgroup_size " + std::to_string(workgroupSize) + " holds no whole subgroup of " +
                    std::to_string(subgroupSize) + " lanes");
    c.raysPerFetch = options.raysPerFetch ? options.raysPerFetch : subgroupSize;
    if (c.raysPerFetch % subgroupSize)
        throw Error("strategy.rays_per_fetch " + std::to_string(c.raysPerFetch) + " is not a multiple of the subgroup size " +
                    std::to_string(subgroupSize));
    c.subgroups = std::uint64_t(options.workgroups) * (workgroupSize / subgroupSize);
    c.handedOut = (rays + c.raysPerFetch - 1) / c.raysPerFetch * c.raysPerFetch;
    c.fetchedWhenDone = c.handedOut + c.subgroups * c.raysPerFetch;
    return c;
}

std::uint64_t persistentMaxFetches(std::uint64_t budget, std::uint64_t walkIterations, std::uint64_t rounds) {
    if (budget == 0) return 0;
    const std::uint64_t perFetch = rounds * (2 * walkIterations + 4) + 2;
    return budget > perFetch ? std::max<std::uint64_t>(1, (budget - 1) / perFetch) : 1;
}

namespace {

// Persistent threads' own columns (results schema 12; persistent_max_fetches 22), declared once,
// here, where they are written.
struct PersistentColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    ColumnGroup group;
    Column<U64> raysPerFetch = group.add<U64>(
        {"persistent_rays_per_fetch", K::Exact, "rays", "persistent: rays a subgroup took per fetch (strategy.rays_per_fetch, 0 made the subgroup size)", 0.0, false, {}, 12});
    Column<U64> maxFetches = group.add<U64>(
        {"persistent_max_fetches", K::Exact, "fetches", "persistent: fetches a subgroup may make (0: until the stream is done); on a device with a loop limit (llvmpipe: 65,535 iterations of all loops together, a workgroup's subgroups run one after another) as many as its longest walks fit, each counted as 2 passes a loop trip (docs/method.md)", 0.0, false, {}, 22});
    Column<U64> fetched = group.add<U64>(
        {"rays_fetched", K::Scheduled, "rays", "persistent: the fetch counter's final value, the batches handed out and the last fetch, which found none, of each subgroup that did not reach persistent_max_fetches (which subgroups reach it is the device's scheduling: the run checks it lies between the batches handed out and those plus a last fetch of every subgroup)", 0.0, false, {}, 12});
    Column<U64> traced = group.add<U64>(
        {"rays_traced", K::Exact, "rays", "persistent: records the kernel wrote (must equal the rays: each traced once)", 0.0, false, {}, 12});
};

const PersistentColumns& persistentColumns() {
    static const PersistentColumns columns;
    return columns;
}

StrategyRun runPersistentStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                  const RunConfig& config, const TimingOptions& timing, Row& row) {
    PersistentOptions options;
    options.workgroups = std::uint32_t(config.getInt("strategy.persistent_workgroups"));
    options.raysPerFetch = std::uint32_t(config.getInt("strategy.rays_per_fetch"));
    const std::uint64_t rays = batch.rays.size();
    const unsigned subgroupSize = vk.info().subgroupSize;
    requireWholeSubgroups(vk, timing.workgroupSize);  // before anything divides by its subgroups
    const PersistentCounts expected = persistentCounts(options, rays, timing.workgroupSize, subgroupSize);
    // The lane model's loop iterations bound the fetches a subgroup may make under the device's
    // loop limit (llvmpipe); the grid must then still hand out every batch.
    const std::uint64_t budget = loopIterationBudget(vk.info());
    const LaneCounts lanes = branchingLaneCounts(structure, batch.rays, subgroupSize, budget, batch.query);
    const std::uint64_t rounds = expected.raysPerFetch / subgroupSize;
    const std::uint64_t maxFetches = persistentMaxFetches(budget, lanes.maxSubgroupIterations, rounds);
    if (maxFetches && lanes.raysInLongSubgroups == 0 && expected.subgroups * maxFetches * expected.raysPerFetch < rays) {
        const std::uint64_t batchesPerWorkgroup = maxFetches * (timing.workgroupSize / subgroupSize);
        const std::uint64_t needed = (expected.handedOut / expected.raysPerFetch + batchesPerWorkgroup - 1) / batchesPerWorkgroup;
        throw Error("persistent threads: " + vk.info().name + " ends a kernel invocation after " +
                    std::to_string(vk.info().loopIterationLimit) + " loop iterations (all loops together) and runs a "
                    "workgroup's subgroups one after another, so a subgroup may make " + std::to_string(maxFetches) +
                    " fetches of " + std::to_string(expected.raysPerFetch) + " rays here (its walks take up to " +
                    std::to_string(lanes.maxSubgroupIterations) + " loop trips a round); " +
                    std::to_string(expected.subgroups) + " subgroups cannot take all " + std::to_string(rays) +
                    " rays: strategy.persistent_workgroups needs at least " + std::to_string(needed));
    }
    TraceLaunch launch;
    launch.kernel = "persistent";
    launch.invocations = std::uint64_t(options.workgroups) * timing.workgroupSize;
    launch.constants = {{gpu::kSpecRaysPerFetch, std::uint32_t(expected.raysPerFetch)},
                        {gpu::kSpecMaxFetches, std::uint32_t(std::min<std::uint64_t>(maxFetches, UINT32_MAX))},
                        {gpu::kSpecPersistentWorkgroups, options.workgroups}};
    launch.countersWhenTimed = true;  // the ray-fetch counter starts at 0 in every dispatch
    BranchingRun kernel = runBranching(vk, structure, batch.rays, timing, batch.query, launch);
    // A stream in batches is a fetch loop per batch: the counter ends where each batch's does.
    std::uint64_t handedOut = 0, fetchedWhenDone = 0;
    for (const auto& [first, end] : streamBatches(rays, kernel.batchRays)) {
        const PersistentCounts c = persistentCounts(options, end - first, timing.workgroupSize, subgroupSize);
        handedOut += c.handedOut;
        fetchedWhenDone += c.fetchedWhenDone;
    }
    const std::uint64_t fetched = kernel.counters.counts[gpu::kCountRaysFetched];
    const std::uint64_t traced = kernel.counters.counts[gpu::kCountRaysTraced];
    const PersistentColumns& c = persistentColumns();
    put(row, c.raysPerFetch, expected.raysPerFetch);
    put(row, c.maxFetches, maxFetches);
    put(row, c.fetched, fetched);
    put(row, c.traced, traced);
    StrategyRun run = judgeWholeTraversal(vk, structure, batch, std::move(kernel), lanes,
                                          "; multipass (a few iterations per pass), a finer grid or the BVH stay within it", row);
    // Every ray traced exactly once: the records are checked against the CPU's; the count of
    // records written must be the ray count, and the fetch counter where every subgroup ended:
    // unbounded, each made a last fetch that found none; bounded, those that reached the bound did not.
    const bool fetchesOff = maxFetches == 0 ? fetched != fetchedWhenDone
                                            : fetched < handedOut || fetched > fetchedWhenDone ||
                                                  (fetched - handedOut) % expected.raysPerFetch != 0;
    if (traced != rays && run.truncatedWhy.empty()) {
        run.truncatedRays = traced < rays ? rays - traced : traced - rays;
        run.truncatedWhy = "persistent threads wrote " + std::to_string(traced) + " records for " + std::to_string(rays) + " rays";
    } else if (fetchesOff) {
        run.countsMismatch = "the fetch counter ended at " + std::to_string(fetched) + ", not " +
                             (maxFetches == 0 ? std::to_string(fetchedWhenDone) + " (" + std::to_string(expected.subgroups) +
                                                    " subgroups each fetching until none is left)"
                                              : "a batch's multiple in [" + std::to_string(handedOut) + ", " +
                                                    std::to_string(fetchedWhenDone) + "] (the batches, and a last fetch of " +
                                                    "each subgroup that did not reach its " + std::to_string(maxFetches) + ")");
    }
    return run;
}

}  // namespace

const StrategyType& persistentStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "persistent";
        t.help = "persistent threads: a fixed grid of workgroups fetching rays from an atomic counter (Aila & Laine 2009)";
        t.keys = {
            {"strategy.persistent_workgroups", ValueType::Int, "persistent: workgroups launched (once; each runs until the stream is done). An H100/H200 holds about 4,224 of 64 invocations at once (132 multiprocessors x 2,048 threads)", std::int64_t(1024), false, 1, 1 << 22},
            {"strategy.rays_per_fetch", ValueType::Int, "persistent: rays a subgroup takes per fetch, a multiple of the subgroup size (0: the subgroup size, one ray per lane as Aila & Laine)", std::int64_t(0), false, 0, 1 << 16},
        };
        for (KeySpec& k : t.keys) k.since = 12;
        t.columns = wholeTraversalColumns().group.specs();
        for (const ColumnSpec& c : persistentColumns().group.specs()) t.columns.push_back(c);
        t.trace = runPersistentStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
