#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "strategies/ray_batch.h"

namespace rtbench {

Agreement compareHits(const std::vector<gpu::HitRecord>& hits, const std::vector<gpu::HitRecord>& reference,
                      std::uint32_t query) {
    Agreement a;
    a.rays = hits.size();
    a.primitivesCompared = answersNearest(query);
    double errorSum = 0.0;
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const bool hit = hits[i].primitive != gpu::kNoHit;
        const bool refHit = reference[i].primitive != gpu::kNoHit;
        if (hit != refHit) {
            ++a.hitMissMismatches;
            continue;
        }
        if (!hit) continue;
        ++a.bothHit;
        if (!a.primitivesCompared) continue;
        if (hits[i].primitive != reference[i].primitive) ++a.primitiveMismatches;
        const double ref = reference[i].t;
        const double err = ref != 0.0 ? std::abs(double(hits[i].t) - ref) / std::abs(ref) : std::abs(double(hits[i].t));
        errorSum += err;
        a.relDistanceErrorMax = std::max(a.relDistanceErrorMax, err);
    }
    if (a.rays) a.hitMissAgreement = 1.0 - double(a.hitMissMismatches) / double(a.rays);
    if (a.bothHit && a.primitivesCompared) {
        a.samePrimitiveAgreement = 1.0 - double(a.primitiveMismatches) / double(a.bothHit);
        a.relDistanceErrorMean = errorSum / double(a.bothHit);
    }
    return a;
}

WorkStats workStats(const std::vector<gpu::HitRecord>& hits) {
    WorkStats w;
    for (const gpu::HitRecord& h : hits) {
        w.hits += h.primitive != gpu::kNoHit;
        w.cellsTotal += h.cellsVisited;
        w.trianglesTotal += h.trianglesTested;
        w.stepsTotal += h.traversalSteps;
        w.stepsPerRayMax = std::max(w.stepsPerRayMax, h.traversalSteps);
        w.cellsPerRayMax = std::max(w.cellsPerRayMax, h.cellsVisited);
        w.trianglesPerRayMax = std::max(w.trianglesPerRayMax, h.trianglesTested);
        w.workPerRayMax = std::max(w.workPerRayMax, h.traversalSteps + h.trianglesTested);
    }
    if (!hits.empty()) {
        w.cellsPerRayMean = double(w.cellsTotal) / double(hits.size());
        w.trianglesPerRayMean = double(w.trianglesTotal) / double(hits.size());
    }
    return w;
}

std::uint64_t recordMismatches(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b) {
    std::uint64_t mismatches = 0;
    for (std::size_t i = 0; i < a.size(); ++i) mismatches += std::memcmp(&a[i], &b[i], sizeof(gpu::HitRecord)) != 0;
    return mismatches;
}


}  // namespace rtbench
