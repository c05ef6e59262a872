// Passes, SIMD efficiency and bandwidth by data type for both architectures, from exact counts
// (definitions: README "Metric definitions"; Purcell et al. 2002 §4, Tables 1-2, Fig. 8).
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/gpu_layout.h"
#include "metrics.h"
#include "structures/multipass_reference.h"

namespace rtbench {

// Bytes each kernel moves per ray it serves, besides the counted voxel/triangle reads.
// Multipass state variables: Ray 32 B, RayTraversalState 32 B, RayHitState 16 B.
namespace bytes {
constexpr std::uint64_t kStencil = 1;        // the ray-state byte
constexpr std::uint64_t kCellOffset = 4;     // one entry of the per-voxel offsets
constexpr std::uint64_t kListEntry = 4;      // one triangle id of a voxel's list
constexpr std::uint64_t kTriangle = sizeof(gpu::Triangle);  // 3 vec4 vertices
constexpr std::uint64_t kOutput = 16;        // t, primitive, u, v of the hit record
constexpr std::uint64_t kSetupState = 32 + 32 + 16;          // read ray; write traversal + hit state
constexpr std::uint64_t kTraverseState = 32 + 32 + 16 + 32;  // read ray, traversal, hit; write traversal
constexpr std::uint64_t kIntersectState = 32 + 32 + 16 + 32 + 16;  // ... and write hit state
constexpr std::uint64_t kWriteState = 16;    // read hit state
constexpr std::uint64_t kBranchingState = 32;  // read the ray once (the rest lives in registers)
}  // namespace bytes

struct Bandwidth {
    std::uint64_t stencil = 0, state = 0, voxel = 0, triangleList = 0, vertices = 0, output = 0;
    std::uint64_t total() const { return stencil + state + voxel + triangleList + vertices + output; }
};

struct ArchitectureMetrics {
    std::uint64_t passes = 0;  // all dispatches
    std::uint64_t passesSetup = 0, passesTraverse = 0, passesIntersect = 0, passesWrite = 0;
    std::uint64_t passesLowerBound = 0;  // multipass only (Purcell): traverse + intersect passes
    double simdEfficiency = 0.0;
    Bandwidth bytes;
    WorkStats work;  // per-ray counters of the run's hit records
};

// Branching: one pass; SIMD efficiency = active lanes / lane slots over subgroup ballots.
ArchitectureMetrics branchingMetrics(const std::vector<gpu::HitRecord>& hits, std::uint64_t activeLanes,
                                     std::uint64_t laneSlots);

// Multipass: SIMD efficiency = mean over traverse and intersect passes of useful rays / rays.
ArchitectureMetrics multipassMetrics(const std::vector<gpu::HitRecord>& hits, const MultipassCounts& counts,
                                     const MultipassOptions& options);

}  // namespace rtbench
