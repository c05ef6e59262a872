// Vulkan compute, read top to bottom: instance (validation optional), device choice, buffers,
// pipelines with specialization constants, one-shot dispatches timed by timestamp queries.
// Every call is checked; a failure throws rtbench::Error naming the call and the VkResult.
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <functional>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rtbench {

struct DeviceInfo {
    std::string name;
    std::string driver;       // driver name and info, e.g. "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"
    std::string apiVersion;   // "1.3.230"
    std::string type;         // discrete | integrated | virtual | cpu | other
    std::uint32_t subgroupSize = 0;
    // Loop iterations after which the driver silently ends a kernel invocation (all its loops
    // together), 0 when none is known: llvmpipe's is 65,535 (Mesa's LP_MAX_TGSI_LOOP_ITERATIONS,
    // per subgroup: lanes run in lockstep, so the count is the subgroup's).
    std::uint64_t loopIterationLimit = 0;
    // Whether a subgroup's lanes run a loop in lock step, every lane of the subgroup at the same
    // iteration and reconverged after it: llvmpipe's subgroups are SIMD vectors, so its ballots
    // count what branching's CPU lane model (strategies/branching/lane_counts.h) counts. Elsewhere
    // (NVIDIA's independent thread scheduling) the lanes of a loop may run apart, and the model
    // is not the device's measure.
    bool lockStepSubgroups = false;
    std::uint64_t maxStorageBufferRange = 0;
    std::uint32_t maxWorkGroupCountX = 0;
    std::uint32_t maxPushConstantsSize = 0;
    std::uint64_t deviceLocalBytes = 0;  // largest DEVICE_LOCAL heap
    double timestampPeriodNs = 0.0;
    bool timestampsSupported = false;
    // Features the kernels need (kernels/bindings.glsl): one-byte stencil, 64-bit counters,
    // subgroup arithmetic and ballots.
    std::string missingFeatures;  // empty when all are supported
    // The driver's own ray tracing for compute kernels (methods/ray_query): VK_KHR_ray_query and
    // VK_KHR_acceleration_structure with their features and buffer device addresses. Enabled on
    // the device when present; rayQueryMissing says what is not (empty when rayQuery).
    bool rayQuery = false;
    std::string rayQueryMissing;
};

std::string vkResultName(VkResult result);

// The workgroup grid of a dispatch of `groups` workgroups (x, y): one row when they fit
// maxComputeWorkGroupCount[0], else the fewest rows, each of the fewest groups, so that at most
// y - 1 groups find no ray (kernels/bindings.glsl rtRayIndex). Rows of the full limit left up to
// 65,534 empty groups at 2048 x 2048 rays, 44% of the branching kernel's time on lavapipe.
std::pair<std::uint64_t, std::uint64_t> workgroupGrid(std::uint64_t groups, std::uint64_t maxGroupsX);

// Throws rtbench::Error naming the buffer (`what`), its size and the device's limit when `bytes`
// exceed what one storage binding can hold (maxStorageBufferRange).
void checkBindingSize(const DeviceInfo& device, const std::string& what, std::uint64_t bytes);

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // non-null when the memory is host-visible (e.g. lavapipe)
};

struct SpecializationConstant {
    std::uint32_t id;
    std::uint32_t value;
};

struct ComputePipeline {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    std::uint32_t bindingCount = 0;
    std::uint32_t pushConstantBytes = 0;
    std::uint32_t workgroupSize = 0;
};

class VulkanContext {
public:
    // What a validated context's new storage buffers hold until written: every float a NaN, every
    // uint 0xFFFFFFFF (no ray, primitive or slot index).
    static constexpr std::uint32_t kPoisonWord = 0xFFFFFFFFu;

    // deviceChoice: "auto" (a discrete GPU if any, else lavapipe/CPU, else the first) or a
    // case-insensitive substring of the device name. validation: enable
    // VK_LAYER_KHRONOS_validation and collect what it reports (see validationMessages()), and
    // poison every new storage buffer (kPoisonWord in each 4 bytes) so that a kernel or a check
    // reading memory nothing wrote finds NaNs and out-of-range indices, not whatever was there.
    VulkanContext(const std::string& deviceChoice, bool validation);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    static std::vector<DeviceInfo> listDevices();

    const DeviceInfo& info() const { return info_; }

    // A storage buffer in DEVICE_LOCAL memory (uploaded through a staging buffer when that
    // memory is not host-visible), poisoned when validating. Throws when size exceeds
    // maxStorageBufferRange.
    Buffer createStorageBuffer(VkDeviceSize size, const std::string& what);
    // A small buffer in HOST_VISIBLE | HOST_COHERENT memory that copies land in (the host reads
    // counters the kernels summed in a device-local buffer: CounterReadback).
    Buffer createHostReadbackBuffer(VkDeviceSize size);
    void upload(Buffer& buffer, const void* data, VkDeviceSize size);
    // Every 4 bytes of the buffer set to `value` on the device (vkCmdFillBuffer), before later kernels.
    void fill(Buffer& buffer, std::uint32_t value);
    void download(const Buffer& buffer, void* data, VkDeviceSize size);
    void destroy(Buffer& buffer);

    ComputePipeline createComputePipeline(std::span<const std::uint32_t> spirv, std::uint32_t bindingCount,
                                          std::uint32_t pushConstantBytes,
                                          std::uint32_t workgroupSize,
                                          const std::vector<SpecializationConstant>& constants);
    void destroy(ComputePipeline& pipeline);

    // A descriptor set binding the buffers to slots 0..n-1 (for pipelines of that layout).
    VkDescriptorSet createDescriptorSet(const ComputePipeline& pipeline, const std::vector<const Buffer*>& buffers);
    void destroy(VkDescriptorSet set);

    // Counters the kernels sum with atomics in device-local memory (not in host memory, where on a
    // discrete GPU every atomic would cross the bus): zeroed before the dispatch and copied to
    // `host` (createHostReadbackBuffer) after it, in the same command buffer, outside its timestamps.
    struct CounterReadback {
        const Buffer* device;
        const Buffer* host;
    };
    // Pushes the constants, dispatches enough workgroups for `invocations` (2D when needed),
    // waits, and returns the GPU time in ms from timestamps (or -1 where unsupported).
    double dispatch(const ComputePipeline& pipeline, VkDescriptorSet set, const void* pushConstants,
                    std::uint64_t invocations, const CounterReadback* counters = nullptr);
    // Many dispatches recorded into one command buffer, each ordered after the one before by a
    // barrier and timed by its own pair of timestamps, submitted once (in chunks of
    // kDispatchesPerSubmit); returns each one's GPU time in ms (-1 where unsupported).
    struct DispatchCall {
        const ComputePipeline* pipeline;
        VkDescriptorSet set;
        const void* pushConstants;
        std::uint64_t invocations;
        const CounterReadback* counters = nullptr;  // read back after this dispatch (the last call's stays)
        // Indirect: the workgroup counts (VkDispatchIndirectCommand) at `indirectOffset` of this
        // buffer, written by an earlier dispatch; `invocations` is then unused.
        const Buffer* indirect = nullptr;
        VkDeviceSize indirectOffset = 0;
        std::array<const Buffer*, 2> zeroFirst{};  // buffers filled with zeros before this dispatch
    };
    static constexpr std::uint32_t kDispatchesPerSubmit = 1024;
    std::vector<double> dispatchAll(const std::vector<DispatchCall>& calls);
    // The same with a descriptor set made for this one dispatch.
    double dispatch(const ComputePipeline& pipeline, const std::vector<const Buffer*>& buffers,
                    const void* pushConstants, std::uint64_t invocations);

    // ---- the driver's ray tracing (DeviceInfo::rayQuery; device/acceleration_structure.h) ----
    VkDevice device() const { return device_; }
    // A DEVICE_LOCAL buffer with a device address (builds and kernels take addresses), `usage`
    // besides; upload() fills it. Not bound as a storage buffer, so not limited to one binding.
    Buffer createAddressedBuffer(VkDeviceSize size, VkBufferUsageFlags usage);
    VkDeviceAddress deviceAddress(const Buffer& buffer) const;
    // Records `commands` into one command buffer between two timestamps, submits it and waits;
    // returns their GPU time in ms (-1 where unsupported).
    double runTimed(const std::function<void(VkCommandBuffer)>& commands);

    // Messages of the validation layer (warnings and errors) since creation.
    const std::vector<std::string>& validationMessages() const { return messages_; }

private:
    void create(const std::string& deviceChoice, bool validation);
    void release();  // everything made, in reverse (a member not made yet is a null handle)
    std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred) const;
    Buffer createBuffer(VkDeviceSize size, VkBufferUsageFlags usage,
                        VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred, bool deviceAddress = false);
    void submitAndWait(VkCommandBuffer cmd);
    double intervalMs(std::uint64_t start, std::uint64_t end) const;  // two timestamps' ticks apart, in ms
    VkCommandBuffer beginOneShot();
    void copyBuffer(VkBuffer from, VkBuffer to, VkDeviceSize size, bool toDevice);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queueFamily_ = 0;
    VkCommandPool commandPool_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
    VkQueryPool queryPool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    DeviceInfo info_;
    std::uint32_t timestampValidBits_ = 0;
    std::vector<std::string> messages_;
    bool poisonNewBuffers_ = false;  // the validation mode's fill of new storage buffers
};

}  // namespace rtbench
