#include "noise_guard.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "schema/columns.h"

namespace rtbench {

namespace {

std::string readProcFile(const char* path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return in ? text.str() : std::string();
}

}  // namespace

double machineBusyTicks(const std::string& procStat) {
    // "cpu  user nice system idle iowait irq softirq steal guest guest_nice" (proc(5)); guest
    // time is already inside user.
    std::istringstream lines(procStat);
    std::string line;
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        std::string name;
        fields >> name;
        if (name != "cpu") continue;
        double v[8];
        for (double& x : v)
            if (!(fields >> x)) return -1.0;
        return v[0] + v[1] + v[2] + v[5] + v[6] + v[7];  // all but idle and iowait
    }
    return -1.0;
}

double selfTicks(const std::string& procSelfStat) {
    // "pid (comm) state ppid ... utime stime": fields 14 and 15; comm may hold spaces and ')'.
    const std::size_t close = procSelfStat.rfind(')');
    if (close == std::string::npos) return -1.0;
    std::istringstream fields(procSelfStat.substr(close + 1));
    std::string field;
    double utime = 0, stime = 0;
    for (int i = 3; i <= 15; ++i) {  // field 3 (state) onwards
        if (!(fields >> field)) return -1.0;
        if (i == 14) utime = std::strtod(field.c_str(), nullptr);
        if (i == 15) stime = std::strtod(field.c_str(), nullptr);
    }
    return utime + stime;
}

CpuTimes sampleCpuTimes() {
    CpuTimes t;
    t.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    t.machineBusyTicks = machineBusyTicks(readProcFile("/proc/stat"));
    t.selfTicks = selfTicks(readProcFile("/proc/self/stat"));
    t.valid = t.machineBusyTicks >= 0 && t.selfTicks >= 0;
    return t;
}

double otherCpuFraction(const CpuTimes& before, const CpuTimes& after, unsigned cores, double ticksPerSecond) {
    const double wall = after.wallSeconds - before.wallSeconds;
    if (!before.valid || !after.valid || wall <= 0 || cores == 0 || ticksPerSecond <= 0) return -1.0;
    // /proc counts in clock ticks (10 ms at USER_HZ 100): a window of fewer than kMinTicks of the
    // machine's capacity cannot tell one stray tick from a busy neighbour.
    if (wall * double(cores) * ticksPerSecond < kMinTicks) return -1.0;
    const double others = (after.machineBusyTicks - before.machineBusyTicks) - (after.selfTicks - before.selfTicks);
    return std::clamp(others / ticksPerSecond / (wall * double(cores)), 0.0, 1.0);
}

// A percentage in plain digits: a spread of 1,140% reads "1140", never "1.14e+03".
static std::string percentText(double fraction) {
    const double percent = 100.0 * fraction;
    return percent >= 1000.0 ? std::to_string(std::llround(percent)) : formatNumber(percent, 3);
}

std::string spreadWarning(const std::string& method, const SampleStats& s, double noiseCi, double noiseCv) {
    if (s.ci) {
        const double halfWidth = s.relativeHalfWidth();
        if (halfWidth <= noiseCi) return "";
        return method + " interval +-" + percentText(halfWidth) + "% > experiment.noise_ci " + formatNumber(noiseCi, 3);
    }
    if (!s.cv || *s.cv <= noiseCv) return "";
    return method + " CV " + formatNumber(*s.cv, 3) + " (" + std::to_string(s.n) + " repetitions: no interval) > experiment.noise_cv " +
           formatNumber(noiseCv, 3);
}

double loadAverage() {
    double load[1];
    return ::getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

unsigned deviceHostThreads(bool cpuDevice, unsigned cores) {
    if (!cpuDevice) return 0;
    if (const char* env = std::getenv("LP_NUM_THREADS")) return std::min(unsigned(std::strtoul(env, nullptr, 10)), 32u);
    return std::min(cores, 32u);
}

}  // namespace rtbench
