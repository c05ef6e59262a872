// The plain twin of the branching kernel (strategy.type = "plain"): strategies/branching/branching.comp
// as it is, but dividing as the device does (OpFDiv, which Vulkan lets err by 2.5 ULP) instead of
// through rtDivide's double quotient. It is the control for issue 18 §2's question, what rtbench's
// bit-exact division costs: the same traversal, rays and buffers, less that one constraint. Its
// hits are judged against the exact reference (and Embree), as the driver's are; the records that
// differ from the CPU reference's (which divides exactly) are counted, not failed.
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& plainStrategyType();

// Rays whose hit (distance, triangle, barycentrics) differs between two record streams; the work
// counters are not compared.
std::uint64_t hitMismatches(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b);

}  // namespace rtbench
