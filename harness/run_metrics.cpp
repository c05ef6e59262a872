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
    if (const WalkColumns* walk = structure.walkColumns()) walk->write(w.cellsPerRayMean, w.cellsPerRayMax, m.bytes.cells, row);
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

namespace {

// A timed method's columns: <m>_ms_median, _min, _max, its spread (_mean, _std, _cv and the
// median's interval _ci_low, _ci_high; results schema 5) and its rate <m>_mrays_s.
struct MethodTimingColumns {
    using K = ColumnKind;
    struct Texts {
        std::string median, fastest, slowest, who, rate;
    };
    MethodTimingColumns(const std::string& m, const Texts& t)
        : median(group.add<double>({m + "_ms_median", K::Timing, "ms", t.median})),
          min(group.add<double>({m + "_ms_min", K::Timing, "ms", t.fastest})),
          max(group.add<double>({m + "_ms_max", K::Timing, "ms", t.slowest})),
          mean(group.add<double>({m + "_ms_mean", K::Timing, "ms", t.who + ", mean of the repetitions", 0.0, false, {}, 5})),
          stddev(group.add<double>({m + "_ms_std", K::Timing, "ms", t.who + ", sample standard deviation of the repetitions (empty for one)", 0.0, false, {}, 5}, 4)),
          cv(group.add<double>({m + "_ms_cv", K::Timing, "", t.who + ", coefficient of variation (std / mean; empty for one repetition)", 0.0, false, {}, 5}, 4)),
          ciLow(group.add<double>({m + "_ms_ci_low", K::Timing, "ms",
                                   t.who + ", 95% interval of the median from the order statistics (distribution-free, coverage at least 95%; "
                                   "empty below 6 repetitions; before results schema 23: percentile bootstrap): low end", 0.0, false, {}, 5})),
          ciHigh(group.add<double>({m + "_ms_ci_high", K::Timing, "ms", t.who + ", 95% interval of the median (as _ci_low): high end", 0.0, false, {}, 5})),
          rate(group.add<double>({m + "_mrays_s", K::Timing, "Mrays/s", t.rate})) {}
    ColumnGroup group;
    Column<double> median, min, max, mean, stddev, cv, ciLow, ciHigh, rate;

    // The series' statistics, and its rate for `rays` rays (none where the median is 0).
    SampleStats write(const std::vector<double>& ms, std::size_t rays, Row& row) const {
        const SampleStats s = summarize(ms);
        put(row, median, s.median);
        put(row, min, s.min);
        put(row, max, s.max);
        put(row, mean, s.mean);
        // Spread and interval where the samples have them (empty, never 0: one sample has no
        // spread, fewer than 6 no distribution-free 95% interval of the median).
        put(row, stddev, s.stddev);
        put(row, cv, s.cv);
        put(row, ciLow, s.ci ? std::optional<double>(s.ci->low) : std::nullopt);
        put(row, ciHigh, s.ci ? std::optional<double>(s.ci->high) : std::nullopt);
        put(row, rate, s.median > 0 ? double(rays) / (s.median * 1e3) : 0.0);
        return s;
    }
};

// The run's timing: the kernel's and Embree's on the same rays (every sample is in samples.csv),
// the speed ratio, and how the timing went with the noise guard's judgement of it.
struct TimingColumns {
    using K = ColumnKind;
    MethodTimingColumns kernel{
        "kernel",
        {"GPU time of the kernel(s), median of the repetitions (multipass with strategy.control = host, since results schema 25: "
         "host wall time of its live pass loop, the oracle's read-back after every pass)",
         "GPU time, fastest repetition", "GPU time, slowest repetition", "GPU time",
         "rays / median GPU time (the rays of every generation for a strategy that traces the whole path: whole_path_rays)"}};
    MethodTimingColumns embree1 = embree("embree1");
    MethodTimingColumns embree16 = embree("embree16");
    ColumnGroup ratio;
    Column<double> speedRatio = ratio.add<double>({"speed_ratio_vs_embree1", K::Timing, "ratio", "kernel Mrays/s / Embree rtcIntersect1 Mrays/s"}, 4);
    Column<double> ratioLow = ratio.add<double>(
        {"speed_ratio_ci_low", K::Timing, "ratio",
         "speed_ratio_vs_embree1: 95% interval, from each median's 97.5% order-statistic interval (both hold at once with at least "
         "95%; empty below 7 repetitions; before results schema 23: percentile bootstrap), low end", 0.0, false, {}, 5}, 4);
    Column<double> ratioHigh = ratio.add<double>(
        {"speed_ratio_ci_high", K::Timing, "ratio", "speed_ratio_vs_embree1: 95% interval (as _ci_low), high end", 0.0, false, {}, 5}, 4);
    ColumnGroup rounds;
    Column<int> repetitions = rounds.add<int>(
        {"timing_repetitions", K::Timing, "repetitions", "timed repetitions of each method (kernel, Embree 1, Embree 16)", 0.0, false, {}, 5});
    Column<int> roundCount = rounds.add<int>(
        {"timing_rounds", K::Timing, "rounds", "rounds they were timed in, each the kernel then Embree 1 then Embree 16", 0.0, false, {}, 5});
    Column<std::string> stop = rounds.add<std::string>(
        {"timing_stop", K::Timing, "",
         "why the timing stopped: repetitions (experiment.repetitions, fixed), converged (every interval within experiment.target_ci), "
         "max_repetitions, time_budget", 0.0, false, {}, 5});
    Column<double> seconds = rounds.add<double>(
        {"timing_s", K::Timing, "s",
         "wall time of the timed rounds (with experiment.target_ci, the judging after each included: what experiment.time_budget_s bounds)",
         0.0, false, {}, 5}, 4);
    Column<std::string> warning = rounds.add<std::string>(
        {"timing_warning", K::Context, "",
         "noise guard: why the run's timings are not results of record (a median's 95% interval wider than +- experiment.noise_ci of "
         "it, or below 6 repetitions a coefficient of variation above experiment.noise_cv; other processes above "
         "experiment.noise_other_cpu, one repetition: noise not measured); empty when clean", 0.0, false, {}, 5});
    ColumnGroup machine;
    Column<double> otherCpu = machine.add<double>(
        {"other_cpu_fraction", K::Timing, "fraction",
         "noise guard: CPU time other processes took while the run ran (from its scene to the end of its timing), over cores x wall "
         "time (Linux /proc/stat, hypervisor steal included); empty when that window held under 100 clock ticks of the machine",
         0.0, false, {}, 5}, 3);
    Column<double> loadAverage = machine.add<double>({"load_average", K::Timing, "", "noise guard: 1-minute load average when the timing ended", 0.0, false, {}, 5}, 3);
    Column<unsigned> deviceHostThreads = machine.add<unsigned>(
        {"device_host_threads", K::Context, "threads",
         "threads the device runs on the host's cores (lavapipe: LP_NUM_THREADS, else one per core up to 32; 0 for a GPU), beside "
         "embree_threads, against the machine's cores (context.json cpu_threads)", 0.0, false, {}, 5});

private:
    static MethodTimingColumns embree(const std::string& m) {
        return MethodTimingColumns(m, {"Embree " + m + " on the same rays, median", "Embree " + m + ", fastest repetition",
                                       "Embree " + m + ", slowest repetition", "Embree " + m, "rays / Embree's median time"});
    }
};

const TimingColumns& timingColumnsDeclared() {
    static const TimingColumns columns;
    return columns;
}

// The noise guard's reading of the window from `before` to now, and of each method's spread.
std::vector<std::string> noiseWarnings(const RunConfig& run, const VulkanContext& vk, const CpuTimes& before,
                                       const std::vector<std::pair<std::string, SampleStats>>& methods, Row& row) {
    const TimingColumns& c = timingColumnsDeclared();
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const double other = otherCpuFraction(before, sampleCpuTimes(), cores, double(::sysconf(_SC_CLK_TCK)));
    put(row, c.otherCpu, other < 0 ? std::nullopt : std::optional<double>(other));
    const double load = loadAverage();
    put(row, c.loadAverage, load < 0 ? std::nullopt : std::optional<double>(load));
    put(row, c.deviceHostThreads, deviceHostThreads(vk.info().type == "cpu", cores));
    std::vector<std::string> noisy;
    const double noiseCi = run.getFloat("experiment.noise_ci"), noiseCv = run.getFloat("experiment.noise_cv");
    for (const auto& [method, s] : methods)
        if (std::string w = spreadWarning(method, s, noiseCi, noiseCv); !w.empty()) noisy.push_back(std::move(w));
    if (!methods.front().second.cv) noisy.push_back("one repetition: its noise is not measured");
    if (other > run.getFloat("experiment.noise_other_cpu"))
        noisy.push_back("other processes took " + formatNumber(100 * other, 3) + "% of the machine's CPU time (> experiment.noise_other_cpu " +
                        formatNumber(run.getFloat("experiment.noise_other_cpu"), 3) + ")");
    return noisy;
}

}  // namespace

std::vector<ColumnSpec> timingColumns(TimingColumnPart part) {
    const TimingColumns& c = timingColumnsDeclared();
    switch (part) {
        case TimingColumnPart::Methods: {
            std::vector<ColumnSpec> specs;
            for (const MethodTimingColumns* m : {&c.kernel, &c.embree1, &c.embree16})
                specs.insert(specs.end(), m->group.specs().begin(), m->group.specs().end());
            return specs;
        }
        case TimingColumnPart::Ratio: return c.ratio.specs();
        case TimingColumnPart::Rounds: return c.rounds.specs();
        case TimingColumnPart::Machine: return c.machine.specs();
    }
    return {};
}

void writeTimingResults(const RunConfig& run, const VulkanContext& vk, const StrategyType& strategy, std::size_t rays,
                        const RoundsResult& timed, const CpuTimes& before, Row& row) {
    const TimingColumns& c = timingColumnsDeclared();
    const SampleStats k = c.kernel.write(timed.of("kernel"), rays, row);
    const SampleStats e1 = c.embree1.write(timed.of("embree1"), rays, row);
    const SampleStats e16 = c.embree16.write(timed.of("embree16"), rays, row);
    // The strategy's own series, each with the column it declares: the parts of a repetition, its
    // host-controlled loops. A series it does not declare is a timer out of step with its strategy.
    for (const auto& [name, ms] : timed.series) {
        if (name == "kernel" || name == "embree1" || name == "embree16") continue;
        const auto declared = std::find_if(strategy.series.begin(), strategy.series.end(),
                                           [&name](const TimedSeries* s) { return s->name == name; });
        if (declared == strategy.series.end())
            throw Error("strategy.type = " + strategy.name + ": its timer made the series " + name + ", which it does not declare");
        put(row, (*declared)->median, median(ms));
    }
    put(row, c.speedRatio, k.median > 0 ? e1.median / k.median : 0.0);
    const std::optional<Interval> ratio = ratioOfMediansInterval(timed.of("embree1"), timed.of("kernel"));
    put(row, c.ratioLow, ratio ? std::optional<double>(ratio->low) : std::nullopt);
    put(row, c.ratioHigh, ratio ? std::optional<double>(ratio->high) : std::nullopt);
    put(row, c.repetitions, timed.repetitions);
    put(row, c.roundCount, timed.rounds);
    put(row, c.stop, timed.stop);
    put(row, c.seconds, timed.seconds);
    std::string warning;
    for (const std::string& n : noiseWarnings(run, vk, before, {{"kernel", k}, {"embree1", e1}, {"embree16", e16}}, row))
        warning += (warning.empty() ? "" : "; ") + n;
    put(row, c.warning, warning);
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
