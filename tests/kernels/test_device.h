// The Vulkan device the kernel tests use: lavapipe unless RTBENCH_TEST_DEVICE names another.
// The validation layer is always on; tests assert it reported nothing.
#pragma once
#include <cstdlib>
#include <string>

inline std::string testDeviceName() {
    const char* name = std::getenv("RTBENCH_TEST_DEVICE");
    return name && *name ? name : "llvmpipe";
}
