// A run's measurements into its row, after its timing: the architecture's counts (passes, lanes,
// bytes by data type), the timing statistics and the noise guard, accuracy against the exact
// reference ray by ray and as an image. The last stage of a run (harness/runner.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "config.h"
#include "device/vulkan_context.h"
#include "exact_reference.h"
#include "images.h"
#include "methods/accounting.h"
#include "methods/structure.h"
#include "noise_guard.h"
#include "statistics.h"
#include "timing_rounds.h"
#include "writers.h"

namespace rtbench {

// The architecture's counts (Purcell's passes and SIMD efficiency, work per ray, bytes by data
// type) and the structure's own columns for `rays` rays.
void writeArchitectureColumns(const ArchitectureMetrics& m, const Structure& structure, std::uint64_t rays, Row& row);

// A timed series' statistics into <prefix>_ms_median, _min, _max, _mean, _std, _cv, _ci_low, _ci_high.
SampleStats writeTimingColumns(const std::string& prefix, const std::vector<double>& ms, Row& row);

// A run's timing (harness/timing_rounds.h) into `row`: each method's statistics, the strategy's
// own series, the speed ratio with its interval, and the noise guard's reading of the window
// from `before` to now (harness/noise_guard.h).
void writeTimingResults(const RunConfig& run, const VulkanContext& vk, std::size_t rays, const RoundsResult& timed,
                        const CpuTimes& before, Row& row);

// Accuracy against the exact reference into <prefix>false_misses, _false_hits, _wrong_primitive,
// _wrong_ppm and the distance errors ("exact_" for the kernel, "embree_exact_" for Embree).
void writeExactColumns(const std::string& prefix, const ExactAccuracy& a, Row& row);

// The batch's hits with the exact ones in place of the sampled rays': what the exact render is
// made from. In a tie the kernel's triangle is as right as the lowest-numbered one, and shades as it.
std::vector<gpu::HitRecord> exactInPlace(const std::vector<gpu::HitRecord>& hits, const ExactHits& exact, bool sameTriangles);

// Image-level accuracy (harness/image_compare.h, idiff's measures): the 8-bit grey of the run's
// image (its hits) against the same image made with the exact hits of the sampled rays (the whole
// image when every ray is sampled, else the sampled rays' pixels as one row). `pixels`: the
// pixel of each batch ray (empty: ray i is pixel i).
void writeImageAccuracy(const HitImage& image, const HitImage& exactImage, const ExactHits& exact, std::size_t rays,
                        const std::vector<std::uint32_t>& pixels, Row& row);

}  // namespace rtbench
