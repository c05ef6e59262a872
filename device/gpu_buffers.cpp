#include "gpu_buffers.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

#include "core/error.h"

#include "embedded_kernels.h"

namespace rtbench {

std::vector<BufferSize> rayBufferSizes(std::uint64_t rays) {
    const std::string n = " (" + std::to_string(rays) + " rays)";
    return {{"ray" + n, rays * sizeof(gpu::Ray)}, {"hit record" + n, rays * sizeof(gpu::HitRecord)}};
}

void refuseOversizedBuffers(const DeviceInfo& device, const std::vector<BufferSize>& buffers) {
    for (const BufferSize& b : buffers) checkBindingSize(device, b.what, b.bytes);
    refuseOversizedTotal(device, buffers);
}

void refuseOversizedTotal(const DeviceInfo& device, const std::vector<BufferSize>& buffers) {
    std::uint64_t total = 0;
    for (const BufferSize& b : buffers) total += b.bytes;
    if (device.deviceLocalBytes && total > device.deviceLocalBytes)
        throw Error("the run's buffers would take " + std::to_string(total) + " bytes, over " + device.name +
                    "'s largest device-local heap of " + std::to_string(device.deviceLocalBytes) + " bytes");
}

std::uint64_t hostMemoryLimit(std::uint64_t physicalBytes, std::uint64_t addressSpaceLimit) {
    const std::uint64_t physicalHalf = physicalBytes / 2;
    return addressSpaceLimit == std::uint64_t(RLIM_INFINITY) ? physicalHalf : std::min(physicalHalf, addressSpaceLimit / 2);
}

std::uint64_t hostMemoryLimit() {
    rlimit limit{};
    const std::uint64_t addressSpace = ::getrlimit(RLIMIT_AS, &limit) == 0 ? std::uint64_t(limit.rlim_cur) : std::uint64_t(RLIM_INFINITY);
    return hostMemoryLimit(std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE)), addressSpace);
}

void refuseOversizedRayStream(std::uint64_t rays) {
    const std::uint64_t bytes = rays * kHostBytesPerRay;
    if (bytes > hostMemoryLimit())
        throw Error(std::to_string(rays) + " rays need " + std::to_string(bytes) + " bytes of host memory (" +
                    std::to_string(kHostBytesPerRay) + " per ray), over the limit of " +
                    std::to_string(hostMemoryLimit()) + " bytes (half the physical memory, or of the address-space limit, ulimit -v, when lower)");
}

std::vector<BufferSize> sizesOf(const std::vector<BufferData>& buffers) {
    std::vector<BufferSize> sizes;
    for (const BufferData& b : buffers) sizes.push_back({b.what, b.bytes});
    return sizes;
}

DeviceStructure::DeviceStructure(VulkanContext& vk, const std::vector<BufferData>& buffers)
    : vk_(vk), sizes_(sizesOf(buffers)) {
    refuseOversizedBuffers(vk.info(), sizes_);
    buffers_.resize(buffers.size());
    try {
        for (std::size_t i = 0; i < buffers.size(); ++i) {
            buffers_[i] = vk.createStorageBuffer(buffers[i].bytes, buffers[i].what);
            vk.upload(buffers_[i], buffers[i].data, buffers[i].bytes);
        }
    } catch (...) {
        for (Buffer& b : buffers_) vk.destroy(b);
        throw;
    }
}

DeviceStructure::~DeviceStructure() {
    for (Buffer& b : buffers_) vk_.destroy(b);
}

namespace {

// Every buffer of a run: its per-ray slots, the strategy's and the structure's, in slot order
// (without the pass counters), for the refusals before anything is allocated.
std::vector<BufferSize> runBufferSizes(std::uint64_t rays, const std::vector<BufferSize>& strategyBuffers,
                                       const std::vector<BufferSize>& structureBuffers) {
    if (strategyBuffers.size() > gpu::kStrategySlots)
        throw Error("a strategy asked for " + std::to_string(strategyBuffers.size()) + " buffers of its own; there are " +
                    std::to_string(gpu::kStrategySlots) + " slots (kernels/gpu_layout.h kStrategySlots)");
    std::vector<BufferSize> sizes = rayBufferSizes(rays);  // slots kBindingRays, kBindingHits
    for (std::uint32_t i = 0; i < gpu::kStrategySlots; ++i)  // slots kBindingStrategy..
        sizes.push_back(i < strategyBuffers.size() ? strategyBuffers[i] : BufferSize{"unused strategy slot", 4});
    sizes.insert(sizes.end(), structureBuffers.begin(), structureBuffers.end());
    return sizes;
}

// The structure's buffers on the device, once the whole run is known to fit.
std::shared_ptr<const DeviceStructure> uploadStructure(VulkanContext& vk, std::uint64_t rays,
                                                       const std::vector<BufferData>& structureBuffers,
                                                       const std::vector<BufferSize>& strategyBuffers) {
    refuseOversizedBuffers(vk.info(), runBufferSizes(rays, strategyBuffers, sizesOf(structureBuffers)));
    return std::make_shared<const DeviceStructure>(vk, structureBuffers);
}

}  // namespace

GpuBuffers::GpuBuffers(VulkanContext& vk, const std::vector<gpu::Ray>& rays,
                       const std::vector<BufferData>& structureBuffers, const std::vector<std::uint8_t>& structureParams,
                       const std::vector<BufferSize>& strategyBuffers)
    : GpuBuffers(vk, rays, uploadStructure(vk, rays.size(), structureBuffers, strategyBuffers), structureParams,
                 strategyBuffers) {}

GpuBuffers::GpuBuffers(VulkanContext& vk, const std::vector<gpu::Ray>& rays,
                       std::shared_ptr<const DeviceStructure> structure, const std::vector<std::uint8_t>& structureParams,
                       const std::vector<BufferSize>& strategyBuffers)
    : vk_(vk), structure_(std::move(structure)), rayCount_(rays.size()) {
    static_assert(gpu::kBindingRays == 0 && gpu::kBindingHits == 1 && gpu::kBindingPassCounters == 2 &&
                      gpu::kBindingStrategy == 3 && gpu::kBindingStrategy + gpu::kStrategySlots == gpu::kBindingStructure,
                  "the slot order runBufferSizes lists");
    const std::size_t n = rays.size();
    const std::vector<BufferSize> sizes = runBufferSizes(n, strategyBuffers, structure_->sizes());
    refuseOversizedBuffers(vk.info(), sizes);
    buffers_.resize(gpu::kBindingStructure);
    try {
        for (std::uint32_t b : {gpu::kBindingRays, gpu::kBindingHits})
            buffers_[b] = vk.createStorageBuffer(sizes[b].bytes, sizes[b].what);
        // Zero records until a kernel writes them: a whole-path kernel leaves the records of paths
        // that end early unwritten, and the checks read every record.
        vk.fill(buffers_[gpu::kBindingHits], 0);
        buffers_[gpu::kBindingPassCounters] = vk.createStorageBuffer(sizeof(gpu::PassCounters), "the pass counters");
        countersOnHost_ = vk.createHostReadbackBuffer(sizeof(gpu::PassCounters));
        std::memset(countersOnHost_.mapped, 0, sizeof(gpu::PassCounters));  // zeros until a read-back
        vk.upload(buffers_[gpu::kBindingRays], rays.data(), n * sizeof(gpu::Ray));
        for (std::uint32_t b = gpu::kBindingStrategy; b < gpu::kBindingStructure; ++b) {
            buffers_[b] = vk.createStorageBuffer(sizes[b - 1].bytes, sizes[b - 1].what);  // sizes has no pass-counter entry
            vk.fill(buffers_[b], 0);  // zeros, filled on the device (no host copy of the buffer's size)
        }
        const gpu::PassCounters zero{};  // what a dispatch without a read-back adds to
        vk.upload(buffers_[gpu::kBindingPassCounters], &zero, sizeof zero);
    } catch (...) {
        for (Buffer& b : buffers_) vk.destroy(b);
        vk.destroy(countersOnHost_);
        throw;
    }
    counters_ = {&buffers_[gpu::kBindingPassCounters], &countersOnHost_};
    gpu::StreamParams stream{};
    stream.stream.x = static_cast<std::uint32_t>(n);
    pushConstants_.resize(sizeof stream);
    std::memcpy(pushConstants_.data(), &stream, sizeof stream);
    pushConstants_.insert(pushConstants_.end(), structureParams.begin(), structureParams.end());
}

namespace {
std::uint32_t floatBits(float f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits;
}
}  // namespace

ComputePipeline GpuBuffers::createKernel(const std::string& name, const KernelSpec& spec) {
    std::vector<SpecializationConstant> constants = {
        {gpu::kSpecWorkgroupSize, spec.workgroupSize},
        {gpu::kSpecInstrument, spec.instrument ? 1u : 0u},
        {gpu::kSpecTriangleTest, spec.triangleTest},
        {gpu::kSpecDivision, spec.division},
        {gpu::kSpecVertexBits, spec.vertexLattice.bits},
        {gpu::kSpecLatticeOriginX, floatBits(spec.vertexLattice.origin.x)},
        {gpu::kSpecLatticeOriginY, floatBits(spec.vertexLattice.origin.y)},
        {gpu::kSpecLatticeOriginZ, floatBits(spec.vertexLattice.origin.z)},
        {gpu::kSpecLatticeStep, floatBits(spec.vertexLattice.step)},
        {gpu::kSpecQuery, spec.query}};
    for (const SpecializationConstant& c : spec.strategyConstants) {
        for (const SpecializationConstant& earlier : constants)
            if (earlier.id == c.id)  // Vulkan requires each constant ID once per pipeline
                throw Error(name + ": specialization constant " + std::to_string(c.id) + " given twice");
        constants.push_back(c);
    }
    return vk_.createComputePipeline(embeddedKernel(name), std::uint32_t(buffers_.size() + structure_->buffers().size()),
                                     std::uint32_t(pushConstants_.size()), spec.workgroupSize, constants);
}

GpuBuffers::~GpuBuffers() {
    if (set_) vk_.destroy(set_);
    for (Buffer& b : buffers_) vk_.destroy(b);
    vk_.destroy(countersOnHost_);
}

VkDescriptorSet GpuBuffers::descriptorSet(const ComputePipeline& pipeline) {
    if (!set_) {
        std::vector<const Buffer*> bound;
        for (const Buffer& b : buffers_) bound.push_back(&b);
        for (const Buffer& b : structure_->buffers()) bound.push_back(&b);
        set_ = vk_.createDescriptorSet(pipeline, bound);
    }
    return set_;
}

gpu::PassCounters GpuBuffers::readPassCounters() const {
    gpu::PassCounters c;
    std::memcpy(&c, countersOnHost_.mapped, sizeof c);
    return c;
}

std::vector<gpu::HitRecord> GpuBuffers::downloadHits() {
    std::vector<gpu::HitRecord> hits(rayCount_);
    vk_.download(buffers_[gpu::kBindingHits], hits.data(), hits.size() * sizeof(gpu::HitRecord));
    return hits;
}

std::vector<gpu::Ray> GpuBuffers::downloadRays() {
    std::vector<gpu::Ray> rays(rayCount_);
    vk_.download(buffers_[gpu::kBindingRays], rays.data(), rays.size() * sizeof(gpu::Ray));
    return rays;
}

void GpuBuffers::uploadStrategyBuffer(std::uint32_t i, const void* data, std::uint64_t bytes) {
    Buffer& b = buffers_.at(gpu::kBindingStrategy + i);
    if (bytes > b.size)
        throw Error("uploadStrategyBuffer: " + std::to_string(bytes) + " bytes into strategy slot " + std::to_string(i) +
                    " of " + std::to_string(b.size));
    vk_.upload(b, data, bytes);
}

std::vector<std::uint8_t> GpuBuffers::downloadStrategyBuffer(std::uint32_t i) {
    const Buffer& b = strategyBuffer(i);
    std::vector<std::uint8_t> bytes(b.size);
    vk_.download(b, bytes.data(), bytes.size());
    return bytes;
}

}  // namespace rtbench
