// Passes, SIMD efficiency and bandwidth by data type for both strategies on any structure, from
// exact counts (definitions: README "Metric definitions"; Purcell et al. 2002 §4, Tables 1-2,
// Fig. 8). The structure supplies the unit costs of its reads (StructureCosts).
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/gpu_layout.h"
#include "methods/instructions/instruction_estimate.h"
#include "methods/metrics.h"
#include "strategies/multipass/multipass_schedule.h"
#include "structures/structure.h"

namespace rtbench {

// Bytes each kernel moves per ray it serves, besides the counted structure and triangle reads.
namespace bytes {
constexpr std::uint64_t kStencil = 1;                        // the ray-state byte
constexpr std::uint64_t kRay = sizeof(gpu::Ray);             // 32
constexpr std::uint64_t kHitState = sizeof(gpu::RayHitState);  // 16
constexpr std::uint64_t kOutput = 16;                        // t, primitive, u, v of the hit record
constexpr std::uint64_t kBranchingState = kRay;              // read the ray once (the rest lives in registers)
constexpr std::uint64_t kListEntry = 4;                      // a ray index in a compacted list
constexpr std::uint64_t kStackEntry = 4;                     // a node reference on a saved stack (BVH)
}  // namespace bytes

struct Bandwidth {
    std::uint64_t stencil = 0, state = 0, stack = 0, cells = 0, triangleList = 0, vertices = 0, output = 0;
    std::uint64_t compaction = 0;  // multipass with the control on the device: ray-list entries read and appended
    std::uint64_t total() const { return stencil + state + stack + cells + triangleList + vertices + output + compaction; }
};

struct ArchitectureMetrics {
    std::uint64_t passes = 0;  // all dispatches
    std::uint64_t passesSetup = 0, passesTraverse = 0, passesIntersect = 0, passesWrite = 0;
    std::uint64_t passesLowerBound = 0;  // multipass only (Purcell): traverse + intersect passes
    double simdEfficiency = 0.0;  // the strategy's own measure (simd_efficiency, as before schema 14)
    // Subgroup lane utilisation (Aila & Laine 2009): active lanes / lane slots over the kernel's
    // ballots; negative where no ballots are counted (multipass).
    double laneUtilisation = -1.0;
    // Purcell et al. 2002 Table 2's SIMD efficiency, "the average fraction of rays doing useful work
    // in a given pass", over the whole stream (misses included): multipass, rays served over stream
    // rays x traverse and intersect passes; a whole-traversal kernel, the stream run in lock step one
    // traversal step or triangle test at a time, Σ (steps + tests) / (rays x the most of one ray).
    double purcellSimdEfficiency = 0.0;
    Bandwidth bytes;
    WorkStats work;  // per-ray counters of the run's hit records
    InstructionEstimate instructions;  // Purcell Table 1 / Fig. 7's compute (branching and multipass)
    bool countsKnown = true;  // false: the method counts no work (the driver's ray query); only work.hits is set
};

// Branching: one pass; SIMD efficiency = active lanes / lane slots over subgroup ballots; Purcell's
// over the stream in lock step (lockStepStreamEfficiency).
// Σ (traversal steps + triangle tests) / (rays x the most of one ray): Purcell's SIMD efficiency of
// a whole-traversal kernel whose stream runs in lock step, one step or test an iteration (1 when
// no ray works).
double lockStepStreamEfficiency(const WorkStats& work, std::uint64_t rays);

ArchitectureMetrics branchingMetrics(const std::vector<gpu::HitRecord>& hits, std::uint64_t activeLanes,
                                     std::uint64_t laneSlots, const StructureCosts& costs);

// Multipass: SIMD efficiency = mean over traverse and intersect passes of useful rays / rays.
ArchitectureMetrics multipassMetrics(const std::vector<gpu::HitRecord>& hits, const MultipassCounts& counts,
                                     const MultipassOptions& options, const StructureCosts& costs);

}  // namespace rtbench
