// What both fuzz targets share: how a finding is reported, and the triage switch.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "core/error.h"

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

// Runs `body`: rtbench::Error is the expected outcome for a bad input (printed when verbose());
// any other exception escaping `entry` (the function under test) is a finding.
template <class Body>
void expectOnlyRtbenchErrors(const char* target, const char* entry, Body&& body) {
    try {
        body();
    } catch (const rtbench::Error& e) {
        if (verbose()) std::fprintf(stderr, "rtbench::Error: %s\n", e.what());
    } catch (const std::exception& e) {
        finding(target, std::string("exception other than rtbench::Error from ") + entry + ": " +
                            typeid(e).name() + ": " + e.what());
    } catch (...) {
        finding(target, std::string("a non-std exception escaped ") + entry);
    }
}

}  // namespace fuzz
