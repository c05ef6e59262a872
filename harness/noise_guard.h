// The noise guard: what else the machine did while a run was timed. lavapipe's threads and
// Embree's TBB threads run on the host's cores; another process on them (a build, a test suite,
// a second sweep) slows whichever is timed, and a timing taken beside it is not a result of record.
#pragma once
#include <string>

#include "statistics.h"

namespace rtbench {

// The host's CPU time at one moment (Linux /proc): every process's busy time and this process's
// (all its threads, lavapipe's and TBB's included), in clock ticks.
struct CpuTimes {
    double machineBusyTicks = 0.0;  // /proc/stat "cpu": user nice system irq softirq steal
    double selfTicks = 0.0;         // /proc/self/stat: utime + stime
    double wallSeconds = 0.0;       // steady clock
    bool valid = false;             // /proc could be read
};
CpuTimes sampleCpuTimes();

// The parsers, on the files' text (tests feed them).
double machineBusyTicks(const std::string& procStat);  // -1 when the "cpu" line is not there
double selfTicks(const std::string& procSelfStat);     // -1 when malformed

// What other processes used between two samples, as a fraction of the machine's CPU time
// (cores x wall time): 0 on a quiet machine, 1 when others kept every core busy. Hypervisor
// steal time counts as others'. -1 when either sample is invalid or the window held fewer than
// kMinTicks clock ticks of the machine's capacity (too short to tell).
constexpr double kMinTicks = 100.0;
double otherCpuFraction(const CpuTimes& before, const CpuTimes& after, unsigned cores, double ticksPerSecond);

// Why one method's repetitions are not results of record, or "" when they are. The guard judges
// the statistic the results publish, the median: where 6 or more repetitions give its 95%
// interval (order statistics), a half-width beyond +-noiseCi of the median; below 6, a coefficient
// of variation above noiseCv; one repetition never (the caller says its noise is not measured).
// The mean's spread is not the median's: one slow repetition of ten moves the CV and not the
// median's interval (results schema 28; before, the CV at any count).
std::string spreadWarning(const std::string& method, const SampleStats& s, double noiseCi, double noiseCv);

// The 1-minute load average (getloadavg), -1 when unknown.
double loadAverage();

// The threads a device runs on the host's cores: for a CPU device (lavapipe) Mesa's
// LP_NUM_THREADS when set, else one per core, at most LP_MAX_THREADS (Mesa 22's lp_limits.h:
// 32; src/gallium/drivers/llvmpipe/lp_screen.c); 0 for a GPU.
unsigned deviceHostThreads(bool cpuDevice, unsigned cores);

}  // namespace rtbench
