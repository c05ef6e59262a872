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

// One device buffer of a run and its size, known from the run's parameters before allocation.
struct BufferSize {
    std::string what;
    std::uint64_t bytes = 0;
};

// The per-ray buffers (rays, hit records; multipass: stencil, traversal and hit state, counters).
std::vector<BufferSize> rayBufferSizes(std::uint64_t rays, bool multipassState);
// The grid's buffers (Purcell Fig. 4): cell offsets, triangle list, triangle vertices.
std::vector<BufferSize> gridBufferSizes(const std::array<unsigned, 3>& resolution, std::uint64_t references,
                                        std::uint64_t triangles);
// Throws rtbench::Error naming the first buffer over the device's maxStorageBufferRange (one
// binding), or the total over its largest device-local heap; allocates nothing.
void refuseOversizedBuffers(const DeviceInfo& device, const std::vector<BufferSize>& buffers);

// Host memory a run holds per ray: the ray, and hit records from the kernel (instrumented and
// timed), the CPU reference (twice for multipass), Embree (and its scratch), and the image's
// shade and difference per pixel.
constexpr std::uint64_t kHostBytesPerRay = sizeof(gpu::Ray) + 7 * sizeof(gpu::HitRecord) + 5;
// The host-memory limit of a run's per-ray data: half the machine's physical memory.
std::uint64_t hostMemoryLimit();
// Throws rtbench::Error when `rays` rays need more than hostMemoryLimit(); allocates nothing.
void refuseOversizedRayStream(std::uint64_t rays);

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
    // Multipass: the per-ray DDA state saved by the last pass (tests compare it with the CPU's).
    std::vector<gpu::RayTraversalState> downloadTraversalStates();
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
