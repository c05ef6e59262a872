#include "acceleration_structure.h"

#include <algorithm>
#include <array>
#include <string>

#include "core/error.h"

namespace rtbench {

namespace {

// The extension's entry points (not in the loader's exports).
struct AccelerationStructureCalls {
    PFN_vkGetAccelerationStructureBuildSizesKHR buildSizes;
    PFN_vkCreateAccelerationStructureKHR create;
    PFN_vkDestroyAccelerationStructureKHR destroy;
    PFN_vkCmdBuildAccelerationStructuresKHR build;
    PFN_vkGetAccelerationStructureDeviceAddressKHR address;
};

template <class F>
F entryPoint(VkDevice device, const char* name) {
    auto f = reinterpret_cast<F>(vkGetDeviceProcAddr(device, name));
    if (!f) throw Error(std::string("Vulkan: vkGetDeviceProcAddr found no ") + name);
    return f;
}

AccelerationStructureCalls calls(VkDevice d) {
    return {entryPoint<PFN_vkGetAccelerationStructureBuildSizesKHR>(d, "vkGetAccelerationStructureBuildSizesKHR"),
            entryPoint<PFN_vkCreateAccelerationStructureKHR>(d, "vkCreateAccelerationStructureKHR"),
            entryPoint<PFN_vkDestroyAccelerationStructureKHR>(d, "vkDestroyAccelerationStructureKHR"),
            entryPoint<PFN_vkCmdBuildAccelerationStructuresKHR>(d, "vkCmdBuildAccelerationStructuresKHR"),
            entryPoint<PFN_vkGetAccelerationStructureDeviceAddressKHR>(d, "vkGetAccelerationStructureDeviceAddressKHR")};
}

void check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) throw Error(std::string("Vulkan: ") + call + " failed: " + vkResultName(result));
}

// minAccelerationStructureScratchOffsetAlignment is a power of two of at most 256 (the spec's limit).
constexpr VkDeviceSize kScratchAlignment = 256;

// The bottom level's geometry: the triangles, opaque (no any-hit shader is asked), triangle i its
// primitive i.
VkAccelerationStructureGeometryKHR triangleGeometry(VkDeviceAddress vertices, std::size_t vertexCount, VkDeviceAddress indices) {
    VkAccelerationStructureGeometryKHR mesh{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    mesh.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    mesh.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
    VkAccelerationStructureGeometryTrianglesDataKHR& data = mesh.geometry.triangles;
    data.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
    data.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    data.vertexData.deviceAddress = vertices;
    data.vertexStride = sizeof(glm::vec3);
    data.maxVertex = std::uint32_t(vertexCount - 1);
    data.indexType = VK_INDEX_TYPE_UINT32;
    data.indexData.deviceAddress = indices;
    return mesh;
}

// The top level's instance: the bottom level once, at the identity, both faces hit.
VkAccelerationStructureInstanceKHR identityInstance(VkDeviceAddress bottomLevel) {
    VkAccelerationStructureInstanceKHR placed{};
    placed.transform.matrix[0][0] = placed.transform.matrix[1][1] = placed.transform.matrix[2][2] = 1.0f;
    placed.mask = 0xFF;
    placed.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    placed.accelerationStructureReference = bottomLevel;
    return placed;
}

VkAccelerationStructureGeometryKHR instanceGeometry(VkDeviceAddress instances) {
    VkAccelerationStructureGeometryKHR geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
    geometry.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
    geometry.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
    geometry.geometry.instances.data.deviceAddress = instances;
    return geometry;
}

// A level's storage, as large as the driver asks for `count` primitives of `build`, and its handle
// (the build's destination). Returns the sizes the driver asked for.
VkAccelerationStructureBuildSizesInfoKHR createLevel(VulkanContext& vk, const AccelerationStructureCalls& rt,
                                                     VkAccelerationStructureBuildGeometryInfoKHR& build, std::uint32_t count,
                                                     Buffer& storage, VkAccelerationStructureKHR& handle, const char* level) {
    VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    rt.buildSizes(vk.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &count, &sizes);
    storage = vk.createAddressedBuffer(sizes.accelerationStructureSize, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR);
    VkAccelerationStructureCreateInfoKHR create{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
    create.buffer = storage.buffer;
    create.size = sizes.accelerationStructureSize;
    create.type = build.type;
    check(rt.create(vk.device(), &create, nullptr, &handle), (std::string("vkCreateAccelerationStructureKHR (") + level + ")").c_str());
    build.dstAccelerationStructure = handle;
    return sizes;
}

// The two builds, one after the other, on the device.
void recordBuilds(VkCommandBuffer cmd, const AccelerationStructureCalls& rt, const VkAccelerationStructureBuildGeometryInfoKHR& bottom,
                  std::uint32_t triangleCount, const VkAccelerationStructureBuildGeometryInfoKHR& top) {
    auto barrier = [cmd](VkPipelineStageFlags from, VkAccessFlags written, VkPipelineStageFlags to, VkAccessFlags read) {
        VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        b.srcAccessMask = written;
        b.dstAccessMask = read;
        vkCmdPipelineBarrier(cmd, from, to, 0, 1, &b, 0, nullptr, 0, nullptr);
    };
    const VkAccelerationStructureBuildRangeInfoKHR bottomRange{triangleCount, 0, 0, 0}, topRange{1, 0, 0, 0};
    const VkAccelerationStructureBuildRangeInfoKHR* bottomRanges = &bottomRange;
    const VkAccelerationStructureBuildRangeInfoKHR* topRanges = &topRange;
    const VkPipelineStageFlags buildStage = VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
    // Orders the uploads of vertices, indices and the instance before the builds read them.
    barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, buildStage, VK_ACCESS_SHADER_READ_BIT);
    rt.build(cmd, 1, &bottom, &bottomRanges);
    // Orders the bottom level's build (and its scratch use) before the top level's, which reads it.
    barrier(buildStage, VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, buildStage,
            VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR);
    rt.build(cmd, 1, &top, &topRanges);
    // Orders the top level's build before the ray-query kernels that trace it.
    barrier(buildStage, VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR);
}

VkDeviceAddress levelAddress(const AccelerationStructureCalls& rt, VkDevice device, VkAccelerationStructureKHR handle) {
    VkAccelerationStructureDeviceAddressInfoKHR address{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    address.accelerationStructure = handle;
    return rt.address(device, &address);
}

}  // namespace

DriverAccelerationStructure::DriverAccelerationStructure(VulkanContext& vk, const std::vector<glm::vec3>& vertices,
                                                         const std::vector<glm::uvec3>& triangles)
    : vk_(vk) {
    try {
        build(vertices, triangles);
    } catch (...) {
        release();  // what a failed build made so far
        throw;
    }
}

void DriverAccelerationStructure::build(const std::vector<glm::vec3>& vertices, const std::vector<glm::uvec3>& triangles) {
    VulkanContext& vk = vk_;
    if (!vk.info().rayQuery)
        throw Error(vk.info().name + " lacks VK_KHR_ray_query (missing: " + vk.info().rayQueryMissing + ")");
    if (triangles.empty()) throw Error("the driver's acceleration structure needs at least one triangle");
    const VkDevice device = vk.device();
    const AccelerationStructureCalls rt = calls(device);

    // The build's inputs on the device: vertices (3 floats each), indices (3 per triangle).
    const VkBufferUsageFlags input = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
    vertices_ = vk.createAddressedBuffer(vertices.size() * sizeof(glm::vec3), input);
    vk.upload(vertices_, vertices.data(), vertices.size() * sizeof(glm::vec3));
    indices_ = vk.createAddressedBuffer(triangles.size() * sizeof(glm::uvec3), input);
    vk.upload(indices_, triangles.data(), triangles.size() * sizeof(glm::uvec3));

    const VkAccelerationStructureGeometryKHR mesh =
        triangleGeometry(vk.deviceAddress(vertices_), vertices.size(), vk.deviceAddress(indices_));
    VkAccelerationStructureBuildGeometryInfoKHR bottomBuild{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    bottomBuild.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    bottomBuild.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    bottomBuild.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    bottomBuild.geometryCount = 1;
    bottomBuild.pGeometries = &mesh;
    const std::uint32_t triangleCount = std::uint32_t(triangles.size());
    const auto bottomSizes = createLevel(vk, rt, bottomBuild, triangleCount, bottom_, bottomHandle_, "bottom level");

    const VkAccelerationStructureInstanceKHR placed = identityInstance(levelAddress(rt, device, bottomHandle_));
    instance_ = vk.createAddressedBuffer(sizeof(placed), input);
    vk.upload(instance_, &placed, sizeof(placed));
    const VkAccelerationStructureGeometryKHR instances = instanceGeometry(vk.deviceAddress(instance_));
    VkAccelerationStructureBuildGeometryInfoKHR topBuild = bottomBuild;
    topBuild.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
    topBuild.pGeometries = &instances;
    topBuild.dstAccelerationStructure = VK_NULL_HANDLE;
    const auto topSizes = createLevel(vk, rt, topBuild, 1, top_, topHandle_, "top level");
    inputBytes_ = vertices_.size + indices_.size + instance_.size;

    // One scratch buffer for both builds, one after the other.
    scratchBytes_ = std::max(bottomSizes.buildScratchSize, topSizes.buildScratchSize);
    scratch_ = vk.createAddressedBuffer(scratchBytes_ + kScratchAlignment, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const VkDeviceAddress scratchAddress = (vk.deviceAddress(scratch_) + kScratchAlignment - 1) & ~(kScratchAlignment - 1);
    bottomBuild.scratchData.deviceAddress = topBuild.scratchData.deviceAddress = scratchAddress;
    buildMs_ = vk.runTimed([&](VkCommandBuffer cmd) { recordBuilds(cmd, rt, bottomBuild, triangleCount, topBuild); });
    // The levels hold what they need: the build's inputs and scratch go.
    for (Buffer* b : {&scratch_, &instance_, &indices_, &vertices_}) vk.destroy(*b);
    topAddress_ = levelAddress(rt, device, topHandle_);
}

DriverAccelerationStructure::~DriverAccelerationStructure() { release(); }

void DriverAccelerationStructure::release() {
    const auto destroy = reinterpret_cast<PFN_vkDestroyAccelerationStructureKHR>(
        vkGetDeviceProcAddr(vk_.device(), "vkDestroyAccelerationStructureKHR"));
    if (destroy) {
        if (topHandle_) destroy(vk_.device(), topHandle_, nullptr);
        if (bottomHandle_) destroy(vk_.device(), bottomHandle_, nullptr);
    }
    topHandle_ = bottomHandle_ = VK_NULL_HANDLE;
    for (Buffer* b : {&scratch_, &top_, &bottom_, &instance_, &indices_, &vertices_}) vk_.destroy(*b);
}

}  // namespace rtbench
