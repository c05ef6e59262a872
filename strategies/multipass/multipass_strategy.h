// The multipass (non-branching) strategy, Purcell et al. 2002 §3.2: a setup pass, then traverse
// or intersect passes chosen by the oracle from the ray-state counts read back after each pass,
// then a write pass. Each pass is one dispatch of a generic kernel (strategies/multipass/multipass_*.comp)
// over the whole stream, running the structure's per-ray steps.
#pragma once
#include <array>
#include <vector>

#include "device/gpu_buffers.h"
#include "strategies/strategy.h"
#include "multipass_schedule.h"

namespace rtbench {

const StrategyType& multipassStrategyType();

// The strategy's options from a run's keys.
MultipassOptions multipassOptions(const RunConfig& run);

struct MultipassRun {
    std::vector<gpu::HitRecord> hits;  // instrumented run, per-ray counters filled
    MultipassCounts counts;            // instrumented run
    std::vector<double> gpuMs;         // total GPU time of each timed repetition `timing` asked for
    std::vector<std::uint8_t> traversalStates;  // the per-ray state the last pass saved
    std::unique_ptr<KernelTimer> timer;         // more timed replays (and live loops), same buffers
    std::uint64_t batchRays = 0;                // rays per batch (multipassBatchRays)
    std::uint64_t batches = 1;                  // batches the stream ran in
};

// Multipass's own buffers in the strategy slots of kernels/gpu_layout.h (kBindingStencil on), for
// `rays` rays and a traversal state of `traversalStateBytes` each: the stencil, the traversal
// state, the hit state, the per-ray counters and, with the control on the device
// (`deviceControl`), the ray lists (`listPartitions` each) and the oracle's control block
// (`batches` of them: the sizes of a stream's batches together, each with its own block).
std::vector<BufferSize> multipassBuffers(std::uint64_t rays, std::uint64_t traversalStateBytes, bool deviceControl,
                                         unsigned listPartitions = 1, std::uint64_t batches = 1);
// The device-controlled loop's ray lists for `rays` rays: T0, T1, W0, W1, each in `partitions`
// partitions that can each hold every ray, a ray index per entry.
std::uint64_t multipassListBytes(std::uint64_t rays, unsigned partitions);
// The traversal state the last pass saved, as bytes (tests compare it with the CPU's).
std::vector<std::uint8_t> downloadTraversalStates(GpuBuffers& buffers);

// Rays per batch: `requested` (strategy.batch_rays) if not 0, else the most rays whose largest
// per-ray record (the ray, the hit record, the traversal state of `traversalStateBytes`, the ray
// lists' `listBytesPerRay`) fits one binding (maxStorageBufferRange), a multiple of the workgroup size.
std::uint64_t multipassBatchRays(const DeviceInfo& device, std::uint64_t traversalStateBytes, std::uint64_t requested,
                                 unsigned workgroupSize, std::uint64_t listBytesPerRay = 0);

// One instrumented run (the oracle reads the ray-state counts after every pass), then the
// warm-ups and timed repetitions `timing` asks for (none: the timer does them later), replaying
// its pass sequence in one submission with instrumentation off; their hits must equal the
// instrumented run's. Throws rtbench::Error when the pass cap is reached. `query`: gpu::kQuery*.
MultipassRun runMultipass(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                          const MultipassOptions& options, const TimingOptions& timing,
                          std::uint32_t query = gpu::kQueryClosest);

}  // namespace rtbench
