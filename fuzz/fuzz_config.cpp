// libFuzzer target for the experiment config loader (harness/config.h, loadExperimentText).
// Input: the config text. Expected: an ExperimentPlan or rtbench::Error (toml++'s parse_error
// must have been turned into one). Anything else is a finding: another exception (reported, then
// abort), a crash, a sanitizer report, a leak, a hang (-timeout) or a huge allocation.
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "harness/config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    fuzz::expectOnlyRtbenchErrors("fuzz_config", "loadExperimentText", [&] {
        const rtbench::ExperimentPlan plan = rtbench::loadExperimentText(text, "fuzz.toml", "/nonexistent-rtbench-fuzz");
        // Exercise what the runner and writers call on every run of the plan.
        for (const rtbench::RunConfig& run : plan.runs) {
            (void)run.canonical();
            (void)run.hash();
            (void)run.label();
        }
    });
    return 0;
}
