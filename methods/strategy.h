// The strategy half of a method's seam. A strategy (branching, multipass) runs any structure's
// kernels on a Vulkan device: it lives in methods/<name>/ with its host side, its CPU model of
// what the device counts, its accounting, and its config keys and columns. It checks itself: the
// device's hits and counts against the structure's CPU reference on the same rays.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "device/vulkan_context.h"
#include "methods/accounting.h"
#include "methods/structure.h"

namespace rtbench {

struct TimingOptions {
    unsigned workgroupSize = 64;
    int warmups = 1;
    int repetitions = 5;
};

// What a strategy's run measured and how it compares with the CPU reference. A mismatch is
// written to the row and then fails the run.
struct StrategyRun {
    std::vector<gpu::HitRecord> hits;  // instrumented run (per-ray counters filled)
    std::vector<double> gpuMs;         // total GPU time of each timed repetition
    ArchitectureMetrics metrics;
    std::uint64_t cpuMismatches = 0;     // rays whose record differs from the CPU reference's
    std::string countsMismatch;          // what of the pass or lane counts differs ("" if none)
    std::uint64_t branchingMismatches = 0;  // multipass: rays whose record differs from rtTrace's
    // Rays in subgroups that need more loop iterations than the device runs (the CPU lane model's
    // count against DeviceInfo::loopIterationLimit), and why; fails the run first.
    std::uint64_t truncatedRays = 0;
    std::string truncatedWhy;
};

struct StrategyType {
    std::string name;  // the strategy.type value
    std::string help;
    std::vector<KeySpec> keys;        // read only when strategy.type is this name
    std::vector<ColumnSpec> columns;  // written only by its runs
    // Whether it keeps per-ray traversal state on the device (sizes the buffers before allocating).
    bool perRayState = false;
    // Uploads, runs one instrumented and then the timed repetitions, compares with the CPU
    // reference, and writes its own columns to `row`.
    StrategyRun (*run)(VulkanContext& vk, const Structure& structure, const std::vector<gpu::Ray>& rays,
                       const RunConfig& config, const TimingOptions& timing, Row& row);
};

// Throws, with the count of differing rays, when a timed run's hits differ from the instrumented
// run's (t and primitive); a NaN distance is named as what it is, an out-of-range input.
void expectSameHits(const std::vector<gpu::HitRecord>& timed, const std::vector<gpu::HitRecord>& counted,
                    const char* strategy);

}  // namespace rtbench
