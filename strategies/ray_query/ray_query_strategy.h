// The driver's own ray tracing as a peer method (strategy.type = "ray_query"): one invocation per
// ray asks VK_KHR_ray_query for the query's answer over the driver's acceleration structure
// (structure.type = "driver"), in strategies/ray_query/kernels/ray_query.comp. The driver's
// arithmetic is not rtbench's: its hits are judged against the exact reference and Embree, as
// Embree's are, not bit for bit against a CPU re-implementation, and it counts no work.
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& rayQueryStrategyType();

// Why `device` cannot run the driver's ray query ("" when it can): the run fails at once with it.
std::string rayQueryRefusal(const DeviceInfo& device);

// Hits the driver reports outside the query's interval [tMin, tMax) of their ray, or a miss
// whose distance is not kNoHitT: rays whose record cannot be an answer, and the first of them.
struct ImpossibleHits {
    std::uint64_t rays = 0;
    std::uint64_t first = 0;
};
ImpossibleHits impossibleHits(const std::vector<gpu::Ray>& rays, const std::vector<gpu::HitRecord>& hits);

// Judges `run.hits` as Embree's are, for a kernel whose arithmetic is not rtbench's CPU reference's
// (the driver's, the plain twin's OpFDiv): throws, naming `who`, when an answer lies outside its
// ray's interval (impossibleHits); counts the hits; marks the run's work and its CPU comparison
// unknown, to be judged by the exact reference.
void judgeByTheExactReference(const std::vector<gpu::Ray>& rays, StrategyRun& run, const std::string& who);

}  // namespace rtbench
