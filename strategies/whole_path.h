// What the strategies that trace a whole path from the camera rays share (StrategyType::TracePath:
// the wavefront's queues, the path megakernel's registers): the refusals of what they cannot trace,
// the capacities of a path's generations, and the device buffers of kernels/gpu_layout.h's
// kBindingPath* slots with the passes, the material, the camera rays and the vertices uploaded.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/gpu_buffers.h"
#include "strategies/ray_batch.h"
#include "structures/structure.h"
#include "schema/columns.h"

namespace rtbench {

// Nothing, or rtbench::Error naming `strategy` and what of `path` it cannot trace: surfaces of
// more than one material or lights, more passes than kPathMaxPasses.
void requireTraceablePath(const BatchPath& path, const std::string& strategy);

// The most rays a generation of a path of `cameraRays` rays through passes of fan-outs `fanOuts`
// can hold (every ray of the one before making fan-out rays), and the most slots a pass can fill.
// Throws when a generation would outgrow 32-bit indices.
struct WholePathCapacity {
    std::uint64_t queue = 0, slots = 0;
};
WholePathCapacity wholePathCapacity(std::uint64_t cameraRays, const std::vector<std::uint32_t>& fanOuts);
// The same for `path`: its camera rays and its passes' fan-outs.
WholePathCapacity wholePathCapacity(const BatchPath& path);

// The sizes of a whole path's buffers in the kBindingPath* slots, in order: the control block
// (with `groupSums` 4-byte entries after it), the camera rays, `queue` queue entries, `slots` made
// rays and their flags, the triangles.
struct WholePathSizes {
    std::uint64_t groupSums = 0, queue = 0, slots = 0;
};
// The run's buffers: the common rays and hits slots sized for `streamRays` (zeroed), the path's own
// slots, and the control block (passes, material and limits: x `queueCapacity`, y `slotCapacity`,
// z the passes), the camera rays and the triangles uploaded.
std::unique_ptr<GpuBuffers> uploadWholePath(VulkanContext& vk, const Structure& structure, const BatchPath& path,
                                            std::uint64_t streamRays, const WholePathSizes& sizes,
                                            std::uint32_t queueCapacity, std::uint32_t slotCapacity);

// A whole-path strategy's columns: the whole-traversal kernels' (rays_cut_short, the lane model's,
// stream_batches), whole_path_generations and whole_path_rays, which both write
// (writeWholePathColumns), then its `own` (results schema 19).
std::vector<ColumnSpec> wholePathStrategyColumns(std::vector<ColumnSpec> own);
void writeWholePathColumns(const BatchPath& path, Row& row);

}  // namespace rtbench
