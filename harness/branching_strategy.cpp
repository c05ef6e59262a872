#include "branching_strategy.h"

#include <cmath>

#include "structures/error.h"
#include "structures/scene_limits.h"

namespace rtbench {

void expectSameHits(const std::vector<gpu::HitRecord>& timed, const std::vector<gpu::HitRecord>& counted,
                    const char* strategy) {
    std::uint64_t differing = 0;
    std::size_t first = 0;
    for (std::size_t i = 0; i < timed.size(); ++i) {
        if (std::isnan(timed[i].t) || std::isnan(counted[i].t))
            throw Error(std::string(strategy) + ": ray " + std::to_string(i) +
                        " has a NaN hit distance: its ray-triangle arithmetic overflowed, so the scene or the ray "
                        "lies outside the range the kernels handle (" + rayRangeText() + ")");
        if ((timed[i].primitive != counted[i].primitive || timed[i].t != counted[i].t) && differing++ == 0) first = i;
    }
    if (differing)
        throw Error(std::string(strategy) + ": the timed run's hits differ from the instrumented run's on " +
                    std::to_string(differing) + " of " + std::to_string(timed.size()) + " rays (first: ray " +
                    std::to_string(first) + ", t " + std::to_string(timed[first].t) + " vs " +
                    std::to_string(counted[first].t) + "): the kernel gives different results on the same input");
}

KernelRun runBranching(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                       const TimingOptions& options) {
    KernelRun run;
    GpuBuffers buffers(vk, grid, rays, /*multipassState=*/false);
    KernelSpec spec;
    spec.workgroupSize = options.workgroupSize;
    {
        ComputePipeline counted = createKernel(vk, "raycast_branching", spec);
        vk.dispatch(counted, buffers.descriptorSet(counted), &buffers.params(), rays.size());
        vk.destroy(counted);
        run.hits = buffers.downloadHits();
        const gpu::PassCounters c = buffers.readPassCounters();
        run.activeLanes = c.counts[gpu::kCountActiveLanes];
        run.laneSlots = c.counts[gpu::kCountLaneSlots];
    }
    spec.instrument = false;
    ComputePipeline timed = createKernel(vk, "raycast_branching", spec);
    for (int i = 0; i < options.warmups; ++i) vk.dispatch(timed, buffers.descriptorSet(timed), &buffers.params(), rays.size());
    for (int i = 0; i < options.repetitions; ++i)
        run.gpuMs.push_back(vk.dispatch(timed, buffers.descriptorSet(timed), &buffers.params(), rays.size()));
    vk.destroy(timed);
    expectSameHits(buffers.downloadHits(), run.hits, "branching kernel");
    return run;
}

}  // namespace rtbench
