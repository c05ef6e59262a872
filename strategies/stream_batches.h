// A ray stream traced in batches, when one binding (maxStorageBufferRange) cannot hold its per-ray
// records: each batch its own per-ray buffers and dispatches, one after another, the structure on the
// device once for all of them (uploadForBatches), and their timers as one.
// Batches are whole workgroups (so whole subgroups): every subgroup's lanes, ballots and loops are
// the ones it has in one unbatched dispatch.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "strategies/strategy.h"

namespace rtbench {

// The most rays whose records of `perRayBytes` fit one binding, a multiple of `workgroupSize`
// (at least one workgroup).
std::uint64_t raysPerBinding(const DeviceInfo& device, std::uint64_t perRayBytes, unsigned workgroupSize);

// The structure's buffers on the device, once for every batch of a stream, after refusing
// (allocating nothing) when the stream's per-ray buffers (`perRay`, for all its rays: every batch
// keeps its own until the timer is done) and the structure's exceed the device's largest
// device-local heap.
std::shared_ptr<const DeviceStructure> uploadForBatches(VulkanContext& vk, std::vector<BufferSize> perRay,
                                                        const std::vector<BufferData>& structureBuffers);

// [first, end) of each batch of `batchRays` rays over a stream of `rays` (the last may be shorter).
std::vector<std::pair<std::uint64_t, std::uint64_t>> streamBatches(std::uint64_t rays, std::uint64_t batchRays);

// Runs `runBatch(part)` on each batch of `batchRays` rays of `rays`, one after another, hands each
// batch's run to `gather` (its hits and counts, in stream order), and returns the batches'
// timers as one (BatchedTimer). A run is a strategy's *Run struct with a `timer`.
template <class RunBatch, class Gather>
std::unique_ptr<KernelTimer> traceInBatches(const std::vector<gpu::Ray>& rays, std::uint64_t batchRays,
                                            RunBatch runBatch, Gather gather);

// The timers of a stream's batches as one: a repetition is every batch's, one after another (its
// time and each part's the sum of the batches'); the host loops add up alike.
class BatchedTimer : public KernelTimer {
public:
    explicit BatchedTimer(std::vector<std::unique_ptr<KernelTimer>> batches) : batches_(std::move(batches)) {}
    TimedBatch time(int warmups, int repetitions) override;
    HostLoopTimes timeHostLoops() override;
    void checkHits() override;

private:
    std::vector<std::unique_ptr<KernelTimer>> batches_;
};

template <class RunBatch, class Gather>
std::unique_ptr<KernelTimer> traceInBatches(const std::vector<gpu::Ray>& rays, std::uint64_t batchRays,
                                            RunBatch runBatch, Gather gather) {
    std::vector<std::unique_ptr<KernelTimer>> timers;
    for (const auto& [first, end] : streamBatches(rays.size(), batchRays)) {
        const std::vector<gpu::Ray> part(rays.begin() + std::ptrdiff_t(first), rays.begin() + std::ptrdiff_t(end));
        auto run = runBatch(part);
        gather(run);
        timers.push_back(std::move(run.timer));
    }
    return std::make_unique<BatchedTimer>(std::move(timers));
}

}  // namespace rtbench
