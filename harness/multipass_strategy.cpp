#include "multipass_strategy.h"

#include "structures/error.h"

namespace rtbench {

namespace {

struct Pipelines {
    VulkanContext& vk;
    std::array<ComputePipeline, kPassKinds> byKind{};
    Pipelines(VulkanContext& v, const KernelSpec& spec) : vk(v) {
        static const char* names[kPassKinds] = {"multipass_setup", "multipass_traverse", "multipass_intersect",
                                                "multipass_write"};
        for (int k = 0; k < kPassKinds; ++k) byKind[k] = createKernel(vk, names[k], spec);
    }
    ~Pipelines() {
        for (ComputePipeline& p : byKind) vk.destroy(p);
    }
};

// One run of the whole pass loop; the counts beyond the oracle's are filled when instrumented.
MultipassCounts runPasses(VulkanContext& vk, GpuBuffers& buffers, Pipelines& pipelines, const MultipassOptions& options,
                          std::uint64_t cap, std::array<double, kPassKinds>& msByKind) {
    msByKind.fill(0.0);
    return runPassLoop(options, cap, [&](PassKind kind) {
        buffers.resetPassCounters();
        const ComputePipeline& p = pipelines.byKind[static_cast<int>(kind)];
        msByKind[static_cast<int>(kind)] += vk.dispatch(p, buffers.descriptorSet(p), &buffers.params(), buffers.rayCount());
        const gpu::PassCounters c = buffers.readPassCounters();
        PassSums sums;
        sums.traversing = c.counts[gpu::kCountTraversing];
        sums.waiting = c.counts[gpu::kCountWaiting];
        sums.useful = c.counts[gpu::kCountUsefulRays];
        sums.stencilWrites = c.counts[gpu::kCountStencilWrites];
        sums.offsetReads = c.counts[gpu::kCountOffsetReads];
        sums.triangleReads = c.counts[gpu::kCountTriangleReads];
        return sums;
    });
}

}  // namespace

MultipassRun runMultipass(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                          const MultipassOptions& options, const TimingOptions& timing) {
    if (options.traverseStepsPerPass < 1 || options.intersectionsPerPass < 1)
        throw Error("multipass: traverse_steps_per_pass and intersections_per_pass must be at least 1");
    MultipassRun run;
    GpuBuffers buffers(vk, grid, rays, /*multipassState=*/true);
    const std::uint64_t cap = options.maxPasses ? options.maxPasses
                                                : multipassPassCap(&grid.stats.resolution[0], grid.stats.maxReferencesInCell, options);
    KernelSpec spec;
    spec.workgroupSize = timing.workgroupSize;
    spec.traverseStepsPerPass = options.traverseStepsPerPass;
    spec.intersectionsPerPass = options.intersectionsPerPass;
    spec.suppressFinishedReads = options.suppressFinishedReads;
    std::array<double, kPassKinds> ms{};
    {
        Pipelines counted(vk, spec);
        run.counts = runPasses(vk, buffers, counted, options, cap, ms);
        run.hits = buffers.downloadHits();
    }
    spec.instrument = false;
    Pipelines timed(vk, spec);
    for (int i = 0; i < timing.warmups + timing.repetitions; ++i) {
        const MultipassCounts again = runPasses(vk, buffers, timed, options, cap, ms);
        if (again.sequence != run.counts.sequence)
            throw Error("multipass: the timed run's pass sequence differs from the instrumented run's");
        if (i < timing.warmups) continue;
        run.gpuMsByKind.push_back(ms);
        run.gpuMs.push_back(ms[0] + ms[1] + ms[2] + ms[3]);
    }
    expectSameHits(buffers.downloadHits(), run.hits, "multipass kernels");
    return run;
}

}  // namespace rtbench
