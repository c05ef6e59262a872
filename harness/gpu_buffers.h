// The device buffers of one grid and ray stream, in the slots of kernels/gpu_layout.h, with the
// one descriptor set every kernel binds. Per-ray multipass state is allocated only when needed.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "structures/uniform_grid.h"
#include "vulkan_context.h"

namespace rtbench {

struct KernelSpec {
    std::uint32_t workgroupSize = 64;
    bool instrument = true;
    std::uint32_t traverseStepsPerPass = 1;
    std::uint32_t intersectionsPerPass = 1;
    bool suppressFinishedReads = false;
};

// A pipeline for kernels/<name>.comp with the specialization constants of `spec`.
ComputePipeline createKernel(VulkanContext& vk, const std::string& name, const KernelSpec& spec);

class GpuBuffers {
public:
    GpuBuffers(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays, bool multipassState);
    ~GpuBuffers();
    GpuBuffers(const GpuBuffers&) = delete;
    GpuBuffers& operator=(const GpuBuffers&) = delete;

    // The descriptor set for pipelines made by createKernel (all share one layout).
    VkDescriptorSet descriptorSet(const ComputePipeline& pipeline);
    const gpu::GridParams& params() const { return params_; }
    std::uint64_t rayCount() const { return rayCount_; }

    gpu::PassCounters readPassCounters() const;
    void resetPassCounters();
    std::vector<gpu::HitRecord> downloadHits();
    double uploadMs() const { return uploadMs_; }

private:
    VulkanContext& vk_;
    std::array<Buffer, gpu::kBindingCount> buffers_{};
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    gpu::GridParams params_{};
    std::uint64_t rayCount_ = 0;
    double uploadMs_ = 0.0;
};

}  // namespace rtbench
