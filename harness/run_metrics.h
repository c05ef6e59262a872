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
#include "structures/structure.h"
#include "noise_guard.h"
#include "statistics.h"
#include "timing_rounds.h"
#include "writers.h"

namespace rtbench {

// The columns writeArchitectureColumns writes, declared where it writes them.
const std::vector<ColumnSpec>& architectureColumns();

// The architecture's counts (Purcell's passes and SIMD efficiency, work per ray, bytes by data
// type) and the structure's own columns for `rays` rays.
void writeArchitectureColumns(const ArchitectureMetrics& m, const Structure& structure, std::uint64_t rays, Row& row);

// The columns writeTimingResults writes, in their places among runs.csv's: each method's
// statistics and rate (kernel, embree1, embree16), the speed ratio, how the rounds went, and the
// machine's load the noise guard read.
enum class TimingColumnPart { Methods, Ratio, Rounds, Machine };
std::vector<ColumnSpec> timingColumns(TimingColumnPart part);

// A run's timing (harness/timing_rounds.h) into `row`: each method's statistics, the strategy's
// own series (StrategyType::series), the speed ratio with its interval, and the noise guard's
// reading of the window from `before` to now (harness/noise_guard.h).
void writeTimingResults(const RunConfig& run, const VulkanContext& vk, const StrategyType& strategy, std::size_t rays,
                        const RoundsResult& timed, const CpuTimes& before, Row& row);

// Accuracy against the exact reference into <prefix>false_misses, _false_hits, _wrong_primitive,
// _wrong_ppm and the distance errors (prefix "exact_" for the kernel, "embree_exact_" for Embree),
// and the columns it writes.
void writeExactColumns(bool embree, const ExactAccuracy& a, Row& row);
const std::vector<ColumnSpec>& exactColumns(bool embree);

// The batch's hits with the exact ones in place of the sampled rays': what the exact render is
// made from. A kernel's answer the exact reference confirms keeps its triangle, and shades as it:
// one of a tie's triangles, or for an any-hit query any triangle when the exact ray hits too (on
// the same triangles: not a simplified scene).
std::vector<gpu::HitRecord> exactInPlace(const std::vector<gpu::HitRecord>& hits, const ExactHits& exact, bool sameTriangles,
                                         std::uint32_t query);

// Image-level accuracy (harness/image_compare.h, idiff's measures): the 8-bit grey of `shades`
// (harness/images.h: a hit's shade, -1 a miss) against `exactShades`, width x height values:
// a run's image and the same image made with the exact hits, or one value per sampled ray.
const std::vector<ColumnSpec>& imageColumns();
void writeImageAccuracy(const std::vector<float>& shades, const std::vector<float>& exactShades, unsigned width,
                        unsigned height, Row& row);

}  // namespace rtbench
