#include "megakernel_strategy.h"

#include "megakernel_layout.h"
#include "megakernel_model.h"
#include "schema/column.h"
#include "strategies/branching/branching_strategy.h"

namespace rtbench {

namespace {

// The megakernel's state executions (OptiX Fig. 6), the device's and the CPU model's (results
// schema 12), declared once, here, where they are written.
struct MegakernelColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    ColumnGroup group;
    Column<U64> runsTraverse = group.add<U64>(
        {"megakernel_runs_traverse", K::Exact, "executions", "megakernel: subgroup executions of the traverse state (one traversal step for the lanes in it; OptiX Fig. 6's state executions, per subgroup)", 0.0, false, {}, 12});
    Column<U64> runsIntersect = group.add<U64>(
        {"megakernel_runs_intersect", K::Exact, "executions", "megakernel: subgroup executions of the intersect state (one triangle test for the lanes in it)", 0.0, false, {}, 12});
    Column<U64> modelRuns = group.add<U64>(
        {"megakernel_model_runs", K::Exact, "executions", "megakernel: state executions of the CPU model of the schedule (equal to the device's two; a difference fails the run)", 0.0, false, {}, 12});
};

const MegakernelColumns& megakernelColumns() {
    static const MegakernelColumns columns;
    return columns;
}

StrategyRun runMegakernelStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                  const RunConfig& config, const TimingOptions& timing, Row& row) {
    const std::vector<gpu::Ray>& rays = batch.rays;
    const std::uint32_t schedule = megakernelSchedule(config.getString("strategy.schedule"));
    TraceLaunch launch;
    launch.kernel = "megakernel";
    launch.constants = {{gpu::kSpecSchedule, schedule}};
    BranchingRun kernel = runBranching(vk, structure, rays, timing, batch.query, launch);
    const MegakernelCounts model =
        megakernelCounts(structure, rays, vk.info().subgroupSize, schedule, batch.query, loopIterationBudget(vk.info()));
    const std::uint64_t runsTraverse = kernel.counters.counts[gpu::kCountRunsTraverse];
    const std::uint64_t runsIntersect = kernel.counters.counts[gpu::kCountRunsIntersect];
    const MegakernelColumns& c = megakernelColumns();
    put(row, c.runsTraverse, runsTraverse);
    put(row, c.runsIntersect, runsIntersect);
    put(row, c.modelRuns, model.runsTraverse + model.runsIntersect);
    StrategyRun run;
    run.metrics = branchingMetrics(kernel.hits, kernel.activeLanes, kernel.laneSlots, structure.costs());
    // The state machine's records are the branching caster's, counters too.
    run.cpuMismatches = recordMismatches(kernel.hits, structure.trace(rays, batch.query));
    if (runsTraverse != model.runsTraverse || runsIntersect != model.runsIntersect ||
        kernel.activeLanes != model.activeLanes || kernel.laneSlots != model.laneSlots)
        run.countsMismatch = "state executions or lanes (" + std::to_string(runsTraverse) + " + " +
                             std::to_string(runsIntersect) + " executions, " + std::to_string(kernel.activeLanes) + "/" +
                             std::to_string(kernel.laneSlots) + " lanes on the device; " +
                             std::to_string(model.runsTraverse) + " + " + std::to_string(model.runsIntersect) + ", " +
                             std::to_string(model.activeLanes) + "/" + std::to_string(model.laneSlots) +
                             " in the CPU model) differ";
    run.truncatedRays = model.raysInLongSubgroups;
    put(row, wholeTraversalColumns().raysCutShort, run.truncatedRays);
    put(row, wholeTraversalColumns().streamBatches, kernel.batches);
    if (run.truncatedRays) run.truncatedWhy = loopLimitWhy(vk.info(), model.maxSubgroupIterations, run.truncatedRays);
    run.hits = std::move(kernel.hits);
    run.timer = std::move(kernel.timer);
    return run;
}

}  // namespace

const StrategyType& megakernelStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "megakernel";
        t.help = "one kernel stepping each ray's state machine, the subgroup choosing the state it runs (OptiX, Parker et al. 2013 §5)";
        t.keys = {{"strategy.schedule", ValueType::String,
                   "megakernel: the states a subgroup runs each iteration: switch (every state present, one after another: "
                   "SIMT serialisation of a divergent switch, OptiX §5.1), intersect_first or traverse_first (one state by a "
                   "fixed priority, §5.2; which priority OptiX used is not stated), majority (the state more lanes are in)",
                   std::string("intersect_first"), false, -1e300, 1e300, {"switch", "intersect_first", "traverse_first", "majority"}}};
        t.keys.back().since = 12;
        t.columns.push_back(wholeTraversalColumns().raysCutShort.spec());
        t.columns.push_back(wholeTraversalColumns().streamBatches.spec());
        for (const ColumnSpec& c : megakernelColumns().group.specs()) t.columns.push_back(c);
        t.trace = runMegakernelStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
