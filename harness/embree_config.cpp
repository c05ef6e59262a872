#include "embree_config.h"

#include <algorithm>
#include <sstream>

#include "structures/error.h"

namespace rtbench {

namespace {

bool cpuSupports(const std::string& isa) {
    __builtin_cpu_init();
    if (isa == "sse2") return __builtin_cpu_supports("sse2");
    if (isa == "sse4.2") return __builtin_cpu_supports("sse4.2");
    if (isa == "avx") return __builtin_cpu_supports("avx");
    if (isa == "avx2") return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (isa == "avx512")  // Embree's AVX-512 path (SKX): F, CD, DQ, BW, VL
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
               __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
               __builtin_cpu_supports("avx512vl");
    return false;
}

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
    return out;
}

bool isInteger(const std::string& s, long lo, long hi) {
    if (s.empty() || s.size() > 9 ||
        !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return false;
    const long v = std::stol(s);
    return v >= lo && v <= hi;
}

}  // namespace

const std::vector<std::string>& embreeIsaNames() {
    static const std::vector<std::string> names = {"sse2", "sse4.2", "avx", "avx2", "avx512"};
    return names;
}

std::vector<std::string> embreeIsasSupportedHere() {
    std::vector<std::string> supported;
    for (const std::string& isa : embreeIsaNames())
        if (cpuSupports(isa)) supported.push_back(isa);
    return supported;
}

void checkEmbreeConfig(const std::string& config) {
    std::istringstream items(config);
    std::string item;
    while (std::getline(items, item, ',')) {
        const std::size_t eq = item.find('=');
        const std::string key = item.substr(0, eq),
                          value = eq == std::string::npos ? "" : item.substr(eq + 1);
        if (eq == std::string::npos || key.empty())
            throw Error("'" + item + "' is not key=value (e.g. \"isa=avx2,threads=2\")");
        if (key == "isa" || key == "max_isa") {
            const auto& names = embreeIsaNames();
            if (std::find(names.begin(), names.end(), value) == names.end())
                throw Error(key + "=" + value + ": unknown ISA (allowed: " + join(names) + ")");
            if (!cpuSupports(value))
                throw Error(key + "=" + value + ": this CPU cannot run it (supported here: " +
                            join(embreeIsasSupportedHere()) + ")");
        } else if (key == "threads") {
            if (!isInteger(value, 0, 1 << 20))
                throw Error("threads=" + value + ": expected an integer >= 0 (0: all)");
        } else if (key == "start_threads" || key == "set_affinity") {
            if (value != "0" && value != "1") throw Error(key + "=" + value + ": expected 0 or 1");
        } else if (key == "verbose") {
            if (!isInteger(value, 0, 3)) throw Error("verbose=" + value + ": expected 0 to 3");
        } else {
            throw Error("unknown Embree config key '" + key +
                        "' (allowed: isa, max_isa, threads, start_threads, set_affinity, verbose)");
        }
    }
}

}  // namespace rtbench
