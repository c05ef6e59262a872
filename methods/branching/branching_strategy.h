// The branching strategy (Purcell et al. 2002 §5's branching architecture): one dispatch of
// kernels/branching.comp over the whole ray stream, each invocation running the structure's
// whole traversal.
#pragma once
#include "methods/strategy.h"

namespace rtbench {

const StrategyType& branchingStrategyType();

struct BranchingRun {
    std::vector<gpu::HitRecord> hits;  // from the instrumented run (counters filled)
    std::vector<double> gpuMs;         // total GPU time of each timed repetition `timing` asked for
    std::uint64_t activeLanes = 0, laneSlots = 0;  // subgroup ballots of the instrumented run
    std::unique_ptr<KernelTimer> timer;            // more timed repetitions, on the same buffers
};

// Uploads structure and rays, runs one instrumented dispatch for hits and counters, then the
// warm-ups and timed repetitions `timing` asks for (none: the timer does them later) with
// instrumentation off; checks the timed runs' hits equal the counted ones. `query`: gpu::kQuery*.
BranchingRun runBranching(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                          const TimingOptions& timing, std::uint32_t query = gpu::kQueryClosest);

}  // namespace rtbench
