// The strategy half of a method's seam. A strategy (branching, multipass) runs any structure's
// kernels on a Vulkan device: it lives in strategies/<name>/ with its host side, its CPU model of
// what the device counts, its accounting, and its config keys and columns. It checks itself: the
// device's hits and counts against the structure's CPU reference on the same rays.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "core/error.h"
#include "device/vulkan_context.h"
#include "methods/accounting.h"
#include "schema/column.h"
#include "strategies/ray_batch.h"
#include "structures/structure.h"

namespace rtbench {

struct TimingOptions {
    unsigned workgroupSize = 64;
    // Warm-ups and timed repetitions done within the strategy's run; the runner passes none and
    // times in rounds with the run's KernelTimer (harness/timing_rounds.h).
    int warmups = 1;
    int repetitions = 5;
};

// A series of times a strategy's timer adds beside its repetitions' totals, declared with the
// column its median goes to: a part of every repetition (TimedBatch::parts) or a loop the host
// controls, timed once a round (KernelTimer::timeHostLoops). The timer hands over the declaration
// itself, so samples.csv's names and the columns come from one place.
struct TimedSeries {
    std::string name;  // samples.csv's method: "kernel_traverse", "multipass_live"
    Column<double> median;
};

// One batch of timed repetitions, uninstrumented.
struct TimedBatch {
    double warmupMs = 0.0;   // the untimed warm-ups before them, together
    std::vector<double> ms;  // each repetition's GPU time
    // A repetition made of parts (multipass: its pass kinds): each part's GPU time per repetition,
    // as the series the strategy declares for it (StrategyType::series).
    std::vector<std::pair<const TimedSeries*, std::vector<double>>> parts;
};

// The host-controlled loops' times of one round, each as its declared series.
using HostLoopTimes = std::vector<std::pair<const TimedSeries*, double>>;

// The TimedBatch of a submission of identical repetitions, whose times `ms` come in order:
// the first `warmups` summed as the warm-up, the rest one each.
inline TimedBatch splitWarmups(const std::vector<double>& ms, int warmups) {
    TimedBatch batch;
    for (int i = 0; i < warmups; ++i) batch.warmupMs += ms.at(std::size_t(i));
    batch.ms.assign(ms.begin() + warmups, ms.end());
    return batch;
}

// What a strategy's run keeps on the device to time its kernels again, a batch at a time: the
// runner alternates its batches with Embree's in rounds, so that drift hits both.
class KernelTimer {
public:
    virtual ~KernelTimer() = default;
    // `warmups` untimed then `repetitions` timed repetitions, recorded into one submission.
    virtual TimedBatch time(int warmups, int repetitions) = 0;
    // Loops the host controls, timed on the host once per round, each a series the strategy
    // declares (multipass: its live loop, the instrumented passes with the oracle's per-pass
    // read-backs, the CPU-controlled loop of Christen 2005 §4.2.2 and §4.3.4).
    virtual HostLoopTimes timeHostLoops() { return {}; }
    // Throws (expectSameHits) when the last timed repetition's hits differ from the instrumented run's.
    virtual void checkHits() = 0;
};

// What a strategy's run measured and how it compares with the CPU reference. A mismatch is
// written to the row and then fails the run.
struct StrategyRun {
    std::vector<gpu::HitRecord> hits;  // instrumented run (per-ray counters filled)
    std::unique_ptr<KernelTimer> timer;  // times the kernels again, uninstrumented
    ArchitectureMetrics metrics;
    std::uint64_t cpuMismatches = 0;     // rays whose record differs from the CPU reference's
    bool cpuCompared = true;             // false: another's arithmetic (the driver's), judged by the exact reference only
    std::string countsMismatch;          // what of the pass or lane counts differs ("" if none)
    bool countsCompared = true;          // false: the device's counts are not the model's to judge (branching's lanes off lock step)
    std::uint64_t branchingMismatches = 0;  // multipass: rays whose record differs from rtTrace's
    // Where two of the strategy's CPU models disagree (cache.simulate: the cache replay's bytes and
    // the bandwidth accounting's); fails the run after the kernel's own checks.
    std::string modelMismatch;
    // Rays in subgroups that need more loop iterations than the device runs (the CPU lane model's
    // count against DeviceInfo::loopIterationLimit), and why; fails the run first.
    std::uint64_t truncatedRays = 0;
    std::string truncatedWhy;
};

// A results schema from which the strategy's kernel_ms measures another thing in the runs the
// conditions select: a comparison across it is of two measures, not a change (rtbench compare).
struct MeasureChange {
    int schema;                            // the first schema of the new measure
    std::vector<std::string> appliesWhen;  // "section.key=value" conditions, as KeySpec::appliesWhen's
    std::string what;                      // what kernel_ms is from `schema` on, and what it was
};

struct StrategyType {
    std::string name;  // the strategy.type value
    std::string help;
    std::vector<KeySpec> keys;        // read only when strategy.type is this name
    std::vector<ColumnSpec> columns;  // written only by its runs
    // Its timer's series (their columns are among `columns`); a run whose timer makes another fails.
    std::vector<const TimedSeries*> series;
    std::vector<MeasureChange> kernelMeasureChanges;  // oldest first
    // Device bytes per ray its own buffers take at least (multipass's state), for the runner's
    // refusal before the structure (and so the exact size) is known; 0: none per ray.
    std::uint64_t ownBytesPerRay = 0;
    std::string onlyStructure;  // the one structure.type it can trace ("": any)
    // Why a device cannot run it ("" when it can; null: any device that runs rtbench can): the
    // run fails with this before anything is loaded.
    std::string (*refusal)(const DeviceInfo& device) = nullptr;
    // What it traces, at one of two levels (pbrt-v4's RayIntegrator::Li against Integrator::Render):
    // - TraceBatch: the batch's rays, each on its own;
    // - TracePath: the whole path from the camera rays that ends in the batch (the wavefront, the
    //   path megakernel). Its time covers every generation and the shading passes between, so
    //   Embree traces every generation's rays too and the rates count them all.
    // Either uploads, runs one instrumented run of the batch's query (and the timed repetitions
    // `timing` asks for), compares with its CPU model, writes its own columns to `row` and returns
    // its timer.
    using TraceBatch = StrategyRun (*)(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                       const RunConfig& config, const TimingOptions& timing, Row& row);
    using TracePath = StrategyRun (*)(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                      const BatchPath& path, const RunConfig& config, const TimingOptions& timing, Row& row);
    std::variant<TraceBatch, TracePath> trace;
};

// The strategy's TraceBatch, for a caller that hands it rays alone (tests); rtbench::Error naming
// the strategy when it traces whole paths.
inline StrategyType::TraceBatch batchTracer(const StrategyType& strategy) {
    if (const auto* trace = std::get_if<StrategyType::TraceBatch>(&strategy.trace)) return *trace;
    throw Error("strategy.type = " + strategy.name + " traces whole paths, not a batch of rays alone");
}

// Throws, with the count of differing rays, when a timed run's hits differ from the instrumented
// run's (t and primitive); a NaN distance is named as what it is, an out-of-range input.
void expectSameHits(const std::vector<gpu::HitRecord>& timed, const std::vector<gpu::HitRecord>& counted,
                    const char* strategy);

}  // namespace rtbench
