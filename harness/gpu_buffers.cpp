#include "gpu_buffers.h"

#include <chrono>
#include <cstring>

namespace rtbench {

ComputePipeline createKernel(VulkanContext& vk, const std::string& name, const KernelSpec& spec) {
    return vk.createComputePipeline(std::string(RTBENCH_SPIRV_DIR) + "/" + name + ".spv", gpu::kBindingCount,
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
    const std::string res = std::to_string(grid.stats.resolution[0]) + "x" + std::to_string(grid.stats.resolution[1]) +
                            "x" + std::to_string(grid.stats.resolution[2]);
    const std::size_t n = rays.size();
    const std::size_t perRay = multipassState ? n : 1;  // unused slots get a minimal buffer
    try {
        buffers_[gpu::kBindingRays] = vk.createStorageBuffer(n * sizeof(gpu::Ray), "ray (" + std::to_string(n) + " rays)");
        buffers_[gpu::kBindingCellOffsets] = vk.createStorageBuffer(grid.cellOffsets.size() * 4, "grid cell offset (" + res + " cells)");
        buffers_[gpu::kBindingTriangleList] = vk.createStorageBuffer(
            grid.triangleList.size() * 4, "grid triangle list (" + std::to_string(grid.triangleList.size()) + " references)");
        buffers_[gpu::kBindingVertices] = vk.createStorageBuffer(grid.triangles.size() * sizeof(gpu::Triangle), "triangle vertex");
        buffers_[gpu::kBindingHits] = vk.createStorageBuffer(n * sizeof(gpu::HitRecord), "hit record");
        buffers_[gpu::kBindingStencil] = vk.createStorageBuffer(perRay, "ray state");
        buffers_[gpu::kBindingTraversal] = vk.createStorageBuffer(perRay * sizeof(gpu::RayTraversalState), "traversal state");
        buffers_[gpu::kBindingHitState] = vk.createStorageBuffer(perRay * sizeof(gpu::RayHitState), "hit state");
        buffers_[gpu::kBindingRayCounters] = vk.createStorageBuffer(perRay * sizeof(gpu::RayCounters), "ray counter");
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

}  // namespace rtbench
