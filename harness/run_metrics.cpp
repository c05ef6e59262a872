#include "run_metrics.h"

#include <unistd.h>

#include <algorithm>
#include <thread>

#include "image_compare.h"
#include "strategies/ray_batch.h"

namespace rtbench {

namespace {

// A shaded pixel differs from the exact render's when its 8-bit grey differs (by a level or more).
constexpr double kPixelDifferThreshold = 0.5 / 255.0;

}  // namespace

void writeArchitectureColumns(const ArchitectureMetrics& m, const Structure& structure, std::uint64_t rays, Row& row) {
    const WorkStats& w = m.work;
    if (!m.countsKnown) return;  // left empty: not zero
    structure.writeWorkColumns(w.cellsPerRayMean, w.cellsPerRayMax, m.bytes.cells, row);
    row["work_per_ray_mean"] = formatNumber(double(w.cellsTotal + w.trianglesTotal) / double(rays));
    row["triangles_per_ray_mean"] = formatNumber(w.trianglesPerRayMean);
    row["triangles_per_ray_max"] = std::to_string(w.trianglesPerRayMax);
    row["traversal_steps_per_ray_mean"] = formatNumber(double(w.stepsTotal) / double(rays));
    row["traversal_steps_per_ray_max"] = std::to_string(w.stepsPerRayMax);
    row["passes_total"] = std::to_string(m.passes);
    row["simd_efficiency"] = formatNumber(m.simdEfficiency);
    if (m.laneUtilisation >= 0) row["simd_lane_utilisation"] = formatNumber(m.laneUtilisation);
    row["simd_efficiency_purcell"] = formatNumber(m.purcellSimdEfficiency);
    row["bytes_stencil"] = std::to_string(m.bytes.stencil);
    row["bytes_state"] = std::to_string(m.bytes.state);
    if (m.bytes.stack) row["bytes_stack"] = std::to_string(m.bytes.stack);
    if (m.bytes.compaction) row["bytes_compaction"] = std::to_string(m.bytes.compaction);
    row["bytes_triangle_list"] = std::to_string(m.bytes.triangleList);
    row["bytes_vertices"] = std::to_string(m.bytes.vertices);
    row["bytes_output"] = std::to_string(m.bytes.output);
    row["bytes_total"] = std::to_string(m.bytes.total());
    row["bytes_per_ray"] = formatNumber(double(m.bytes.total()) / double(rays));
    if (const InstructionEstimate& i = m.instructions; i.known) {
        row["instructions_per_step"] = std::to_string(i.perStep);
        row["instructions_per_test"] = std::to_string(i.perTest);
        row["instructions_traverse"] = std::to_string(i.traverse);
        row["instructions_intersect"] = std::to_string(i.intersect);
        row["instructions_other"] = std::to_string(i.other);
        row["instructions_total"] = std::to_string(i.total());
        row["instructions_per_byte"] = formatNumber(double(i.total()) / double(m.bytes.total()));
    }
}

SampleStats writeTimingColumns(const std::string& prefix, const std::vector<double>& ms, Row& row) {
    const SampleStats s = summarize(ms);
    row[prefix + "_ms_median"] = formatNumber(s.median);
    row[prefix + "_ms_min"] = formatNumber(s.min);
    row[prefix + "_ms_max"] = formatNumber(s.max);
    row[prefix + "_ms_mean"] = formatNumber(s.mean);
    // Spread and interval where the samples have them (empty, never 0: one sample has no spread,
    // fewer than 6 no distribution-free 95% interval of the median).
    row[prefix + "_ms_std"] = s.stddev ? formatNumber(*s.stddev, 4) : "";
    row[prefix + "_ms_cv"] = s.cv ? formatNumber(*s.cv, 4) : "";
    row[prefix + "_ms_ci_low"] = s.ci ? formatNumber(s.ci->low) : "";
    row[prefix + "_ms_ci_high"] = s.ci ? formatNumber(s.ci->high) : "";
    return s;
}

void writeTimingResults(const RunConfig& run, const VulkanContext& vk, std::size_t rays, const RoundsResult& timed,
                        const CpuTimes& before, Row& row) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const CpuTimes after = sampleCpuTimes();
    const SampleStats k = writeTimingColumns("kernel", timed.of("kernel"), row);
    row["kernel_mrays_s"] = formatNumber(k.median > 0 ? double(rays) / (k.median * 1e3) : 0.0);
    std::vector<std::string> noisy;
    const double noiseCi = run.getFloat("experiment.noise_ci"), noiseCv = run.getFloat("experiment.noise_cv");
    auto judge = [&](const std::string& method, const SampleStats& s) {
        if (std::string w = spreadWarning(method, s, noiseCi, noiseCv); !w.empty()) noisy.push_back(std::move(w));
    };
    judge("kernel", k);
    for (const char* m : {"embree1", "embree16"}) {
        const SampleStats e = writeTimingColumns(m, timed.of(m), row);
        row[std::string(m) + "_mrays_s"] = formatNumber(double(rays) / (e.median * 1e3));
        judge(m, e);
    }
    // The strategy's own series: the parts of a repetition, its host-controlled loops.
    for (const auto& [name, ms] : timed.series) {
        if (name.rfind("kernel_", 0) == 0) row["kernel_ms_" + name.substr(7)] = formatNumber(median(ms));
        else if (name != "kernel" && name != "embree1" && name != "embree16") row[name + "_ms_median"] = formatNumber(median(ms));
    }
    const double embreeMedian = median(timed.of("embree1"));
    row["speed_ratio_vs_embree1"] = formatNumber(k.median > 0 ? embreeMedian / k.median : 0.0, 4);
    const std::optional<Interval> ratio = ratioOfMediansInterval(timed.of("embree1"), timed.of("kernel"));
    row["speed_ratio_ci_low"] = ratio ? formatNumber(ratio->low, 4) : "";
    row["speed_ratio_ci_high"] = ratio ? formatNumber(ratio->high, 4) : "";
    row["timing_repetitions"] = std::to_string(timed.repetitions);
    row["timing_rounds"] = std::to_string(timed.rounds);
    row["timing_stop"] = timed.stop;
    row["timing_s"] = formatNumber(timed.seconds, 4);

    // The noise guard.
    const double other = otherCpuFraction(before, after, cores, double(::sysconf(_SC_CLK_TCK)));
    row["other_cpu_fraction"] = other < 0 ? "" : formatNumber(other, 3);
    const double load = loadAverage();
    row["load_average"] = load < 0 ? "" : formatNumber(load, 3);
    row["device_host_threads"] = std::to_string(deviceHostThreads(vk.info().type == "cpu", cores));
    if (!k.cv) noisy.push_back("one repetition: its noise is not measured");
    if (other > run.getFloat("experiment.noise_other_cpu"))
        noisy.push_back("other processes took " + formatNumber(100 * other, 3) + "% of the machine's CPU time (> experiment.noise_other_cpu " +
                        formatNumber(run.getFloat("experiment.noise_other_cpu"), 3) + ")");
    for (const std::string& n : noisy) row["timing_warning"] += (row["timing_warning"].empty() ? "" : "; ") + n;
}

void writeExactColumns(const std::string& prefix, const ExactAccuracy& a, Row& row) {
    row[prefix + "false_misses"] = std::to_string(a.falseMisses);
    row[prefix + "false_hits"] = std::to_string(a.falseHits);
    if (a.primitivesCompared) row[prefix + "wrong_primitive"] = std::to_string(a.wrongPrimitive);
    row[prefix + "wrong_ppm"] = formatNumber(a.wrongPerMillion(), 6);
    if (!a.distancesCompared) return;
    row[prefix + "distance_error_mean"] = formatNumber(a.distanceErrorMean, 4);
    row[prefix + "distance_error_max"] = formatNumber(a.distanceErrorMax, 4);
}

std::vector<gpu::HitRecord> exactInPlace(const std::vector<gpu::HitRecord>& hits, const ExactHits& exact, bool sameTriangles,
                                         std::uint32_t query) {
    std::vector<gpu::HitRecord> out = hits;
    for (std::size_t i = 0; i < exact.rays.size(); ++i) {
        gpu::HitRecord& h = out[exact.rays[i]];
        const bool hit = h.primitive != gpu::kNoHit;
        const bool tie = sameTriangles && hit && exact.isFirstHit(i, h.primitive);
        const bool anyHitRight = sameTriangles && hit && !answersNearest(query) && exact.hits[i].primitive != gpu::kNoHit;
        if (!tie && !anyHitRight) h.primitive = exact.hits[i].primitive;
    }
    return out;
}

void writeImageAccuracy(const std::vector<float>& shades, const std::vector<float>& exactShades, unsigned width,
                        unsigned height, Row& row) {
    std::vector<float> test, reference;
    for (float s : shades) test.push_back(float(pixelGrey(s)) / 255.0f);
    for (float s : exactShades) reference.push_back(float(pixelGrey(s)) / 255.0f);
    const ImageComparison c = compareImages(test, reference, width, height, kPixelDifferThreshold);
    row["image_psnr_db"] = formatNumber(c.psnr, 5);
    row["image_error_mean"] = formatNumber(c.meanError, 4);
    row["image_error_max"] = formatNumber(c.maxError, 4);
    row["image_pixels_differ"] = std::to_string(c.differing);
}

}  // namespace rtbench
