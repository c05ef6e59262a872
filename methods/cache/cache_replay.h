// Purcell et al. 2002 Fig. 9: the bandwidth with a texture cache over the bandwidth without, by
// data type, for the branching and the multipass architecture. The CPU reference replays a run's
// rays through a CacheSimulator as "a single pixel wide graphics pipeline" (§4.1): branching,
// ray after ray, each traced whole; multipass, pass after pass, ray after ray through the
// simulator (host control: every pass reads every ray's stencil byte). The kernels' own source
// makes the structure's reads (methods/cache/memory_trace.h); the stream's are the bandwidth
// accounting's (methods/accounting.cpp), so the bytes without the cache must equal its.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "methods/accounting.h"
#include "methods/cache/cache_simulator.h"
#include "strategies/multipass/multipass_schedule.h"
#include "structures/structure.h"
#include "schema/columns.h"
#include "schema/keys.h"

namespace rtbench {

// Buffers at device addresses in this order, each at a boundary of 256 bytes and of the line
// (MemoryTrace::place): the structure's, as bound, then the stream's (rays; multipass: stencil, traversal state, hit state; hit records).
CacheSimulator branchingCacheReplay(const Structure& structure, const std::vector<gpu::Ray>& rays, std::uint32_t query,
                                    const CacheConfig& config);
// Host control only (strategy.control = host); batches of `batchRays` (0: one) one after another.
CacheSimulator multipassCacheReplay(const Structure& structure, const std::vector<gpu::Ray>& rays,
                                    const MultipassOptions& options, std::uint32_t query, std::uint64_t batchRays,
                                    const CacheConfig& config);

// The cache.* keys (read by branching and multipass runs) and the cache_* columns they add.
const std::vector<KeySpec>& cacheKeys();
const std::vector<ColumnSpec>& cacheColumns();
// The run's cache when it asks for the simulation (cache.simulate), else none.
std::optional<CacheConfig> cacheConfig(const RunConfig& run);

// Writes the cache_* columns. Returns what differs between the replay's bytes without the cache
// and the run's bandwidth accounting, by data type ("" when they agree): StrategyRun::modelMismatch.
std::string writeCacheColumns(const CacheSimulator& cache, const Bandwidth& accounted, Row& row);

}  // namespace rtbench
