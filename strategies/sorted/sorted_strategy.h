// The branching kernel over the batch's rays sorted for coherence (strategy.type = "sorted"): the
// rays ordered by their direction's octant, then by the Morton code of their origin in the
// batch's origin box (ray sorting as in Garanzha & Loop 2010, "Fast ray sorting and breadth-first
// packet traversal for GPU ray tracing", hashing origin and direction), so that a subgroup's lanes
// start near each other and head the same way. The same kernel, structure and rays as branching,
// in another order: what the order alone changes in lane utilisation, SIMD efficiency and time.
// The hits go back to the batch's order; the sort runs on the host, timed on its own
// (sorted_sort_ms), not in kernel_ms.
#pragma once
#include <cstdint>
#include <vector>

#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& sortedStrategyType();

// The order the strategy traces `rays` in: order[i] is the batch's index of the i-th ray traced.
// Keys: the direction's octant (3 bits: x, y, z negative), then the origin's 30-bit Morton code
// (10 bits per axis over the rays' origin box); equal keys keep the batch's order.
std::vector<std::uint32_t> coherentOrder(const std::vector<gpu::Ray>& rays);

}  // namespace rtbench
