#include "branching_strategy.h"

#include <chrono>

#include "structures/error.h"

namespace rtbench {

KernelRun runBranching(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                       const BranchingOptions& options) {
    KernelRun run;
    const auto start = std::chrono::steady_clock::now();
    const std::string res = std::to_string(grid.stats.resolution[0]) + "x" +
                            std::to_string(grid.stats.resolution[1]) + "x" +
                            std::to_string(grid.stats.resolution[2]);
    // Slots as declared in kernels/gpu_layout.h (kBindingRays ... kBindingHits).
    Buffer buffers[gpu::kBindingCount] = {
        vk.createStorageBuffer(rays.size() * sizeof(gpu::Ray), "ray (" + std::to_string(rays.size()) + " rays)"),
        vk.createStorageBuffer(grid.cellOffsets.size() * 4, "grid cell offset (" + res + " cells)"),
        vk.createStorageBuffer(grid.triangleList.size() * 4, "grid triangle list (" + std::to_string(grid.triangleList.size()) + " references)"),
        vk.createStorageBuffer(grid.triangles.size() * sizeof(gpu::Triangle), "triangle vertex"),
        vk.createStorageBuffer(rays.size() * sizeof(gpu::HitRecord), "hit record"),
    };
    struct Release {  // buffers go back to the device whatever happens below
        VulkanContext& vk;
        Buffer* buffers;
        ~Release() {
            for (std::uint32_t i = 0; i < gpu::kBindingCount; ++i) vk.destroy(buffers[i]);
        }
    } release{vk, buffers};
    vk.upload(buffers[gpu::kBindingRays], rays.data(), rays.size() * sizeof(gpu::Ray));
    vk.upload(buffers[gpu::kBindingCellOffsets], grid.cellOffsets.data(), grid.cellOffsets.size() * 4);
    vk.upload(buffers[gpu::kBindingTriangleList], grid.triangleList.data(), grid.triangleList.size() * 4);
    vk.upload(buffers[gpu::kBindingVertices], grid.triangles.data(), grid.triangles.size() * sizeof(gpu::Triangle));
    run.uploadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    gpu::GridParams params = grid.params;
    params.resolution.w = static_cast<std::uint32_t>(rays.size());
    std::vector<const Buffer*> bound;
    for (const Buffer& b : buffers) bound.push_back(&b);
    const std::string spirv = std::string(RTBENCH_SPIRV_DIR) + "/raycast_branching.spv";

    auto pipelineFor = [&](std::uint32_t instrument) {
        return vk.createComputePipeline(spirv, gpu::kBindingCount, sizeof(gpu::GridParams), options.workgroupSize,
                                        {{gpu::kSpecWorkgroupSize, options.workgroupSize},
                                         {gpu::kSpecInstrument, instrument}});
    };
    run.hits.resize(rays.size());
    {
        ComputePipeline counted = pipelineFor(1);
        vk.dispatch(counted, bound, &params, rays.size());
        vk.destroy(counted);
        vk.download(buffers[gpu::kBindingHits], run.hits.data(), rays.size() * sizeof(gpu::HitRecord));
    }
    ComputePipeline timed = pipelineFor(0);
    for (int i = 0; i < options.warmups; ++i) vk.dispatch(timed, bound, &params, rays.size());
    for (int i = 0; i < options.repetitions; ++i) run.gpuMs.push_back(vk.dispatch(timed, bound, &params, rays.size()));
    vk.destroy(timed);

    std::vector<gpu::HitRecord> timedHits(rays.size());
    vk.download(buffers[gpu::kBindingHits], timedHits.data(), rays.size() * sizeof(gpu::HitRecord));
    for (std::size_t i = 0; i < rays.size(); ++i)
        if (timedHits[i].primitive != run.hits[i].primitive || timedHits[i].t != run.hits[i].t)
            throw Error("branching kernel: the timed dispatch's hit for ray " + std::to_string(i) +
                        " differs from the instrumented one (nondeterministic kernel?)");
    return run;
}

}  // namespace rtbench
