// libFuzzer target for the experiment config loader (harness/config.h, loadExperimentText).
// Input: the config text. Expected: an ExperimentPlan or rtbench::Error (toml++'s parse_error
// must have been turned into one). Anything else is a finding: another exception (reported, then
// abort), a crash, a sanitizer report, a leak, a hang (-timeout) or a huge allocation.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "harness/config.h"
#include "fuzz_common.h"
#include "structures/error.h"

namespace {

[[noreturn]] void finding(const std::string& what) { fuzz::finding("fuzz_config", what); }
using fuzz::verbose;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const rtbench::ExperimentPlan plan = rtbench::loadExperimentText(text, "fuzz.toml", "/nonexistent-rtbench-fuzz");
        // Exercise what the runner and writers call on every run of the plan.
        for (const rtbench::RunConfig& run : plan.runs) {
            (void)run.canonical();
            (void)run.hash();
            (void)run.label();
        }
    } catch (const rtbench::Error& e) {
        if (verbose()) std::fprintf(stderr, "rtbench::Error: %s\n", e.what());
        // the expected outcome for a bad config
    } catch (const std::exception& e) {
        finding(std::string("exception other than rtbench::Error: ") + typeid(e).name() + ": " + e.what());
    } catch (...) {
        finding("a non-std exception escaped loadExperimentText");
    }
    return 0;
}
