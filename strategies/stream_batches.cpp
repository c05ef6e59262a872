#include "stream_batches.h"

#include <algorithm>

namespace rtbench {

std::uint64_t raysPerBinding(const DeviceInfo& device, std::uint64_t perRayBytes, unsigned workgroupSize) {
    const std::uint64_t fit = device.maxStorageBufferRange / std::max<std::uint64_t>(perRayBytes, 1);
    return std::max<std::uint64_t>(fit / workgroupSize * workgroupSize, workgroupSize);
}

std::shared_ptr<const DeviceStructure> uploadForBatches(VulkanContext& vk, std::vector<BufferSize> perRay,
                                                        const std::vector<BufferData>& structureBuffers) {
    const std::vector<BufferSize> structure = sizesOf(structureBuffers);
    perRay.insert(perRay.end(), structure.begin(), structure.end());
    refuseOversizedTotal(vk.info(), perRay);
    return std::make_shared<const DeviceStructure>(vk, structureBuffers);
}

std::vector<std::pair<std::uint64_t, std::uint64_t>> streamBatches(std::uint64_t rays, std::uint64_t batchRays) {
    std::vector<std::pair<std::uint64_t, std::uint64_t>> batches;
    for (std::uint64_t first = 0; first < rays; first += batchRays) batches.emplace_back(first, std::min(first + batchRays, rays));
    return batches;
}

TimedBatch BatchedTimer::time(int warmups, int repetitions) {
    TimedBatch all;
    for (const auto& batch : batches_) {
        const TimedBatch b = batch->time(warmups, repetitions);
        all.warmupMs += b.warmupMs;
        if (all.ms.empty()) {
            all.ms = b.ms;
            all.parts = b.parts;
            continue;
        }
        for (std::size_t i = 0; i < all.ms.size(); ++i) all.ms[i] += b.ms[i];
        for (std::size_t p = 0; p < all.parts.size(); ++p)
            for (std::size_t i = 0; i < all.parts[p].second.size(); ++i) all.parts[p].second[i] += b.parts[p].second[i];
    }
    return all;
}

HostLoopTimes BatchedTimer::timeHostLoops() {
    HostLoopTimes all;
    for (const auto& batch : batches_) {
        const auto loops = batch->timeHostLoops();
        if (all.empty())
            all = loops;
        else
            for (std::size_t i = 0; i < all.size(); ++i) all[i].second += loops[i].second;
    }
    return all;
}

void BatchedTimer::checkHits() {
    for (const auto& batch : batches_) batch->checkHits();
}

}  // namespace rtbench
