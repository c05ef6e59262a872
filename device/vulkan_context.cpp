#include "vulkan_context.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iostream>

#include "core/error.h"

namespace rtbench {

std::string vkResultName(VkResult result) {
    switch (result) {
#define RT_CASE(x) \
    case x:        \
        return #x;
        RT_CASE(VK_SUCCESS)
        RT_CASE(VK_NOT_READY)
        RT_CASE(VK_TIMEOUT)
        RT_CASE(VK_INCOMPLETE)
        RT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        RT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        RT_CASE(VK_ERROR_INITIALIZATION_FAILED)
        RT_CASE(VK_ERROR_DEVICE_LOST)
        RT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        RT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        RT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        RT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        RT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        RT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        RT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        RT_CASE(VK_ERROR_FRAGMENTED_POOL)
        RT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        RT_CASE(VK_ERROR_INVALID_SHADER_NV)
#undef RT_CASE
        default:
            return "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
    }
}

namespace {

void check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) throw Error(std::string("Vulkan: ") + call + " failed: " + vkResultName(result));
}
#define VK_CHECK(call) check((call), #call)

std::string versionString(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
    auto* messages = static_cast<std::vector<std::string>*>(user);
    messages->push_back(data->pMessage ? data->pMessage : "(no message)");
    std::cerr << "[vulkan validation] " << messages->back() << "\n";
    return VK_FALSE;
}

VkInstance createInstance(bool validation, const std::vector<std::string>* messages,
                          VkDebugUtilsMessengerEXT* messenger) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "rtbench";
    app.apiVersion = VK_API_VERSION_1_2;
    std::vector<const char*> layers, extensions;
    if (validation) {
        layers.push_back("VK_LAYER_KHRONOS_validation");
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkDebugUtilsMessengerCreateInfoEXT debugInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    debugInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    debugInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    debugInfo.pfnUserCallback = onValidationMessage;
    debugInfo.pUserData = const_cast<std::vector<std::string>*>(messages);

    VkInstanceCreateInfo create{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    create.pNext = validation ? &debugInfo : nullptr;  // also reports on create/destroy
    create.pApplicationInfo = &app;
    create.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    create.ppEnabledLayerNames = layers.data();
    create.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    create.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    VkResult result = vkCreateInstance(&create, nullptr, &instance);
    if (result == VK_ERROR_LAYER_NOT_PRESENT)
        throw Error("Vulkan: vkCreateInstance failed: VK_ERROR_LAYER_NOT_PRESENT "
                    "(install vulkan-validationlayers for validation)");
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw Error("Vulkan: vkCreateInstance failed: VK_ERROR_INCOMPATIBLE_DRIVER (no Vulkan "
                    "driver found: install mesa-vulkan-drivers for lavapipe)");
    check(result, "vkCreateInstance");
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) throw Error("Vulkan: vkCreateDebugUtilsMessengerEXT not available");
        VK_CHECK(create(instance, &debugInfo, nullptr, messenger));
    }
    return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

// The device extensions the driver's ray tracing needs (VK_KHR_acceleration_structure requires
// deferred host operations).
constexpr std::array<const char*, 3> kRayQueryExtensions = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                                            VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                                            VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

// DeviceInfo::rayQuery: the extensions, then (only when they are there) their features.
void describeRayQuery(VkPhysicalDevice device, bool bufferDeviceAddress, DeviceInfo& info) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> extensions(count);
    VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));
    std::string missing;
    auto lacks = [&](const std::string& what) { missing += (missing.empty() ? "" : ", ") + what; };
    for (const char* name : kRayQueryExtensions)
        if (std::none_of(extensions.begin(), extensions.end(),
                         [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; }))
            lacks(name);
    if (missing.empty()) {
        VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
        VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
        structures.pNext = &rayQuery;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.pNext = &structures;
        vkGetPhysicalDeviceFeatures2(device, &features);
        if (!rayQuery.rayQuery) lacks("the rayQuery feature");
        if (!structures.accelerationStructure) lacks("the accelerationStructure feature");
    }
    if (!bufferDeviceAddress) lacks("the bufferDeviceAddress feature");
    info.rayQuery = missing.empty();
    info.rayQueryMissing = missing;
}

DeviceInfo describe(VkPhysicalDevice device) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    subgroup.pNext = &driver;
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(device, &props);
    const VkPhysicalDeviceLimits& limits = props.properties.limits;
    DeviceInfo info;
    info.name = props.properties.deviceName;
    info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    info.apiVersion = versionString(props.properties.apiVersion);
    switch (props.properties.deviceType) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: info.type = "discrete"; break;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: info.type = "integrated"; break;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: info.type = "virtual"; break;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: info.type = "cpu"; break;
        default: info.type = "other";
    }
    info.subgroupSize = subgroup.subgroupSize;
    if (driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE) {
        info.loopIterationLimit = 65535;
        info.lockStepSubgroups = true;
    }
    info.maxStorageBufferRange = limits.maxStorageBufferRange;
    info.maxWorkGroupCountX = limits.maxComputeWorkGroupCount[0];
    info.maxPushConstantsSize = limits.maxPushConstantsSize;
    info.timestampPeriodNs = limits.timestampPeriod;
    info.timestampsSupported = limits.timestampComputeAndGraphics == VK_TRUE;
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &v12;
    vkGetPhysicalDeviceFeatures2(device, &features);
    auto need = [&](bool supported, const char* name) {
        if (!supported) info.missingFeatures += (info.missingFeatures.empty() ? "" : ", ") + std::string(name);
    };
    need(v12.storageBuffer8BitAccess, "storageBuffer8BitAccess");
    need(v12.shaderInt8, "shaderInt8");
    need(features.features.shaderInt64, "shaderInt64");
    need(features.features.shaderFloat64, "shaderFloat64 (kernels/ray_math.glsl's exact division)");
    need(v12.shaderBufferInt64Atomics, "shaderBufferInt64Atomics");
    const VkSubgroupFeatureFlags ops = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT |
                                       VK_SUBGROUP_FEATURE_BALLOT_BIT;
    need((subgroup.supportedOperations & ops) == ops && (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT),
         "subgroup basic/arithmetic/ballot in compute");
    describeRayQuery(device, v12.bufferDeviceAddress == VK_TRUE, info);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(device, &memory);
    for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            info.deviceLocalBytes = std::max<std::uint64_t>(info.deviceLocalBytes, memory.memoryHeaps[h].size);
    return info;
}

// The device chosen: auto = discrete GPU > CPU (lavapipe) > the first; else the first whose name or
// driver holds the text (two lavapipes share a name: "Mesa 25" picks by the driver's version).
VkPhysicalDevice choosePhysicalDevice(VkInstance instance, const std::string& deviceChoice) {
    const std::vector<VkPhysicalDevice> devices = physicalDevices(instance);
    if (devices.empty()) throw Error("Vulkan: no physical device (install mesa-vulkan-drivers)");
    if (deviceChoice == "auto" || deviceChoice.empty()) {
        auto rank = [](const DeviceInfo& i) { return i.type == "discrete" ? 0 : i.type == "cpu" ? 1 : i.type == "integrated" ? 2 : 3; };
        return *std::min_element(devices.begin(), devices.end(), [&](auto a, auto b) { return rank(describe(a)) < rank(describe(b)); });
    }
    std::string available;
    for (VkPhysicalDevice d : devices) {
        const DeviceInfo info = describe(d);
        if (lower(info.name + " " + info.driver).find(lower(deviceChoice)) != std::string::npos) return d;
        available += (available.empty() ? "" : ", ") + info.name + " (" + info.driver + ")";
    }
    throw Error("Vulkan: no device matches '" + deviceChoice + "' (available: " + available + ")");
}

// The first queue family with compute.
std::uint32_t computeQueueFamily(VkPhysicalDevice physical, const std::string& name, std::uint32_t& timestampValidBits) {
    std::uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, families.data());
    for (std::uint32_t f = 0; f < familyCount; ++f)
        if (families[f].queueFlags & VK_QUEUE_COMPUTE_BIT) {
            timestampValidBits = families[f].timestampValidBits;
            return f;
        }
    throw Error("Vulkan: " + name + " has no compute queue");
}

// The logical device with one compute queue and the features the kernels need: 8-bit storage,
// 64-bit integers, atomics and floats, and the driver's ray tracing where the device has it
// (methods/ray_query: its extensions and features, and buffer device addresses for its builds).
VkDevice createLogicalDevice(VkPhysicalDevice physical, std::uint32_t queueFamily, const DeviceInfo& info) {
    if (!info.missingFeatures.empty())
        throw Error("Vulkan: " + info.name + " lacks features the kernels need: " + info.missingFeatures);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    v12.storageBuffer8BitAccess = VK_TRUE;
    v12.shaderInt8 = VK_TRUE;
    v12.shaderBufferInt64Atomics = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &v12;
    features.features.shaderInt64 = VK_TRUE;
    features.features.shaderFloat64 = VK_TRUE;
    VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
    std::vector<const char*> extensions;
    if (info.rayQuery) {
        rayQuery.rayQuery = VK_TRUE;
        structures.accelerationStructure = VK_TRUE;
        structures.pNext = &rayQuery;
        v12.pNext = &structures;
        v12.bufferDeviceAddress = VK_TRUE;
        extensions.assign(kRayQueryExtensions.begin(), kRayQueryExtensions.end());
    }
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &features;
    deviceInfo.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    deviceInfo.ppEnabledExtensionNames = extensions.data();
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    VkDevice device = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDevice(physical, &deviceInfo, nullptr, &device));
    return device;
}

}  // namespace

std::vector<DeviceInfo> VulkanContext::listDevices() {
    VkInstance instance = createInstance(false, nullptr, nullptr);
    std::vector<DeviceInfo> infos;
    for (VkPhysicalDevice d : physicalDevices(instance)) infos.push_back(describe(d));
    vkDestroyInstance(instance, nullptr);
    return infos;
}

VulkanContext::VulkanContext(const std::string& deviceChoice, bool validation) : poisonNewBuffers_(validation) {
    try {
        create(deviceChoice, validation);
    } catch (...) {
        release();  // what the failed creation made so far (no device matching the choice, ...)
        throw;
    }
}

void VulkanContext::create(const std::string& deviceChoice, bool validation) {
    instance_ = createInstance(validation, &messages_, &messenger_);
    physical_ = choosePhysicalDevice(instance_, deviceChoice);
    info_ = describe(physical_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memoryProperties_);
    queueFamily_ = computeQueueFamily(physical_, info_.name, timestampValidBits_);
    info_.timestampsSupported = info_.timestampsSupported || timestampValidBits_ > 0;
    device_ = createLogicalDevice(physical_, queueFamily_, info_);
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    poolInfo.queueFamilyIndex = queueFamily_;
    VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_));

    const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 64};
    VkDescriptorPoolCreateInfo descriptorPoolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    descriptorPoolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    descriptorPoolInfo.maxSets = 8;
    descriptorPoolInfo.poolSizeCount = 1;
    descriptorPoolInfo.pPoolSizes = &poolSize;
    VK_CHECK(vkCreateDescriptorPool(device_, &descriptorPoolInfo, nullptr, &descriptorPool_));

    if (timestampValidBits_ > 0) {
        VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
        queryInfo.queryCount = 2 * kDispatchesPerSubmit;
        VK_CHECK(vkCreateQueryPool(device_, &queryInfo, nullptr, &queryPool_));
    }
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(device_, &fenceInfo, nullptr, &fence_));
}

VulkanContext::~VulkanContext() { release(); }

void VulkanContext::release() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        vkDestroyFence(device_, fence_, nullptr);
        if (queryPool_) vkDestroyQueryPool(device_, queryPool_, nullptr);
        vkDestroyDescriptorPool(device_, descriptorPool_, nullptr);
        vkDestroyCommandPool(device_, commandPool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

std::uint32_t VulkanContext::findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                                            VkMemoryPropertyFlags preferred) const {
    for (VkMemoryPropertyFlags want : {required | preferred, required})
        for (std::uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (memoryProperties_.memoryTypes[i].propertyFlags & want) == want)
                return i;
    throw Error("Vulkan: no memory type with the required properties on " + info_.name);
}

Buffer VulkanContext::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage,
                                   VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred, bool deviceAddress) {
    Buffer b;
    b.size = std::max<VkDeviceSize>(size, 16);  // zero-sized buffers are invalid
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = b.size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &b.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, b.buffer, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = findMemoryType(req.memoryTypeBits, required, preferred);
    VkMemoryAllocateFlagsInfo addressed{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    addressed.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    if (deviceAddress) alloc.pNext = &addressed;
    VK_CHECK(vkAllocateMemory(device_, &alloc, nullptr, &b.memory));
    VK_CHECK(vkBindBufferMemory(device_, b.buffer, b.memory, 0));
    const VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[alloc.memoryTypeIndex].propertyFlags;
    if ((flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT))
        VK_CHECK(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    return b;
}

void checkBindingSize(const DeviceInfo& device, const std::string& what, std::uint64_t bytes) {
    if (bytes > device.maxStorageBufferRange)
        throw Error("the " + what + " buffer would be " + std::to_string(bytes) + " bytes, over " + device.name +
                    "'s maxStorageBufferRange of " + std::to_string(device.maxStorageBufferRange) +
                    " bytes for one binding");
}

Buffer VulkanContext::createStorageBuffer(VkDeviceSize size, const std::string& what) {
    checkBindingSize(info_, what, size);
    Buffer b = createBuffer(size,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                            VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    if (poisonNewBuffers_) {
        try {
            fill(b, kPoisonWord);
        } catch (...) {
            destroy(b);
            throw;
        }
    }
    return b;
}

Buffer VulkanContext::createHostReadbackBuffer(VkDeviceSize size) {
    return createBuffer(size, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, 0);
}

Buffer VulkanContext::createAddressedBuffer(VkDeviceSize size, VkBufferUsageFlags usage) {
    if (!info_.rayQuery) throw Error("Vulkan: " + info_.name + " has no buffer device addresses enabled (" + info_.rayQueryMissing + ")");
    return createBuffer(size, usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, true);
}

VkDeviceAddress VulkanContext::deviceAddress(const Buffer& b) const {
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = b.buffer;
    return vkGetBufferDeviceAddress(device_, &info);
}

double VulkanContext::runTimed(const std::function<void(VkCommandBuffer)>& commands) {
    VkCommandBuffer cmd = beginOneShot();
    if (queryPool_) {
        vkCmdResetQueryPool(cmd, queryPool_, 0, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queryPool_, 0);
    }
    commands(cmd);
    if (queryPool_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queryPool_, 1);
    submitAndWait(cmd);
    if (!queryPool_) return -1.0;
    std::array<std::uint64_t, 2> stamps{};
    VK_CHECK(vkGetQueryPoolResults(device_, queryPool_, 0, 2, sizeof(stamps), stamps.data(), sizeof(std::uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    return intervalMs(stamps[0], stamps[1]);
}

double VulkanContext::intervalMs(std::uint64_t start, std::uint64_t end) const {
    const std::uint64_t mask = timestampValidBits_ >= 64 ? ~0ull : ((1ull << timestampValidBits_) - 1);
    return static_cast<double>((end - start) & mask) * info_.timestampPeriodNs * 1e-6;
}

void VulkanContext::destroy(Buffer& b) {
    if (b.mapped) vkUnmapMemory(device_, b.memory);
    if (b.buffer) vkDestroyBuffer(device_, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(device_, b.memory, nullptr);
    b = Buffer{};
}

VkCommandBuffer VulkanContext::beginOneShot() {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = commandPool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    return cmd;
}

void VulkanContext::submitAndWait(VkCommandBuffer cmd) {
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_CHECK(vkResetFences(device_, 1, &fence_));
    VK_CHECK(vkQueueSubmit(queue_, 1, &submit, fence_));
    VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
    vkFreeCommandBuffers(device_, commandPool_, 1, &cmd);
}

void VulkanContext::copyBuffer(VkBuffer from, VkBuffer to, VkDeviceSize size, bool toDevice) {
    VkCommandBuffer cmd = beginOneShot();
    const VkBufferCopy region{0, 0, size};
    vkCmdCopyBuffer(cmd, from, to, 1, &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    if (toDevice) {
        // Orders the staging copy before later compute shaders read the buffer.
        barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                             0, 1, &barrier, 0, nullptr, 0, nullptr);
    } else {
        // Orders the read-back copy before the host reads the staging buffer.
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                             &barrier, 0, nullptr, 0, nullptr);
    }
    submitAndWait(cmd);
}

void VulkanContext::upload(Buffer& b, const void* data, VkDeviceSize size) {
    if (size == 0) return;
    if (b.mapped) {
        std::memcpy(b.mapped, data, size);  // host-coherent: visible at the next submit
        return;
    }
    Buffer staging = createBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, 0);
    std::memcpy(staging.mapped, data, size);
    copyBuffer(staging.buffer, b.buffer, size, true);
    destroy(staging);
}

void VulkanContext::fill(Buffer& b, std::uint32_t value) {
    VkCommandBuffer cmd = beginOneShot();
    vkCmdFillBuffer(cmd, b.buffer, 0, VK_WHOLE_SIZE, value);
    // Orders the fill before later compute shaders read or write the buffer.
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    submitAndWait(cmd);
}

void VulkanContext::download(const Buffer& b, void* data, VkDeviceSize size) {
    if (size == 0) return;
    if (b.mapped) {
        std::memcpy(data, b.mapped, size);
        return;
    }
    Buffer staging = createBuffer(size, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                  VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    copyBuffer(b.buffer, staging.buffer, size, false);
    std::memcpy(data, staging.mapped, size);
    destroy(staging);
}

ComputePipeline VulkanContext::createComputePipeline(std::span<const std::uint32_t> spirv,
                                                     std::uint32_t bindingCount,
                                                     std::uint32_t pushConstantBytes,
                                                     std::uint32_t workgroupSize,
                                                     const std::vector<SpecializationConstant>& constants) {
    ComputePipeline p;
    p.bindingCount = bindingCount;
    p.pushConstantBytes = pushConstantBytes;
    p.workgroupSize = workgroupSize;
    std::vector<VkDescriptorSetLayoutBinding> bindings(bindingCount);
    for (std::uint32_t i = 0; i < bindingCount; ++i)
        bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = bindingCount;
    setInfo.pBindings = bindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &p.setLayout));

    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &p.setLayout;
    layoutInfo.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &p.layout));

    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = spirv.size_bytes();
    moduleInfo.pCode = spirv.data();
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(device_, &moduleInfo, nullptr, &module));

    std::vector<VkSpecializationMapEntry> entries;
    std::vector<std::uint32_t> values;
    for (const SpecializationConstant& c : constants) {
        entries.push_back({c.id, static_cast<std::uint32_t>(values.size() * 4), 4});
        values.push_back(c.value);
    }
    VkSpecializationInfo spec{static_cast<std::uint32_t>(entries.size()), entries.data(),
                              values.size() * 4, values.data()};
    VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipelineInfo.stage.module = module;
    pipelineInfo.stage.pName = "main";
    pipelineInfo.stage.pSpecializationInfo = &spec;
    pipelineInfo.layout = p.layout;
    const VkResult result = vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &p.pipeline);
    vkDestroyShaderModule(device_, module, nullptr);
    check(result, "vkCreateComputePipelines");
    return p;
}

void VulkanContext::destroy(ComputePipeline& p) {
    if (p.pipeline) vkDestroyPipeline(device_, p.pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(device_, p.layout, nullptr);
    if (p.setLayout) vkDestroyDescriptorSetLayout(device_, p.setLayout, nullptr);
    p = ComputePipeline{};
}

VkDescriptorSet VulkanContext::createDescriptorSet(const ComputePipeline& p, const std::vector<const Buffer*>& buffers) {
    if (buffers.size() != p.bindingCount) throw Error("Vulkan: descriptor set given the wrong number of buffers");
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = descriptorPool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &p.setLayout;
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(device_, &alloc, &set));
    std::vector<VkDescriptorBufferInfo> infos(buffers.size());
    std::vector<VkWriteDescriptorSet> writes(buffers.size());
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = set;
        writes[i].dstBinding = static_cast<std::uint32_t>(i);
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
    return set;
}

void VulkanContext::destroy(VkDescriptorSet set) { VK_CHECK(vkFreeDescriptorSets(device_, descriptorPool_, 1, &set)); }

double VulkanContext::dispatch(const ComputePipeline& p, const std::vector<const Buffer*>& buffers,
                               const void* pushConstants, std::uint64_t invocations) {
    VkDescriptorSet set = createDescriptorSet(p, buffers);
    const double ms = dispatch(p, set, pushConstants, invocations);
    destroy(set);
    return ms;
}

double VulkanContext::dispatch(const ComputePipeline& p, VkDescriptorSet set, const void* pushConstants,
                               std::uint64_t invocations, const CounterReadback* counters) {
    return dispatchAll({{&p, set, pushConstants, invocations, counters}}).front();
}

std::pair<std::uint64_t, std::uint64_t> workgroupGrid(std::uint64_t groups, std::uint64_t maxGroupsX) {
    const std::uint64_t maxX = std::max<std::uint64_t>(maxGroupsX, 1);
    const std::uint64_t y = std::max<std::uint64_t>((groups + maxX - 1) / maxX, 1);
    return {(groups + y - 1) / y, y};
}

std::vector<double> VulkanContext::dispatchAll(const std::vector<DispatchCall>& calls) {
    std::vector<double> ms;
    for (std::size_t chunk = 0; chunk < calls.size(); chunk += kDispatchesPerSubmit) {
        const std::uint32_t n = std::uint32_t(std::min<std::size_t>(kDispatchesPerSubmit, calls.size() - chunk));
        VkCommandBuffer cmd = beginOneShot();
        if (queryPool_) vkCmdResetQueryPool(cmd, queryPool_, 0, 2 * n);
        for (std::uint32_t i = 0; i < n; ++i) {
            const DispatchCall& call = calls[chunk + i];
            const ComputePipeline& p = *call.pipeline;
            const std::uint64_t groups = (call.invocations + p.workgroupSize - 1) / p.workgroupSize;
            const auto [groupsX, groupsY] = workgroupGrid(groups, info_.maxWorkGroupCountX);
            std::vector<VkBuffer> zeroed;
            if (call.counters) zeroed.push_back(call.counters->device->buffer);
            for (const Buffer* b : call.zeroFirst)
                if (b) zeroed.push_back(b->buffer);
            if (!zeroed.empty()) {
                // Orders earlier kernels' writes and read-back copies of these buffers before the zeroing.
                VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
                before.srcAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                                       VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
                before.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                                              VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                                     VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, nullptr, 0, nullptr);
                for (VkBuffer b : zeroed) vkCmdFillBuffer(cmd, b, 0, VK_WHOLE_SIZE, 0);
            }
            // Orders earlier buffer writes (uploads, the zeroing, the previous pass) before this kernel's
            // reads and writes, and before the read of its workgroup counts when it is indirect.
            VkMemoryBarrier previous{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            previous.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
            previous.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1,
                                 &previous, 0, nullptr, 0, nullptr);
            // The start stamp at the bottom of the pipe: written once every earlier command (the
            // dispatch before) has completed, so an interval never includes another dispatch's tail.
            if (queryPool_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queryPool_, 2 * i);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &call.set, 0, nullptr);
            if (p.pushConstantBytes)
                vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, p.pushConstantBytes, call.pushConstants);
            if (call.indirect)
                vkCmdDispatchIndirect(cmd, call.indirect->buffer, call.indirectOffset);
            else if (groups)
                vkCmdDispatch(cmd, static_cast<std::uint32_t>(groupsX), static_cast<std::uint32_t>(groupsY), 1);
            if (queryPool_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queryPool_, 2 * i + 1);
            if (call.counters) {
                // Orders this kernel's counter atomics before the copy to the host's buffer.
                VkMemoryBarrier counted{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
                counted.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
                counted.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
                vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                                     &counted, 0, nullptr, 0, nullptr);
                const VkBufferCopy region{0, 0, call.counters->device->size};
                vkCmdCopyBuffer(cmd, call.counters->device->buffer, call.counters->host->buffer, 1, &region);
            }
        }
        // Orders the kernels' buffer writes and the counter copies before a read-back copy or a
        // host read of mapped memory.
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                             nullptr, 0, nullptr);
        submitAndWait(cmd);

        if (!queryPool_) {
            ms.insert(ms.end(), n, -1.0);
            continue;
        }
        std::vector<std::uint64_t> stamps(2 * n);
        VK_CHECK(vkGetQueryPoolResults(device_, queryPool_, 0, 2 * n, stamps.size() * sizeof(std::uint64_t),
                                       stamps.data(), sizeof(std::uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        for (std::uint32_t i = 0; i < n; ++i) ms.push_back(intervalMs(stamps[2 * i], stamps[2 * i + 1]));
    }
    return ms;
}

}  // namespace rtbench
