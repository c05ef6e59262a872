// Persistent threads with dynamic ray fetch (Aila & Laine 2009): strategies/persistent/persistent.comp,
// a fixed grid of workgroups whose subgroups take batches of rays from an atomic counter until the
// stream is done, each lane running its ray's whole traversal as the branching kernel does.
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& persistentStrategyType();

struct PersistentOptions {
    std::uint32_t workgroups = 1024;  // launched once; each fetches until the stream is done
    std::uint32_t raysPerFetch = 0;   // per subgroup fetch, a multiple of the subgroup size; 0: the subgroup size
};

// What the counters of a persistent run must read when every subgroup ran to the end: each fetch
// below the ray count hands out a batch, and each subgroup makes one more that finds none.
struct PersistentCounts {
    std::uint64_t raysPerFetch = 0;
    std::uint64_t subgroups = 0;
    std::uint64_t handedOut = 0;        // the batches' rays: the counter's end if no subgroup fetched again
    std::uint64_t fetchedWhenDone = 0;  // the fetch counter's final value
};
PersistentCounts persistentCounts(const PersistentOptions& options, std::uint64_t rays, unsigned workgroupSize,
                                  unsigned subgroupSize);

// Fetches one subgroup may make under a device's loop budget (loopIterationBudget; 0: no limit,
// and so no bound: 0). llvmpipe ends an invocation after its loop limit, all loops together, and
// runs a workgroup's subgroups one after another, so one subgroup can take most of the stream.
// llvmpipe counts a loop's every pass through its header, the pass that leaves it too: a walk of t
// trips (the lane model's most loop iterations of one subgroup, `walkIterations`) enters its loops
// at most t + 1 times (the triangle loop once per trip of the outer one), so it counts at most
// 2t + 1 (measured: 179 for a walk of 72 voxels and 30 tests, t = 102); with 3 for the fixed loops
// around it, 2t + 4 a round, and 2 for the round loop's and the fetch loop's own passes. The
// subgroup's final fetch, which finds none, costs one more. At least 1.
std::uint64_t persistentMaxFetches(std::uint64_t budget, std::uint64_t walkIterations, std::uint64_t rounds);

}  // namespace rtbench
