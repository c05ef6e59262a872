#include "branching_strategy.h"

#include "structures/error.h"

namespace rtbench {

void expectSameHits(const std::vector<gpu::HitRecord>& timed, const std::vector<gpu::HitRecord>& counted,
                    const char* strategy) {
    for (std::size_t i = 0; i < timed.size(); ++i)
        if (timed[i].primitive != counted[i].primitive || timed[i].t != counted[i].t)
            throw Error(std::string(strategy) + ": the timed run's hit for ray " + std::to_string(i) +
                        " differs from the instrumented one (nondeterministic kernel?)");
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
