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

// Counts of one multipass run, the same whether the GPU or the simulator produced them.
struct MultipassCounts {
    std::array<std::uint64_t, kPassKinds> passes{};  // by PassKind
    std::uint64_t usefulTraverse = 0;   // rays served, summed over traverse passes
    std::uint64_t usefulIntersect = 0;  // rays served, summed over intersect passes
    std::uint64_t stencilWrites = 0;  // all passes
    std::uint64_t offsetReads = 0;
    std::uint64_t triangleReads = 0;
    std::vector<PassKind> sequence;   // every pass in order (setup first, write last)

    std::uint64_t totalPasses() const { return passes[0] + passes[1] + passes[2] + passes[3]; }
    bool operator==(const MultipassCounts&) const = default;
};

struct MultipassResult {
    std::vector<gpu::HitRecord> hits;  // with per-ray counters
    MultipassCounts counts;
};

// Throws rtbench::Error when the pass cap is reached with rays still active.
MultipassResult simulateMultipass(const UniformGrid& grid, const std::vector<gpu::Ray>& rays,
                                  const MultipassOptions& options);

}  // namespace rtbench
