// CPU functional simulator of the multipass ray caster (Purcell §4.1): runs the kernels' per-ray
// source (kernels/multipass_steps.glsl, compiled as C++) pass by pass with the same scheduler,
// so its hits, per-ray counters, pass sequence and event counts must equal the GPU's exactly.
#pragma once
#include <array>
#include <vector>

#include "grid_reference.h"
#include "multipass_schedule.h"

namespace rtbench {

namespace gridref {
#define RT_OUT(T) T&
#define RT_INOUT(T) T&
#define precise
struct MultipassSteps : GridTraversal {
    std::uint32_t traverseStepsPerPass = 1;
    std::uint32_t intersectionsPerPass = 1;
    std::uint32_t suppressFinishedReads = 0;
#include "../kernels/multipass_steps.glsl"
};
#undef precise
#undef RT_INOUT
#undef RT_OUT
}  // namespace gridref

struct MultipassResult {
    std::vector<gpu::HitRecord> hits;  // with per-ray counters
    MultipassCounts counts;
};

// Throws rtbench::Error when the pass cap is reached with rays still active.
MultipassResult simulateMultipass(const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                                  const MultipassOptions& options);

}  // namespace rtbench
