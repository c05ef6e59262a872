// The SPIR-V of every kernel, compiled by CMake and embedded in the binary (no files to find at
// run time: the binary runs from any folder, as on a GPU machine where only it travels).
#pragma once
#include <cstdint>
#include <span>
#include <string>

namespace rtbench {

// The SPIR-V words of kernels/<name>.comp; throws rtbench::Error naming the kernels that exist.
std::span<const std::uint32_t> embeddedKernel(const std::string& name);

}  // namespace rtbench
