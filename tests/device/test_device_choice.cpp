// Which device a run gets (device.name, -d): a substring of the device's name or of its driver. Two
// lavapipes (Debian's Mesa 22 and the backports' Mesa 25, VK_ADD_DRIVER_FILES) share a name, so
// only the driver tells them apart.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "device/vulkan_context.h"
#include "tests/error_of.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

// The driver's "Mesa X.Y.Z" (or the driver text whole): a text of the driver the name lacks.
std::string driverOnlyText(const DeviceInfo& device) {
    const std::size_t mesa = device.driver.find("Mesa ");
    if (mesa == std::string::npos) return device.driver;
    return device.driver.substr(mesa, device.driver.find(' ', mesa + 5) - mesa);
}

TEST(DeviceChoice, ASubstringOfTheDriverPicksItsDevice) {
    const std::vector<DeviceInfo> devices = VulkanContext::listDevices();
    ASSERT_FALSE(devices.empty());
    const std::string text = driverOnlyText(devices.front());
    ASSERT_EQ(devices.front().name.find(text), std::string::npos) << devices.front().name << " holds " << text;
    VulkanContext vk(text, false);
    EXPECT_EQ(vk.info().driver, devices.front().driver);
}

TEST(DeviceChoice, NoMatchNamesEveryDeviceWithItsDriver) {
    const std::string error = errorOf([] { VulkanContext vk("no such device 1f3a", false); });
    EXPECT_THAT(error, HasSubstr("no device matches 'no such device 1f3a'"));
    EXPECT_THAT(error, HasSubstr(VulkanContext::listDevices().front().driver));
}

}  // namespace
}  // namespace rtbench
