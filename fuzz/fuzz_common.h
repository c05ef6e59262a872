// What both fuzz targets share: how a finding is reported, and the triage switch.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <string>

namespace fuzz {

// Reports a finding that is not a crash (a wrong result, a stray exception) and aborts, so that
// libFuzzer keeps the input.
[[noreturn]] inline void finding(const char* target, const std::string& what) {
    std::fprintf(stderr, "\n==%s== FINDING: %s\n", target, what.c_str());
    std::fflush(stderr);
    std::abort();
}

// RTBENCH_FUZZ_VERBOSE=1: print the rtbench::Error of each input (triage: build-fuzz/fuzz/TARGET FILE).
inline bool verbose() {
    static const bool on = [] {
        const char* v = std::getenv("RTBENCH_FUZZ_VERBOSE");
        return v && *v && std::string(v) != "0";
    }();
    return on;
}

}  // namespace fuzz
