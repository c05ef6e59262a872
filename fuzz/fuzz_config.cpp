// libFuzzer target for the experiment config loader (harness/config.h, loadExperimentText).
// Input: the config text. Expected: an ExperimentPlan or rtbench::Error (toml++'s parse_error
// must have been turned into one). Anything else is a finding: another exception (reported, then
// abort), a crash, a sanitizer report, a leak, a hang (-timeout) or a huge allocation.
#include <cstdint>
#include <string_view>

#include "fuzz_bodies.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string problem = fuzz::configInput(std::string_view(reinterpret_cast<const char*>(data), size));
    if (!problem.empty()) fuzz::finding("fuzz_config", problem);
    return 0;
}
