#include "run_metrics.h"

#include <unistd.h>

#include <algorithm>
#include <thread>

#include "image_compare.h"
#include "schema/column.h"
#include "strategies/ray_batch.h"

namespace rtbench {

namespace {

// A shaded pixel differs from the exact render's when its 8-bit grey differs (by a level or more).
constexpr double kPixelDifferThreshold = 0.5 / 255.0;

// Work, SIMD efficiency and bytes by data type (exact, from instrumented kernels; equal to the CPU
// reference), and Purcell Table 1 / Fig. 7's compute estimated (methods/instructions/
// instruction_estimate.h, branching and multipass runs since results schema 17).
struct ArchitectureColumns {
    using K = ColumnKind;
    template <class T>
    using C = Column<T>;
    using U64 = std::uint64_t;
    using U32 = std::uint32_t;
    ColumnGroup group;
    C<double> workPerRayMean = group.add<double>(
        {"work_per_ray_mean", K::Exact, "operations", "cells or nodes visited + triangles tested per ray, measured: what predicted_work_per_ray predicts"});
    C<double> trianglesPerRayMean = group.add<double>({"triangles_per_ray_mean", K::Exact, "tests", "ray-triangle tests per ray, mean"});
    C<U32> trianglesPerRayMax = group.add<U32>({"triangles_per_ray_max", K::Exact, "tests", "ray-triangle tests per ray, max"});
    C<double> stepsPerRayMean = group.add<double>(
        {"traversal_steps_per_ray_mean", K::Exact, "steps", "traversal step attempts per ray (grid: DDA steps; BVH: references visited, inner nodes and leaves), mean"});
    C<U32> stepsPerRayMax = group.add<U32>({"traversal_steps_per_ray_max", K::Exact, "steps", "traversal step attempts per ray, max"});
    C<U64> passes = group.add<U64>({"passes_total", K::Exact, "passes", "kernel dispatches over the ray stream"});
    C<double> simdEfficiency = group.add<double>(
        {"simd_efficiency", K::Exact, "fraction",
         "the strategy's own measure, as written before schema 14 (two measures in one column; read the two below): "
         "simd_lane_utilisation for branching, persistent and the megakernel; for multipass Purcell's over the stream "
         "(control = host) or over its compacted lists (control = device: 1)"});
    C<double> laneUtilisation = group.add<double>(
        {"simd_lane_utilisation", K::Exact, "fraction",
         "branching, persistent, megakernel: active lanes / lane slots over the kernel's subgroup ballots (Aila & Laine "
         "2009), counted only where some lane of a subgroup still works (rays that miss at once are left out)",
         0.0, false, {"strategy.type=branching|persistent|megakernel"}, 14});
    C<double> purcellSimdEfficiency = group.add<double>(
        {"simd_efficiency_purcell", K::Exact, "fraction",
         "Purcell et al. 2002 Table 2's SIMD efficiency, the average fraction of the stream's rays doing useful work in a "
         "pass, misses included: multipass, rays served / (rays x traverse and intersect passes), whatever the control; "
         "branching, persistent, megakernel, the stream run in lock step one traversal step or triangle test at a time: "
         "sum of (steps + tests) / (rays x the most steps + tests of one ray)", 0.0, false, {}, 14});
    C<U64> bytesStencil = group.add<U64>({"bytes_stencil", K::Exact, "bytes", "ray-state byte reads and writes"});
    C<U64> bytesState = group.add<U64>({"bytes_state", K::Exact, "bytes", "per-ray state saved and restored"});
    C<U64> bytesStack = group.add<U64>(
        {"bytes_stack", K::Exact, "bytes", "multipass: node-stack entries pushed and popped, 4 bytes each (BVH; its stack stays in memory)"});
    C<U64> bytesCompaction = group.add<U64>(
        {"bytes_compaction", K::Exact, "bytes", "multipass with strategy.control = device: compacted ray-list entries read and appended, 4 bytes each",
         0.0, false, {}, 13});
    C<U64> bytesTriangleList = group.add<U64>({"bytes_triangle_list", K::Exact, "bytes", "triangle-list entries read"});
    C<U64> bytesVertices = group.add<U64>({"bytes_vertices", K::Exact, "bytes", "triangle vertices read"});
    C<U64> bytesOutput = group.add<U64>({"bytes_output", K::Exact, "bytes", "hit records written"});
    C<U64> bytesTotal = group.add<U64>({"bytes_total", K::Exact, "bytes", "all categories"});
    C<double> bytesPerRay = group.add<double>({"bytes_per_ray", K::Exact, "bytes", "bytes_total / rays"});
    C<U64> perStep = instructions("instructions_per_step",
                                  "of one traversal event (grid: rtDdaStep, a DDA step; BVH: rtBvhChildren, an inner node)");
    C<U64> perTest = instructions("instructions_per_test", "of one ray-triangle test (rtIntersectStored, the run's test)");
    C<U64> traverse = instructions("instructions_traverse",
                                   "x exact counts: traversal (Fig. 7's traverser): steps x instructions_per_step, and for multipass "
                                   "each ray a traverse pass serves x the traverse kernel's other instructions");
    C<U64> intersect = instructions("instructions_intersect",
                                    "x exact counts: intersection (Fig. 7's intersector): tests x instructions_per_test, and for "
                                    "multipass each ray an intersect pass serves x the intersect kernel's other instructions");
    C<U64> other = instructions("instructions_other",
                                "x rays: the rest of the kernel (branching) or the setup and write kernels (multipass); rays the "
                                "stencil turns away cost none (Purcell's early fragment kill)");
    C<U64> total = instructions("instructions_total", "", "instructions_traverse + instructions_intersect + instructions_other");
    C<double> perByte = group.add<double>({"instructions_per_byte", K::Exact, "ratio",
                                           "instructions_total / bytes_total: compute against bandwidth (Purcell §4.2)", 0.0, false,
                                           {"strategy.type=branching|multipass"}, 17});

private:
    // An estimate's column (`estimate` empty: a sum of the others).
    C<U64> instructions(std::string name, const std::string& what, const std::string& sum = "") {
        const std::string estimate = "estimate: static SPIR-V instructions (glslang, unoptimised; every branch counted) ";
        return group.add<U64>({std::move(name), K::Exact, "instructions", sum.empty() ? estimate + what : sum, 0.0, false,
                               {"strategy.type=branching|multipass"}, 17});
    }
};

const ArchitectureColumns& architecture() {
    static const ArchitectureColumns columns;
    return columns;
}

}  // namespace

const std::vector<ColumnSpec>& architectureColumns() { return architecture().group.specs(); }

void writeArchitectureColumns(const ArchitectureMetrics& m, const Structure& structure, std::uint64_t rays, Row& row) {
    const WorkStats& w = m.work;
    if (!m.countsKnown) return;  // left empty: not zero
    const ArchitectureColumns& c = architecture();
    structure.writeWorkColumns(w.cellsPerRayMean, w.cellsPerRayMax, m.bytes.cells, row);
    put(row, c.workPerRayMean, double(w.cellsTotal + w.trianglesTotal) / double(rays));
    put(row, c.trianglesPerRayMean, w.trianglesPerRayMean);
    put(row, c.trianglesPerRayMax, w.trianglesPerRayMax);
    put(row, c.stepsPerRayMean, double(w.stepsTotal) / double(rays));
    put(row, c.stepsPerRayMax, w.stepsPerRayMax);
    put(row, c.passes, m.passes);
    put(row, c.simdEfficiency, m.simdEfficiency);
    if (m.laneUtilisation >= 0) put(row, c.laneUtilisation, m.laneUtilisation);
    put(row, c.purcellSimdEfficiency, m.purcellSimdEfficiency);
    put(row, c.bytesStencil, m.bytes.stencil);
    put(row, c.bytesState, m.bytes.state);
    if (m.bytes.stack) put(row, c.bytesStack, m.bytes.stack);
    if (m.bytes.compaction) put(row, c.bytesCompaction, m.bytes.compaction);
    put(row, c.bytesTriangleList, m.bytes.triangleList);
    put(row, c.bytesVertices, m.bytes.vertices);
    put(row, c.bytesOutput, m.bytes.output);
    put(row, c.bytesTotal, m.bytes.total());
    put(row, c.bytesPerRay, double(m.bytes.total()) / double(rays));
    if (const InstructionEstimate& i = m.instructions; i.known) {
        put(row, c.perStep, i.perStep);
        put(row, c.perTest, i.perTest);
        put(row, c.traverse, i.traverse);
        put(row, c.intersect, i.intersect);
        put(row, c.other, i.other);
        put(row, c.total, i.total());
        put(row, c.perByte, double(i.total()) / double(m.bytes.total()));
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

namespace {

// Accuracy against the exact reference (harness/exact_reference.h), the kernel's ("exact_":
// deterministic counts) or Embree's ("embree_exact_": its floating-point path decides, compared
// within a tolerance).
struct ExactColumns {
    using U64 = std::uint64_t;
    explicit ExactColumns(bool embree)
        : prefix(embree ? "embree_exact_" : "exact_"), who(embree ? "Embree" : "the kernel"),
          kind(embree ? ColumnKind::Reference : ColumnKind::Exact) {}
    const std::string prefix, who;
    const ColumnKind kind;
    ColumnGroup group;
    Column<U64> falseMisses = group.add<U64>({prefix + "false_misses", kind, "rays", "the exact ray hits, " + who + " missed (a leak)", 1e-4, true});
    Column<U64> falseHits = group.add<U64>({prefix + "false_hits", kind, "rays", "the exact ray misses, " + who + " hit", 1e-4, true});
    Column<U64> wrongPrimitive = group.add<U64>(
        {prefix + "wrong_primitive", kind, "rays",
         "both hit; " + who + "'s triangle is not one the exact ray hits first (empty for a simplified scene: other triangles, and for any-hit rays: any triangle answers)",
         1e-4, true});
    Column<double> wrongPpm = group.add<double>(
        {prefix + "wrong_ppm", kind, "ppm", "false misses + false hits + wrong primitive, per million exact_rays (of primary rays: wrong pixels)", 100.0});
    Column<double> distanceErrorMean = group.add<double>(
        {prefix + "distance_error_mean", kind, "", "|t - t_exact| / t_exact, mean over rays both hit", 1e-6}, 4);
    Column<double> distanceErrorMax = group.add<double>({prefix + "distance_error_max", kind, "", "|t - t_exact| / t_exact, max", 1e-6}, 4);
};

const ExactColumns& exactOf(bool embree) {
    static const ExactColumns kernel(false), embreeColumns(true);
    return embree ? embreeColumns : kernel;
}

// Image-level accuracy, as OpenImageIO's idiff measures it, on the pixels of the exact_rays.
struct ImageColumns {
    using K = ColumnKind;
    ColumnGroup group;
    Column<double> psnr = group.add<double>(
        {"image_psnr_db", K::Exact, "dB", "shaded pixels (8-bit grey, as the PNG) of the run's image against the same image made with the exact hits on the full scene (rays after the first hit: the batch's image, of its rays' own hits or of the camera hits they change; since results schema 10): PSNR, 20 log10(1 / RMS error) on [0, 1]; inf when equal"},
        5);
    Column<double> errorMean = group.add<double>({"image_error_mean", K::Exact, "", "shaded pixels against the exact render: mean |difference|"}, 4);
    Column<double> errorMax = group.add<double>({"image_error_max", K::Exact, "", "shaded pixels against the exact render: largest |difference|"}, 4);
    Column<std::uint64_t> pixelsDiffer = group.add<std::uint64_t>(
        {"image_pixels_differ", K::Exact, "pixels", "shaded pixels whose 8-bit grey differs from the exact render's"});
};

const ImageColumns& imageOf() {
    static const ImageColumns columns;
    return columns;
}

}  // namespace

const std::vector<ColumnSpec>& exactColumns(bool embree) { return exactOf(embree).group.specs(); }
const std::vector<ColumnSpec>& imageColumns() { return imageOf().group.specs(); }

void writeExactColumns(bool embree, const ExactAccuracy& a, Row& row) {
    const ExactColumns& c = exactOf(embree);
    put(row, c.falseMisses, a.falseMisses);
    put(row, c.falseHits, a.falseHits);
    if (a.primitivesCompared) put(row, c.wrongPrimitive, a.wrongPrimitive);
    put(row, c.wrongPpm, a.wrongPerMillion());
    if (!a.distancesCompared) return;
    put(row, c.distanceErrorMean, a.distanceErrorMean);
    put(row, c.distanceErrorMax, a.distanceErrorMax);
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
    const ImageColumns& columns = imageOf();
    put(row, columns.psnr, c.psnr);
    put(row, columns.errorMean, c.meanError);
    put(row, columns.errorMax, c.maxError);
    put(row, columns.pixelsDiffer, c.differing);
}

}  // namespace rtbench
