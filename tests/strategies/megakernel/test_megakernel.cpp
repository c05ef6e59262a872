// The scheduled megakernel (methods/megakernel): its records are the branching caster's for every
// schedule and structure; its state executions and lanes equal the CPU model of the schedule; and
// checks that do not share the model's source: every schedule runs each ray's steps exactly once
// (the lanes that took a step are the rays' triangle tests and traversal steps, whatever the
// schedule), and a subgroup of identical rays runs in full lock step (efficiency 1, the ray's own
// step counts, the same under every schedule).
#include <gtest/gtest.h>

#include "strategies/branching/branching_strategy.h"
#include "structures/bvh/bvh_build.h"
#include "structures/bvh/bvh_structure.h"
#include "structures/uniform_grid/grid_structure.h"
#include "strategies/megakernel/megakernel_layout.h"
#include "strategies/megakernel/megakernel_model.h"
#include "scene/camera.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {

using Megakernel = VulkanTest;

BranchingRun runMegakernel(VulkanContext& vk, const Structure& s, const std::vector<gpu::Ray>& rays, std::uint32_t schedule) {
    TraceLaunch launch;
    launch.kernel = "megakernel";
    launch.constants = {{gpu::kSpecSchedule, schedule}};
    return runBranching(vk, s, rays, {64, 0, 1}, gpu::kQueryClosest, launch);
}

std::vector<std::unique_ptr<Structure>> structuresOf(const TriangleMesh& mesh) {
    GridResolutionRule rule;
    rule.minDim = 8;
    std::vector<std::unique_ptr<Structure>> s;
    s.push_back(gridStructure(buildUniformGrid(mesh, rule)));
    s.push_back(bvhStructure(buildBvh(mesh, BvhBuildOptions{})));
    return s;
}

const std::uint32_t kSchedules[] = {gpu::kScheduleSwitch, gpu::kScheduleIntersectFirst, gpu::kScheduleTraverseFirst,
                                    gpu::kScheduleMajority};

TEST_F(Megakernel, RecordsAreBranchingsAndCountsTheModelsForEverySchedule) {
    const TriangleMesh mesh = christenSceneB();
    const std::vector<gpu::Ray> rays = generatePrimaryRays(*proceduralCamera("christen_b", 70.0f), 40, 27);
    const unsigned sg = vk_->info().subgroupSize;
    for (const auto& s : structuresOf(mesh)) {
        const std::vector<gpu::HitRecord> cpu = s->trace(rays);
        std::uint64_t steps = 0;
        for (const gpu::HitRecord& h : cpu) steps += h.trianglesTested;
        std::uint64_t lanes = 0;
        for (std::uint32_t schedule : kSchedules) {
            SCOPED_TRACE(s->kernelPrefix() + " schedule " + std::to_string(schedule));
            const BranchingRun run = runMegakernel(*vk_, *s, rays, schedule);
            expectIdentical(run.hits, cpu);
            const MegakernelCounts model = megakernelCounts(*s, rays, sg, schedule);
            EXPECT_EQ(run.counters.counts[gpu::kCountRunsTraverse], model.runsTraverse);
            EXPECT_EQ(run.counters.counts[gpu::kCountRunsIntersect], model.runsIntersect);
            EXPECT_EQ(run.activeLanes, model.activeLanes);
            EXPECT_EQ(run.laneSlots, model.laneSlots);
            EXPECT_EQ(run.laneSlots, std::uint64_t(sg) * (model.runsTraverse + model.runsIntersect));
            // Each ray's steps run once whatever the schedule: the same lanes took a step.
            if (lanes == 0) lanes = run.activeLanes;
            EXPECT_EQ(run.activeLanes, lanes);
            EXPECT_GE(run.activeLanes, steps);  // the triangle tests are among them
        }
    }
}

TEST_F(Megakernel, ASubgroupOfOneRayRepeatedRunsInLockStep) {
    const TriangleMesh mesh = christenSceneB();
    const std::vector<gpu::Ray> camera = generatePrimaryRays(*proceduralCamera("christen_b", 70.0f), 16, 16);
    const unsigned sg = vk_->info().subgroupSize;
    for (const auto& s : structuresOf(mesh)) {
        for (std::size_t pick : {std::size_t(0), std::size_t(100), std::size_t(137)}) {
            const std::vector<gpu::Ray> rays(sg, camera[pick]);
            const gpu::HitRecord one = s->trace({camera[pick]})[0];
            std::uint64_t runs = 0;
            for (std::uint32_t schedule : kSchedules) {
                SCOPED_TRACE(s->kernelPrefix() + " ray " + std::to_string(pick) + " schedule " + std::to_string(schedule));
                const BranchingRun run = runMegakernel(*vk_, *s, rays, schedule);
                EXPECT_EQ(run.activeLanes, run.laneSlots);  // every execution has every lane
                EXPECT_EQ(run.counters.counts[gpu::kCountRunsIntersect], one.trianglesTested);
                const std::uint64_t all = run.counters.counts[gpu::kCountRunsTraverse] + run.counters.counts[gpu::kCountRunsIntersect];
                if (runs == 0) runs = all;
                EXPECT_EQ(all, runs);
            }
        }
    }
}

}  // namespace
}  // namespace rtbench
