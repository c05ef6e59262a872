// Accuracy against Embree and per-ray work, from hit records on the same rays.
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/gpu_layout.h"

namespace rtbench {

struct Agreement {
    std::uint64_t rays = 0;
    std::uint64_t hitMissMismatches = 0;  // one hit, the other missed
    std::uint64_t bothHit = 0;
    std::uint64_t primitiveMismatches = 0;  // both hit, different triangle
    double hitMissAgreement = 1.0;         // fraction of rays with the same hit/miss outcome
    double samePrimitiveAgreement = 1.0;   // among rays both hit: fraction with the same triangle
    double relDistanceErrorMean = 0.0;     // |t - tRef| / tRef over rays both hit
    double relDistanceErrorMax = 0.0;
    bool primitivesCompared = true;  // false for an any-hit query: its answer is hit or miss
};

// `query` (gpu::kQuery*): an any-hit answer names no nearest triangle, so only hit or miss counts.
Agreement compareHits(const std::vector<gpu::HitRecord>& hits, const std::vector<gpu::HitRecord>& reference,
                      std::uint32_t query = gpu::kQueryClosest);

struct WorkStats {
    std::uint64_t hits = 0;
    double cellsPerRayMean = 0.0;
    std::uint32_t cellsPerRayMax = 0;
    double trianglesPerRayMean = 0.0;
    std::uint32_t trianglesPerRayMax = 0;
    std::uint64_t cellsTotal = 0;
    std::uint64_t trianglesTotal = 0;
    std::uint64_t stepsTotal = 0;  // DDA step attempts
    std::uint32_t stepsPerRayMax = 0;
    std::uint32_t workPerRayMax = 0;  // traversal steps + triangle tests of one ray, max
};

WorkStats workStats(const std::vector<gpu::HitRecord>& hits);

// Rays whose hit records differ in any bit (distance, primitive, barycentrics, counters).
std::uint64_t recordMismatches(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b);

}  // namespace rtbench
