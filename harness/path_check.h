// Rays after the first hit, judged by where they came from: a ray leaves from the hit of the ray
// before it on its path (the camera ray, an earlier reflection), as the run's structure found it.
// Where that hit is not an exact first hit on the full scene, the ray left from another surface
// than the exact scene's: such rays are counted, never silently compared against another ray
// (each is still judged as the ray it is).
#pragma once
#include <cstdint>
#include <vector>

#include "harness/exact_reference.h"
#include "rays/workload.h"

namespace rtbench {

// Of the batch rays `sampled` (increasing indices into workload.batch.rays), those with a ray
// earlier on their path whose hit `reference` contradicts (ExactHits::judge; sameTriangles false:
// by hit or miss alone). cameraRays are the rays of the workload's camera hits.
std::uint64_t pathsLeavingWrongHits(const ExactReference& reference, const std::vector<gpu::Ray>& cameraRays,
                                    const Workload& workload, const std::vector<std::uint32_t>& sampled,
                                    bool sameTriangles);

}  // namespace rtbench
