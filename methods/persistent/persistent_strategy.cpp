#include "persistent_strategy.h"

#include "methods/branching/branching_strategy.h"
#include "methods/stream_batches.h"
#include "structures/error.h"

namespace rtbench {

PersistentCounts persistentCounts(const PersistentOptions& options, std::uint64_t rays, unsigned workgroupSize,
                                  unsigned subgroupSize) {
    PersistentCounts c;
    c.raysPerFetch = options.raysPerFetch ? options.raysPerFetch : subgroupSize;
    if (c.raysPerFetch % subgroupSize)
        throw Error("strategy.rays_per_fetch " + std::to_string(c.raysPerFetch) + " is not a multiple of the subgroup size " +
                    std::to_string(subgroupSize));
    c.subgroups = std::uint64_t(options.workgroups) * (workgroupSize / subgroupSize);
    c.fetchedWhenDone = (rays + c.raysPerFetch - 1) / c.raysPerFetch * c.raysPerFetch + c.subgroups * c.raysPerFetch;
    return c;
}

namespace {

StrategyRun runPersistentStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                  const RunConfig& config, const TimingOptions& timing, Row& row) {
    PersistentOptions options;
    options.workgroups = std::uint32_t(config.getInt("strategy.persistent_workgroups"));
    options.raysPerFetch = std::uint32_t(config.getInt("strategy.rays_per_fetch"));
    const std::uint64_t rays = batch.rays.size();
    const PersistentCounts expected = persistentCounts(options, rays, timing.workgroupSize, vk.info().subgroupSize);
    TraceLaunch launch;
    launch.kernel = "persistent";
    launch.invocations = std::uint64_t(options.workgroups) * timing.workgroupSize;
    launch.constants = {{gpu::kSpecRaysPerFetch, std::uint32_t(expected.raysPerFetch)}};
    launch.countersWhenTimed = true;  // the ray-fetch counter starts at 0 in every dispatch
    BranchingRun kernel = runBranching(vk, structure, batch.rays, timing, batch.query, launch);
    // A stream in batches is a fetch loop per batch: the counter ends where each batch's does.
    std::uint64_t fetchedWhenDone = 0;
    for (const auto& [first, end] : streamBatches(rays, kernel.batchRays))
        fetchedWhenDone += persistentCounts(options, end - first, timing.workgroupSize, vk.info().subgroupSize).fetchedWhenDone;
    const std::uint64_t fetched = kernel.counters.counts[gpu::kCountRaysFetched];
    const std::uint64_t traced = kernel.counters.counts[gpu::kCountRaysTraced];
    row["persistent_rays_per_fetch"] = std::to_string(expected.raysPerFetch);
    row["rays_fetched"] = std::to_string(fetched);
    row["rays_traced"] = std::to_string(traced);
    StrategyRun run = judgeWholeTraversal(vk, structure, batch, std::move(kernel), row);
    if (vk.info().driver.find("llvmpipe Mesa 22.") != std::string::npos)
        run.faultNote = "Mesa 22.3's llvmpipe loses rays of the persistent kernel on all but small dispatches; Mesa "
                        "25.0.7's runs the same dispatches right: docs/method.md";
    // Every ray traced exactly once: the records are checked against the CPU's; the count of
    // records written must be the ray count, and the fetch counter where every subgroup ended.
    if (traced != rays && run.truncatedWhy.empty()) {
        run.truncatedRays = traced < rays ? rays - traced : traced - rays;
        run.truncatedWhy = "persistent threads wrote " + std::to_string(traced) + " records for " + std::to_string(rays) + " rays";
    } else if (fetched != fetchedWhenDone) {
        run.countsMismatch = "the fetch counter ended at " + std::to_string(fetched) + ", not " +
                             std::to_string(fetchedWhenDone) + " (" + std::to_string(expected.subgroups) +
                             " subgroups each fetching until none is left)";
    }
    return run;
}

}  // namespace

const StrategyType& persistentStrategyType() {
    static const StrategyType type = [] {
        using K = ColumnKind;
        StrategyType t;
        t.name = "persistent";
        t.help = "persistent threads: a fixed grid of workgroups fetching rays from an atomic counter (Aila & Laine 2009)";
        t.keys = {
            {"strategy.persistent_workgroups", ValueType::Int, "persistent: workgroups launched (once; each runs until the stream is done). An H100/H200 holds about 4,224 of 64 invocations at once (132 multiprocessors x 2,048 threads)", std::int64_t(1024), false, 1, 1 << 22},
            {"strategy.rays_per_fetch", ValueType::Int, "persistent: rays a subgroup takes per fetch, a multiple of the subgroup size (0: the subgroup size, one ray per lane as Aila & Laine)", std::int64_t(0), false, 0, 1 << 16},
        };
        for (KeySpec& k : t.keys) k.since = 12;
        t.columns = wholeTraversalColumns();
        for (ColumnSpec c : std::vector<ColumnSpec>{
                 {"persistent_rays_per_fetch", K::Count, "rays", "persistent: rays a subgroup took per fetch (strategy.rays_per_fetch, 0 made the subgroup size)"},
                 {"rays_fetched", K::Count, "rays", "persistent: the fetch counter's final value, the batches handed out and each subgroup's last fetch that found none"},
                 {"rays_traced", K::Count, "rays", "persistent: records the kernel wrote (must equal the rays: each traced once)"}}) {
            c.since = 12;
            t.columns.push_back(c);
        }
        t.run = runPersistentStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
