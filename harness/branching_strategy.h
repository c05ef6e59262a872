// Host side of the branching architecture (Purcell et al. 2002 §5): one dispatch of
// kernels/raycast_branching.comp over the whole ray stream.
#pragma once
#include <vector>

#include "gpu_buffers.h"

namespace rtbench {

struct TimingOptions {
    unsigned workgroupSize = 64;
    int warmups = 1;
    int repetitions = 5;
};

struct KernelRun {
    std::vector<gpu::HitRecord> hits;  // from the instrumented run (counters filled)
    std::vector<double> gpuMs;         // total GPU time of each timed repetition
    // Branching: lane counts of the subgroup ballots (instrumented run).
    std::uint64_t activeLanes = 0, laneSlots = 0;
};

// Uploads grid and rays, runs one instrumented dispatch for hits and counters, then warm-ups and
// timed repetitions with instrumentation off; checks the timed runs' hits equal the counted ones.
KernelRun runBranching(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                       const TimingOptions& options);

// Throws, with the count of differing rays, when a timed run's hits differ from the instrumented
// run's (t and primitive); a NaN distance is named as what it is, an out-of-range input.
void expectSameHits(const std::vector<gpu::HitRecord>& timed, const std::vector<gpu::HitRecord>& counted,
                    const char* strategy);

}  // namespace rtbench
