#include "sorted_strategy.h"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "strategies/branching/branching_strategy.h"
#include "schema/column.h"

namespace rtbench {

namespace {

// Spreads the low 10 bits of v to every third bit (bit i to bit 3i).
std::uint32_t spreadBits(std::uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

// A coordinate's 10-bit cell in [lo, hi] (the last cell includes hi; a flat box is one cell).
std::uint32_t cellOf(float x, float lo, float hi) {
    if (!(hi > lo)) return 0;
    const double cell = double(x - lo) / double(hi - lo) * 1024.0;
    return std::uint32_t(std::clamp(cell, 0.0, 1023.0));
}

std::uint64_t sortKey(const gpu::Ray& ray, const glm::vec3& lo, const glm::vec3& hi) {
    const std::uint32_t octant = (ray.directionTMax.x < 0.0f ? 4u : 0u) | (ray.directionTMax.y < 0.0f ? 2u : 0u) |
                                 (ray.directionTMax.z < 0.0f ? 1u : 0u);
    const std::uint32_t morton = (spreadBits(cellOf(ray.originTMin.x, lo.x, hi.x)) << 2) |
                                 (spreadBits(cellOf(ray.originTMin.y, lo.y, hi.y)) << 1) |
                                 spreadBits(cellOf(ray.originTMin.z, lo.z, hi.z));
    return (std::uint64_t(octant) << 30) | morton;
}

// The sort's own columns (results schema 29), declared once, here, where they are written.
struct SortedColumns {
    ColumnGroup group;
    Column<double> sortMs = group.add<double>(
        {"sorted_sort_ms", ColumnKind::Timing, "ms",
         "sorted: host wall time of the keys and the stable sort of the batch's rays (once per run; not in kernel_ms)",
         0.0, false, {}, 29}, 4);
    Column<std::uint64_t> raysMoved = group.add<std::uint64_t>(
        {"sorted_rays_moved", ColumnKind::Exact, "rays",
         "sorted: rays the sort put at another place than the batch's (0: the batch was in coherent order already)",
         0.0, false, {}, 29});
};

const SortedColumns& sortedColumns() {
    static const SortedColumns columns;
    return columns;
}

StrategyRun runSorted(VulkanContext& vk, const Structure& structure, const RayBatch& batch, const RunConfig&,
                      const TimingOptions& timing, Row& row) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::uint32_t> order = coherentOrder(batch.rays);
    const RayBatch sorted = inOrder(batch, order);
    put(row, sortedColumns().sortMs, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    std::uint64_t moved = 0;
    for (std::size_t i = 0; i < order.size(); ++i) moved += order[i] != i;
    put(row, sortedColumns().raysMoved, moved);

    // Traced and judged as branching is, on the rays in their new order: records against rtTrace,
    // lanes against the model.
    StrategyRun run = traceBranching(vk, structure, sorted, timing, row);
    run.hits = inBatchOrder(run.hits, order);
    return run;
}

}  // namespace

std::vector<std::uint32_t> coherentOrder(const std::vector<gpu::Ray>& rays) {
    glm::vec3 lo(0.0f), hi(0.0f);
    if (!rays.empty()) lo = hi = glm::vec3(rays[0].originTMin);
    for (const gpu::Ray& r : rays) {
        lo = glm::min(lo, glm::vec3(r.originTMin));
        hi = glm::max(hi, glm::vec3(r.originTMin));
    }
    std::vector<std::uint64_t> keys(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) keys[i] = sortKey(rays[i], lo, hi);
    std::vector<std::uint32_t> order(rays.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
    return order;
}

const StrategyType& sortedStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "sorted";
        t.help = "the branching kernel over the batch's rays sorted by direction octant, then origin Morton code "
                 "(Garanzha & Loop 2010's ray sorting); hits returned in the batch's order, the sort timed on its own";
        t.columns = wholeTraversalColumns().group.specs();
        for (const ColumnSpec& c : sortedColumns().group.specs()) t.columns.push_back(c);
        t.trace = runSorted;
        return t;
    }();
    return type;
}

}  // namespace rtbench
