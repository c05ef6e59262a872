// Host side of the branching architecture (Purcell et al. 2002 §5): one dispatch of
// kernels/raycast_branching.comp over the whole ray stream.
#pragma once
#include <vector>

#include "structures/uniform_grid.h"
#include "vulkan_context.h"

namespace rtbench {

struct KernelRun {
    std::vector<gpu::HitRecord> hits;  // from the instrumented dispatch (counters filled)
    std::vector<double> gpuMs;         // timed dispatches (instrumentation off), one per repetition
    double uploadMs = 0.0;             // wall time to create and fill the buffers
};

struct BranchingOptions {
    unsigned workgroupSize = 64;
    int warmups = 1;
    int repetitions = 5;
};

// Uploads grid and rays, runs one instrumented dispatch for hits and counters, then warm-ups and
// timed repetitions with instrumentation off; checks the timed runs' hits equal the counted ones.
KernelRun runBranching(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                       const BranchingOptions& options);

}  // namespace rtbench
