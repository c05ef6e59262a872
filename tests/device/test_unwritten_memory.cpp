// Memory nothing wrote: a validated context poisons new storage buffers, so a kernel or a check
// that reads such memory fails the same way every time instead of now and then (the path
// megakernel's check read the records of paths that end early, unwritten: a NaN hit distance in
// one fresh-clone run of four, until GpuBuffers zeroed the records).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "device/gpu_buffers.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"

namespace rtbench {
namespace {

using UnwrittenMemory = VulkanTest;  // validated: poisoning

TEST_F(UnwrittenMemory, AValidatedContextPoisonsEveryWordOfANewStorageBuffer) {
    Buffer b = vk_->createStorageBuffer(4096, "poison test");
    std::vector<std::uint32_t> words(1024, 0u);
    vk_->download(b, words.data(), 4096);
    vk_->destroy(b);
    for (std::size_t i = 0; i < words.size(); ++i) ASSERT_EQ(words[i], VulkanContext::kPoisonWord) << i;
    float f;
    std::memcpy(&f, &words[0], 4);
    EXPECT_TRUE(std::isnan(f));  // what a hit distance read from it is
}

// A run's buffers hold what it uploaded, or zeros: the records before any kernel wrote them (the
// checks compare every record), the strategy's buffers, the rays.
TEST_F(UnwrittenMemory, ARunsBuffersStartAsTheirUploadOrZeros) {
    std::vector<gpu::Ray> rays;
    for (int i = 0; i < 100; ++i)
        rays.push_back(gpu::Ray{glm::vec4(float(i), 0.5f, -10.0f, 0.0f), glm::vec4(0, 0, 1, gpu::kNoHitT)});
    GridResolutionRule rule;
    rule.minDim = 4;
    const std::unique_ptr<Structure> structure = gridStructure(buildUniformGrid(christenSceneA(), rule));
    GpuBuffers buffers(*vk_, rays, structure->buffers(), structure->params(), {{"a strategy's buffer", 256}});
    const std::vector<gpu::HitRecord> hits = buffers.downloadHits();
    ASSERT_EQ(hits.size(), rays.size());
    const gpu::HitRecord zero{};
    for (std::size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(std::memcmp(&hits[i], &zero, sizeof zero), 0) << "record " << i;
    const std::vector<gpu::Ray> back = buffers.downloadRays();
    ASSERT_EQ(std::memcmp(back.data(), rays.data(), rays.size() * sizeof(gpu::Ray)), 0);
    for (std::uint8_t byte : buffers.downloadStrategyBuffer(0)) ASSERT_EQ(byte, 0);
}

}  // namespace
}  // namespace rtbench
