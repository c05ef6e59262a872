// The Vulkan device the kernel tests use: lavapipe unless RTBENCH_TEST_DEVICE names another.
// The validation layer is always on; every test asserts it reported nothing.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "device/vulkan_context.h"

inline std::string testDeviceName() {
    const char* name = std::getenv("RTBENCH_TEST_DEVICE");
    return name && *name ? name : "llvmpipe";
}

namespace rtbench {

// One validated context per test suite.
class VulkanTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { vk_ = std::make_unique<VulkanContext>(testDeviceName(), /*validation=*/true); }
    static void TearDownTestSuite() { vk_.reset(); }
    void TearDown() override {
        EXPECT_TRUE(vk_->validationMessages().empty()) << vk_->validationMessages().front();
    }
    static inline std::unique_ptr<VulkanContext> vk_;
};

}  // namespace rtbench
