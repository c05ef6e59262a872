#include "embree_config.h"

#include <algorithm>
#include <set>
#include <sstream>

#include "core/error.h"

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
    // First the form and the keys: Embree takes the last of a repeated key ("isa=avx2,isa=sse2"
    // would silently run SSE2), so a key given twice is refused before any value is judged.
    std::vector<std::pair<std::string, std::string>> pairs;
    {
        std::istringstream items(config);
        std::string item;
        std::set<std::string> seen;
        while (std::getline(items, item, ',')) {
            const std::size_t eq = item.find('=');
            if (eq == std::string::npos || eq == 0)
                throw Error("'" + item + "' is not key=value (e.g. \"isa=avx2,threads=2\")");
            const std::string key = item.substr(0, eq);
            if (!seen.insert(key).second)
                throw Error("key '" + key + "' is given twice in \"" + config + "\" (give each key once)");
            pairs.emplace_back(key, item.substr(eq + 1));
        }
    }
    for (const auto& [key, value] : pairs) {
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
