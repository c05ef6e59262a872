// libFuzzer target for the readers of a results folder's files (runs.csv, samples.csv,
// context.json -> the recorded plan): what check, compare, merge, retime and resume read from a
// folder someone else may have written. Input: the first byte picks the file (byte % 3), the rest
// is its text. Expected: rows, samples or a plan, or rtbench::Error (fuzz_bodies.h).
#include <cstdint>
#include <string_view>

#include "fuzz_bodies.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string problem = fuzz::resultsInput(std::string_view(reinterpret_cast<const char*>(data), size));
    if (!problem.empty()) fuzz::finding("fuzz_results", problem);
    return 0;
}
