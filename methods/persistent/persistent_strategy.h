// Persistent threads with dynamic ray fetch (Aila & Laine 2009): methods/persistent/persistent.comp,
// a fixed grid of workgroups whose subgroups take batches of rays from an atomic counter until the
// stream is done, each lane running its ray's whole traversal as the branching kernel does.
#pragma once
#include "methods/strategy.h"

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
    std::uint64_t fetchedWhenDone = 0;  // the fetch counter's final value
};
PersistentCounts persistentCounts(const PersistentOptions& options, std::uint64_t rays, unsigned workgroupSize,
                                  unsigned subgroupSize);

}  // namespace rtbench
