// Host side of the multipass (non-branching) architecture, Purcell et al. 2002 §3.2: a setup
// pass, then traverse or intersect passes chosen by the oracle from the ray-state counts read
// back after each pass, then a write pass. Each pass is one dispatch over the whole stream.
#pragma once
#include <array>
#include <vector>

#include "branching_strategy.h"
#include "structures/multipass_reference.h"

namespace rtbench {

struct MultipassRun {
    std::vector<gpu::HitRecord> hits;  // instrumented run, per-ray counters filled
    MultipassCounts counts;            // instrumented run
    std::vector<double> gpuMs;         // total GPU time of each timed repetition
    std::vector<std::array<double, kPassKinds>> gpuMsByKind;  // per timed repetition, per PassKind
};

// One instrumented run, then warm-ups and timed repetitions (instrumentation off; the pass
// sequence must repeat exactly). Throws rtbench::Error when the pass cap is reached.
MultipassRun runMultipass(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                          const MultipassOptions& options, const TimingOptions& timing);

}  // namespace rtbench
