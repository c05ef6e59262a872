// llvmpipe ends a kernel invocation after 65,535 loop iterations of all its loops together (Mesa's
// LP_MAX_TGSI_LOOP_ITERATIONS), per subgroup, silently: the rays of a subgroup that needs more come
// back unfinished. This was the cause of the CPU-reference mismatches on dense sliver scenes.
// The branching strategy must fail such a run naming the limit, and pass one just under it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "strategies/branching/branching_strategy.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "strategies/multipass/multipass_strategy.h"
#include "tests/device/test_device.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

// `count` small triangles stacked along z in one voxel (a 1x1x1 grid), each beside the rays' path
// but the last, so every ray tests all of them: one outer iteration, `count` triangle iterations.
TriangleMesh stack(unsigned count) {
    TriangleMesh mesh;
    for (unsigned i = 0; i < count; ++i) {
        const float z = -float(i) * 1e-3f;
        const float x = i + 1 == count ? 0.0f : 2.0f;  // all but the last lie beside the rays
        const unsigned base = unsigned(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), {{x - 1, -1, z}, {x + 1, -1, z}, {x, 1, z}});
        mesh.triangles.emplace_back(base, base + 1, base + 2);
    }
    return mesh;
}

// One subgroup's worth of rays straight down -z through the stack.
std::vector<gpu::Ray> raysDown(unsigned n) {
    std::vector<gpu::Ray> rays;
    for (unsigned i = 0; i < n; ++i)
        rays.push_back({glm::vec4(0.01f * i, 0.0f, 1.0f, 0.0f), glm::vec4(0, 0, -1, gpu::kNoHitT)});
    return rays;
}

using LoopLimit = VulkanTest;

TEST_F(LoopLimit, ARunPastTheDevicesLoopLimitFailsNamingItAndOneUnderItPasses) {
    if (vk_->info().loopIterationLimit == 0) GTEST_SKIP() << vk_->info().name << " has no known loop limit";
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = {1, 1, 1};
    const std::vector<gpu::Ray> rays = raysDown(vk_->info().subgroupSize);
    RunConfig config;
    Row row;
    {
        const std::unique_ptr<Structure> grid = gridStructure(buildUniformGrid(stack(60000), rule));
        const StrategyRun run = batchTracer(branchingStrategyType())(*vk_, *grid, RayBatch{rays}, config, {64, 0, 1}, row);
        EXPECT_EQ(run.truncatedRays, 0u);
        EXPECT_EQ(run.cpuMismatches, 0u);  // 60,001 iterations: the device finishes every ray
        EXPECT_EQ(row.at("rays_cut_short"), "0");
        for (const gpu::HitRecord& h : run.hits) EXPECT_EQ(h.primitive, 59999u);
    }
    {
        const std::unique_ptr<Structure> grid = gridStructure(buildUniformGrid(stack(70000), rule));
        const StrategyRun run = batchTracer(branchingStrategyType())(*vk_, *grid, RayBatch{rays}, config, {64, 0, 1}, row);
        EXPECT_EQ(run.truncatedRays, rays.size());
        EXPECT_GT(run.cpuMismatches, 0u);  // the device really did cut them short
        EXPECT_THAT(run.truncatedWhy, HasSubstr("needs 70001 loop iterations"));
        EXPECT_THAT(run.truncatedWhy, HasSubstr("ends a kernel invocation after 65535"));
        // Multipass runs a few iterations per pass and gets every ray right.
        MultipassOptions o;
        o.intersectionsPerPass = 64;
        const MultipassRun multipass = runMultipass(*vk_, *grid, rays, o, {64, 0, 1});
        for (const gpu::HitRecord& h : multipass.hits) EXPECT_EQ(h.primitive, 69999u);
    }
}

}  // namespace
}  // namespace rtbench
