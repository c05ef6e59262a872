// The device buffers of one run (a ray stream and a structure), in the slots of
// kernels/gpu_layout.h, with the one descriptor set every kernel binds; their sizes, known before
// anything is allocated, and the refusals of what the device or the host cannot hold.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "kernels/gpu_layout.h"
#include "scene/mesh.h"
#include "vulkan_context.h"

namespace rtbench {

// The specialization constants of a kernel: those every kernel reads (kernels/gpu_layout.h), set
// from the run's structure and query, and the strategy's own (multipass: K, M and suppression),
// which the strategy lists; a constant a kernel does not declare is ignored by Vulkan.
struct KernelSpec {
    std::uint32_t workgroupSize = 64;
    bool instrument = true;
    std::uint32_t triangleTest = gpu::kTriangleTestMollerTrumbore;
    std::uint32_t division = gpu::kDivisionDouble;
    std::uint32_t query = gpu::kQueryClosest;  // gpu::kQuery*: closest hit or any hit
    VertexLattice vertexLattice;  // bits != 0: the structure's vertices are packed to it
    std::vector<SpecializationConstant> strategyConstants;
};

// One device buffer of a run and its size, known from the run's parameters before allocation.
struct BufferSize {
    std::string what;
    std::uint64_t bytes = 0;
};

// The per-ray buffers every strategy binds: the rays and their hit records (a strategy's own,
// such as multipass's state, come in its slots).
std::vector<BufferSize> rayBufferSizes(std::uint64_t rays);
// Throws rtbench::Error naming the first buffer over the device's maxStorageBufferRange (one
// binding), or the total over its largest device-local heap; allocates nothing.
void refuseOversizedBuffers(const DeviceInfo& device, const std::vector<BufferSize>& buffers);
// Only the total against the largest device-local heap (a stream that runs in batches binds each
// batch's share; every strategy's batches stay allocated until its timer is done).
void refuseOversizedTotal(const DeviceInfo& device, const std::vector<BufferSize>& buffers);

// Host memory a run holds per ray: the ray, and hit records from the kernel (instrumented and
// timed), the CPU reference (twice for multipass), Embree (and its scratch), and the image's
// shade and difference per pixel, and the exact reference's hit and sample index (28 bytes, when
// every ray is sampled).
constexpr std::uint64_t kHostBytesPerRay = sizeof(gpu::Ray) + 7 * sizeof(gpu::HitRecord) + 5 + 28;
// The host-memory limit of a run's per-ray data: half the machine's physical memory, or half the
// process's address-space limit (RLIMIT_AS, `ulimit -v`, as a cluster's scheduler may set) when
// that is lower: the Vulkan driver and Embree need the rest.
std::uint64_t hostMemoryLimit();
// The same from the two figures (addressSpaceLimit: RLIM_INFINITY when there is none).
std::uint64_t hostMemoryLimit(std::uint64_t physicalBytes, std::uint64_t addressSpaceLimit);
// Throws rtbench::Error when `rays` rays need more than hostMemoryLimit(); allocates nothing.
void refuseOversizedRayStream(std::uint64_t rays);

// One of a structure's buffers, uploaded once: what it is (named in size errors), its size and
// its host data.
struct BufferData {
    std::string what;
    std::uint64_t bytes = 0;
    const void* data = nullptr;
};
// Their sizes, in order, for the refusals.
std::vector<BufferSize> sizesOf(const std::vector<BufferData>& buffers);

// A structure's buffers on the device, uploaded once. The batches of a stream each bind the same
// (GpuBuffers holds it shared: it goes with the last batch's timer), so a stream in many batches
// costs the structure's bytes once.
class DeviceStructure {
public:
    // Throws rtbench::Error naming a buffer over maxStorageBufferRange; allocates nothing then.
    DeviceStructure(VulkanContext& vk, const std::vector<BufferData>& buffers);
    ~DeviceStructure();
    DeviceStructure(const DeviceStructure&) = delete;
    DeviceStructure& operator=(const DeviceStructure&) = delete;

    const std::vector<Buffer>& buffers() const { return buffers_; }
    const std::vector<BufferSize>& sizes() const { return sizes_; }

private:
    VulkanContext& vk_;
    std::vector<Buffer> buffers_;  // from slot kBindingStructure on
    std::vector<BufferSize> sizes_;
};

// The buffers of one run (or one batch of its stream): the common slots of kernels/gpu_layout.h
// (rays, hit records, pass counters), the strategy's own (zeroed, at most kStrategySlots, from
// kBindingStrategy on), then the structure's buffers from kBindingStructure on; and the push
// constants (StreamParams, then the structure's).
class GpuBuffers {
public:
    // Uploads the structure's buffers for this stream alone.
    GpuBuffers(VulkanContext& vk, const std::vector<gpu::Ray>& rays, const std::vector<BufferData>& structureBuffers,
               const std::vector<std::uint8_t>& structureParams, const std::vector<BufferSize>& strategyBuffers = {});
    // Binds a structure already on the device (one batch of a stream).
    GpuBuffers(VulkanContext& vk, const std::vector<gpu::Ray>& rays, std::shared_ptr<const DeviceStructure> structure,
               const std::vector<std::uint8_t>& structureParams, const std::vector<BufferSize>& strategyBuffers = {});
    ~GpuBuffers();
    GpuBuffers(const GpuBuffers&) = delete;
    GpuBuffers& operator=(const GpuBuffers&) = delete;

    // A pipeline for the embedded kernel `name` with the specialization constants of `spec`, in
    // this run's set layout (its binding count and push-constant size).
    ComputePipeline createKernel(const std::string& name, const KernelSpec& spec);
    // The descriptor set for pipelines made by createKernel (all share one layout).
    VkDescriptorSet descriptorSet(const ComputePipeline& pipeline);
    const void* pushConstants() const { return pushConstants_.data(); }
    std::uint64_t rayCount() const { return rayCount_; }

    // The pass counters (kBindingPassCounters) live in device-local memory; a dispatch given
    // passCounters() zeroes them before and copies them to the host after, and readPassCounters()
    // reads that copy.
    const VulkanContext::CounterReadback* passCounters() const { return &counters_; }
    gpu::PassCounters readPassCounters() const;
    std::vector<gpu::HitRecord> downloadHits();
    // The rays slot, as the kernels left it (a strategy that writes its queue there: wavefront).
    std::vector<gpu::Ray> downloadRays();
    // The whole of the strategy's buffer in slot kBindingStrategy + i, as bytes.
    std::vector<std::uint8_t> downloadStrategyBuffer(std::uint32_t i);
    // `bytes` of `data` into the start of the strategy's buffer in slot kBindingStrategy + i.
    void uploadStrategyBuffer(std::uint32_t i, const void* data, std::uint64_t bytes);
    // The strategy's buffer in slot kBindingStrategy + i (a 4-byte placeholder when it has none).
    const Buffer& strategyBuffer(std::uint32_t i) const { return buffers_.at(gpu::kBindingStrategy + i); }
    // The pass counters themselves (device-local), for dispatches that zero them first.
    const Buffer& passCounterBuffer() const { return buffers_[gpu::kBindingPassCounters]; }

private:
    VulkanContext& vk_;
    std::vector<Buffer> buffers_;  // by binding slot, up to kBindingStructure
    std::shared_ptr<const DeviceStructure> structure_;  // the slots from kBindingStructure on
    Buffer countersOnHost_;        // the pass counters' copy the host reads
    VulkanContext::CounterReadback counters_{};
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    std::vector<std::uint8_t> pushConstants_;
    std::uint64_t rayCount_ = 0;
};

}  // namespace rtbench
