// The driver's own acceleration structure over a triangle mesh (VK_KHR_acceleration_structure):
// one bottom level over the triangles, as indexed triangles, opaque, built for fast tracing, and
// one top level holding it once at the identity. Not compacted: the storage is the size the driver
// asks for before the build (an upper bound). Kernels trace it with VK_KHR_ray_query from the
// top level's device address (methods/ray_query). Built on the device and timed there.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "device/vulkan_context.h"

namespace rtbench {

class DriverAccelerationStructure {
public:
    // Throws rtbench::Error when the device lacks the driver's ray tracing (DeviceInfo::rayQuery).
    DriverAccelerationStructure(VulkanContext& vk, const std::vector<glm::vec3>& vertices,
                                const std::vector<glm::uvec3>& triangles);
    ~DriverAccelerationStructure();
    DriverAccelerationStructure(const DriverAccelerationStructure&) = delete;
    DriverAccelerationStructure& operator=(const DriverAccelerationStructure&) = delete;

    VkDeviceAddress topLevelAddress() const { return topAddress_; }
    std::uint64_t bottomLevelBytes() const { return bottom_.size; }  // the structures' storage, as the driver sized it
    std::uint64_t topLevelBytes() const { return top_.size; }
    std::uint64_t scratchBytes() const { return scratchBytes_; }  // the larger build's scratch (freed after the build)
    std::uint64_t inputBytes() const { return inputBytes_; }      // vertices, indices and the instance, uploaded for the build (freed after it)
    double buildMs() const { return buildMs_; }                   // both builds, GPU timestamps

private:
    void build(const std::vector<glm::vec3>& vertices, const std::vector<glm::uvec3>& triangles);
    void release();

    VulkanContext& vk_;
    Buffer vertices_, indices_, instance_, bottom_, top_, scratch_;
    VkAccelerationStructureKHR bottomHandle_ = VK_NULL_HANDLE, topHandle_ = VK_NULL_HANDLE;
    VkDeviceAddress topAddress_ = 0;
    std::uint64_t scratchBytes_ = 0, inputBytes_ = 0;
    double buildMs_ = 0.0;
};

}  // namespace rtbench
