#include "gpu_buffers.h"

#include <unistd.h>

#include <chrono>
#include <cstring>

#include "structures/error.h"

#include "embedded_kernels.h"

namespace rtbench {

std::vector<BufferSize> rayBufferSizes(std::uint64_t rays, bool multipassState) {
    const std::uint64_t perRay = multipassState ? rays : 1;  // unused slots get a minimal buffer
    const std::string n = " (" + std::to_string(rays) + " rays)";
    return {{"ray" + n, rays * sizeof(gpu::Ray)},
            {"hit record" + n, rays * sizeof(gpu::HitRecord)},
            {"ray state", perRay},
            {"traversal state" + n, perRay * sizeof(gpu::RayTraversalState)},
            {"hit state" + n, perRay * sizeof(gpu::RayHitState)},
            {"ray counter" + n, perRay * sizeof(gpu::RayCounters)}};
}

std::vector<BufferSize> gridBufferSizes(const std::array<unsigned, 3>& resolution, std::uint64_t references,
                                        std::uint64_t triangles) {
    const std::uint64_t cells = std::uint64_t(resolution[0]) * resolution[1] * resolution[2];
    const std::string res = std::to_string(resolution[0]) + "x" + std::to_string(resolution[1]) + "x" +
                            std::to_string(resolution[2]);
    return {{"grid cell offset (" + res + " = " + std::to_string(cells) + " cells)", (cells + 1) * 4},
            {"grid triangle list (" + std::to_string(references) + " references)", references * 4},
            {"triangle vertex (" + std::to_string(triangles) + " triangles)", triangles * sizeof(gpu::Triangle)}};
}

void refuseOversizedBuffers(const DeviceInfo& device, const std::vector<BufferSize>& buffers) {
    std::uint64_t total = 0;
    for (const BufferSize& b : buffers) {
        checkBindingSize(device, b.what, b.bytes);
        total += b.bytes;
    }
    if (device.deviceLocalBytes && total > device.deviceLocalBytes)
        throw Error("the run's buffers would take " + std::to_string(total) + " bytes, over " + device.name +
                    "'s largest device-local heap of " + std::to_string(device.deviceLocalBytes) + " bytes");
}

std::uint64_t hostMemoryLimit() {
    return std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE)) / 2;
}

void refuseOversizedRayStream(std::uint64_t rays) {
    const std::uint64_t bytes = rays * kHostBytesPerRay;
    if (bytes > hostMemoryLimit())
        throw Error(std::to_string(rays) + " rays need " + std::to_string(bytes) + " bytes of host memory (" +
                    std::to_string(kHostBytesPerRay) + " per ray), over the limit of " +
                    std::to_string(hostMemoryLimit()) + " bytes (half the physical memory)");
}

ComputePipeline createKernel(VulkanContext& vk, const std::string& name, const KernelSpec& spec) {
    return vk.createComputePipeline(embeddedKernel(name), gpu::kBindingCount,
                                    sizeof(gpu::GridParams), spec.workgroupSize,
                                    {{gpu::kSpecWorkgroupSize, spec.workgroupSize},
                                     {gpu::kSpecInstrument, spec.instrument ? 1u : 0u},
                                     {gpu::kSpecTraverseSteps, spec.traverseStepsPerPass},
                                     {gpu::kSpecIntersections, spec.intersectionsPerPass},
                                     {gpu::kSpecSuppress, spec.suppressFinishedReads ? 1u : 0u}});
}

GpuBuffers::GpuBuffers(VulkanContext& vk, const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                       bool multipassState)
    : vk_(vk), rayCount_(rays.size()) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = rays.size();
    std::vector<BufferSize> sizes = rayBufferSizes(n, multipassState);
    const std::vector<BufferSize> gridSizes =
        gridBufferSizes(grid.stats.resolution, grid.triangleList.size(), grid.triangles.size());
    sizes.insert(sizes.begin() + 1, gridSizes.begin(), gridSizes.end());  // in binding order
    refuseOversizedBuffers(vk.info(), sizes);
    try {
        for (std::uint32_t b = gpu::kBindingRays; b <= gpu::kBindingRayCounters; ++b)
            buffers_[b] = vk.createStorageBuffer(sizes[b].bytes, sizes[b].what);
        buffers_[gpu::kBindingPassCounters] = vk.createHostStorageBuffer(sizeof(gpu::PassCounters));
        vk.upload(buffers_[gpu::kBindingRays], rays.data(), n * sizeof(gpu::Ray));
        vk.upload(buffers_[gpu::kBindingCellOffsets], grid.cellOffsets.data(), grid.cellOffsets.size() * 4);
        vk.upload(buffers_[gpu::kBindingTriangleList], grid.triangleList.data(), grid.triangleList.size() * 4);
        vk.upload(buffers_[gpu::kBindingVertices], grid.triangles.data(), grid.triangles.size() * sizeof(gpu::Triangle));
    } catch (...) {
        for (Buffer& b : buffers_) vk.destroy(b);
        throw;
    }
    resetPassCounters();
    params_ = grid.params;
    params_.resolution.w = static_cast<std::uint32_t>(n);
    uploadMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

GpuBuffers::~GpuBuffers() {
    if (set_) vk_.destroy(set_);
    for (Buffer& b : buffers_) vk_.destroy(b);
}

VkDescriptorSet GpuBuffers::descriptorSet(const ComputePipeline& pipeline) {
    if (!set_) {
        std::vector<const Buffer*> bound;
        for (const Buffer& b : buffers_) bound.push_back(&b);
        set_ = vk_.createDescriptorSet(pipeline, bound);
    }
    return set_;
}

gpu::PassCounters GpuBuffers::readPassCounters() const {
    gpu::PassCounters c;
    std::memcpy(&c, buffers_[gpu::kBindingPassCounters].mapped, sizeof c);
    return c;
}

void GpuBuffers::resetPassCounters() {
    std::memset(buffers_[gpu::kBindingPassCounters].mapped, 0, sizeof(gpu::PassCounters));
}

std::vector<gpu::HitRecord> GpuBuffers::downloadHits() {
    std::vector<gpu::HitRecord> hits(rayCount_);
    vk_.download(buffers_[gpu::kBindingHits], hits.data(), hits.size() * sizeof(gpu::HitRecord));
    return hits;
}

std::vector<gpu::RayTraversalState> GpuBuffers::downloadTraversalStates() {
    std::vector<gpu::RayTraversalState> states(rayCount_);
    vk_.download(buffers_[gpu::kBindingTraversal], states.data(), states.size() * sizeof(gpu::RayTraversalState));
    return states;
}

}  // namespace rtbench
