#include "plain_strategy.h"

#include "strategies/branching/branching_strategy.h"
#include "strategies/ray_query/ray_query_strategy.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {

std::uint64_t hitMismatches(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b) {
    if (a.size() != b.size()) throw Error("hitMismatches: record streams of different lengths");
    std::uint64_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        differing += a[i].primitive != b[i].primitive || a[i].t != b[i].t || a[i].u != b[i].u || a[i].v != b[i].v;
    return differing;
}

namespace {

// Rays the plain kernel's hits differ from the CPU reference's on (results schema 15).
const Column<std::uint64_t>& plainCpuDiffering() {
    static const Column<std::uint64_t> column(
        {"plain_cpu_differing", ColumnKind::Exact, "rays",
         "plain: rays whose hit (t, triangle, u, v) differs from the CPU reference's, which divides exactly "
         "(0 where the device's division is IEEE's, as on llvmpipe; counted, not failed)", 0.0, false, {}, 15});
    return column;
}

StrategyRun runPlain(VulkanContext& vk, const Structure& structure, const RayBatch& batch, const RunConfig&,
                     const TimingOptions& timing, Row& row) {
    TraceLaunch launch;
    launch.constants = {{gpu::kSpecNativeDivision, 1u}};
    BranchingRun kernel = runBranching(vk, structure, batch.rays, timing, batch.query, launch);
    put(row, plainCpuDiffering(), hitMismatches(kernel.hits, structure.trace(batch.rays, batch.query)));
    put(row, wholeTraversalColumns().streamBatches, kernel.batches);
    StrategyRun run;
    run.hits = std::move(kernel.hits);
    run.timer = std::move(kernel.timer);
    // The device's own division may take another path through the structure than the CPU model's:
    // its work is not the model's to state, and its accuracy is the exact reference's to judge.
    judgeByTheExactReference(batch.rays, run, "the plain kernel");
    return run;
}

}  // namespace

const StrategyType& plainStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "plain";
        t.help = "the branching kernel dividing as the device does (OpFDiv) instead of exactly: the control that measures "
                 "what bit-exact division costs; judged against the exact reference, no work counted";
        t.columns = {plainCpuDiffering().spec(), wholeTraversalColumns().streamBatches.spec()};
        t.trace = runPlain;
        return t;
    }();
    return type;
}

}  // namespace rtbench
