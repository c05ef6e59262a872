

// Persistent threads (methods/persistent): every ray traced exactly once whatever the grid of
// workgroups and the batch size, its record equal to the CPU reference's; the fetch counter ends
// where persistentCounts says; the subgroup ballots equal the branching lane model's.
// llvmpipe ends an invocation after 65,535 loop iterations, all loops together, and runs a
// workgroup's subgroups one after another, so an unbounded subgroup can take most of the stream and
// be cut short: there the runner bounds each subgroup's fetches (persistentMaxFetches; the kernel
// tests below run unbounded on rays few enough for any subgroup).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "strategies/branching/branching_strategy.h"
#include "strategies/branching/lane_counts.h"
#include "structures/uniform_grid/grid_reference.h"
#include "structures/uniform_grid/grid_structure.h"
#include "methods/metrics.h"
#include "strategies/persistent/persistent_layout.h"
#include "strategies/persistent/persistent_strategy.h"
#include "core/error.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/methods/test_rays.h"
#include "tests/temp_dir.h"
#include "harness/config.h"
#include "harness/runner.h"

namespace rtbench {
namespace {

using PersistentKernel = VulkanTest;

BranchingRun runPersistent(VulkanContext& vk, const Structure& s, const std::vector<gpu::Ray>& rays,
                           const PersistentOptions& o, unsigned workgroupSize = 64) {
    const PersistentCounts c = persistentCounts(o, rays.size(), workgroupSize, vk.info().subgroupSize);
    TraceLaunch launch;
    launch.kernel = "persistent";
    launch.invocations = std::uint64_t(o.workgroups) * workgroupSize;
    launch.constants = {{gpu::kSpecRaysPerFetch, std::uint32_t(c.raysPerFetch)}};
    launch.countersWhenTimed = true;
    return runBranching(vk, s, rays, {workgroupSize, 0, 0}, gpu::kQueryClosest, launch);
}

TEST_F(PersistentKernel, TracesEveryRayOnceForAnyGridAndBatch) {
    const TriangleMesh mesh = christenSceneB();
    GridResolutionRule rule;
    rule.minDim = 16;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const auto s = gridStructure(grid);
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 1001, 16);  // not a multiple of any batch
    const std::vector<gpu::HitRecord> cpu = traceGridReference(grid, rays);
    const LaneCounts lanes = branchingLaneCounts(*s, rays, vk_->info().subgroupSize);
    const std::uint32_t sg = vk_->info().subgroupSize;
    for (const PersistentOptions o : {PersistentOptions{1, 0}, PersistentOptions{3, 4 * sg}, PersistentOptions{64, sg},
                                      PersistentOptions{4096, 2 * sg}}) {
        SCOPED_TRACE("workgroups " + std::to_string(o.workgroups) + ", rays per fetch " + std::to_string(o.raysPerFetch));
        const BranchingRun run = runPersistent(*vk_, *s, rays, o);
        expectIdentical(run.hits, cpu);
        EXPECT_EQ(run.counters.counts[gpu::kCountRaysTraced], rays.size());
        EXPECT_EQ(run.counters.counts[gpu::kCountRaysFetched],
                  persistentCounts(o, rays.size(), 64, sg).fetchedWhenDone);
        if (vk_->info().lockStepSubgroups) {
            EXPECT_EQ(run.activeLanes, lanes.activeLanes);
            EXPECT_EQ(run.laneSlots, lanes.laneSlots);
        }
    }
}

// The bound at its worst: one ray repeated, so every batch walks as long as the longest and a
// subgroup at its bound runs next to llvmpipe's limit. One workgroup, whose first subgroup takes
// its bound's worth of batches before the next starts: bounded, every record comes back whole (an
// iteration a fetch the bound forgot would cut the last batches short); unbounded, that subgroup
// takes all eight subgroups' batches, several times the limit, and records come back cut.
TEST_F(PersistentKernel, TheFetchBoundHoldsWhenEveryBatchWalksTheLongest) {
    if (vk_->info().loopIterationLimit == 0) GTEST_SKIP() << "this device has no loop limit to bound under";
    const TriangleMesh mesh = christenSceneB();
    GridResolutionRule rule;
    rule.minDim = 16;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const auto s = gridStructure(grid);
    const std::vector<gpu::Ray> candidates = randomRays(mesh.bounds(), 1001, 16);
    const std::vector<gpu::HitRecord> walks = traceGridReference(grid, candidates);
    std::size_t longest = 0;
    for (std::size_t i = 0; i < walks.size(); ++i)
        if (walks[i].cellsVisited + walks[i].trianglesTested > walks[longest].cellsVisited + walks[longest].trianglesTested)
            longest = i;
    const unsigned sg = vk_->info().subgroupSize;
    const std::vector<gpu::Ray> one(sg, candidates[longest]);
    const std::uint64_t walk = branchingLaneCounts(*s, one, sg).maxSubgroupIterations;
    const std::uint64_t maxFetches = persistentMaxFetches(loopIterationBudget(vk_->info()), walk, 1);
    ASSERT_GT(maxFetches, 1u);
    const std::vector<gpu::Ray> rays((64 / sg) * maxFetches * sg, candidates[longest]);  // every subgroup's bound
    const std::vector<gpu::HitRecord> cpu = traceGridReference(grid, rays);
    for (const std::uint64_t bound : {maxFetches, std::uint64_t(0)}) {
        SCOPED_TRACE("bound " + std::to_string(bound) + ", walks of " + std::to_string(walk) + " loop trips");
        TraceLaunch launch;
        launch.kernel = "persistent";
        launch.invocations = 64;
        launch.constants = {{gpu::kSpecRaysPerFetch, sg}, {gpu::kSpecMaxFetches, std::uint32_t(bound)}};
        launch.countersWhenTimed = true;
        const BranchingRun run = runBranching(*vk_, *s, rays, {64, 0, 0}, gpu::kQueryClosest, launch);
        if (bound) {
            expectIdentical(run.hits, cpu);
            EXPECT_EQ(run.counters.counts[gpu::kCountRaysFetched], rays.size());  // every subgroup at its bound
        } else {
            EXPECT_GT(recordMismatches(run.hits, cpu), 0u);
        }
    }
}

}  // namespace
}  // namespace rtbench

namespace rtbench {
namespace {

// The fetch counter's end by hand: 20,011 rays in batches of 16 are 1,251 batches (20,016 rays
// handed out); 4,096 workgroups of 64 are 32,768 subgroups of 8, each making one fetch of 16 more
// that finds none: 20,016 + 524,288.
TEST(PersistentCounts, TheFetchCounterEndsWhereEverySubgroupFoundNone) {
    EXPECT_EQ(persistentCounts({4096, 16}, 20011, 64, 8).handedOut, 20016u);
    EXPECT_EQ(persistentCounts({4096, 16}, 20011, 64, 8).fetchedWhenDone, 544304u);
    EXPECT_EQ(persistentCounts({1, 0}, 20011, 64, 8).raysPerFetch, 8u);
    EXPECT_EQ(persistentCounts({1, 0}, 20011, 64, 8).fetchedWhenDone, 20016u + 64u);
    EXPECT_THROW(persistentCounts({1, 12}, 100, 64, 8), Error);
    EXPECT_THROW(persistentCounts({1, 0}, 100, 4, 8), Error) << "a workgroup of 4 holds no subgroup of 8";
}

// More workgroups than one grid row holds (65,535 on llvmpipe): the 2-D grid pads a few more, which
// fetch nothing, so the fetch counter still ends in its range (65,537 was a failed row).
TEST(PersistentRuns, MoreWorkgroupsThanAGridRowHoldsTraceEveryRayOnce) {
    TempDir dir;
    const std::string path = dir.write("w.toml", "[experiment]\nname = \"w\"\noutput = \"" + dir.file("out") +
                                                     "\"\nrepetitions = 1\nwarmups = 0\n[device]\nname = \"" + testDeviceName() +
                                                     "\"\n[scene]\nsource = \"procedural:christen_a\"\n[camera]\nwidth = 16\n"
                                                     "height = 16\n[strategy]\ntype = \"persistent\"\nworkgroup_size = 8\n"
                                                     "persistent_workgroups = [65535, 65537, 100003]\n[output]\nimages = false\n");
    RunnerOptions quiet;
    quiet.quiet = true;
    const ExperimentResult result = runExperiment(loadExperiment(path), quiet);
    ASSERT_EQ(result.rows.size(), 3u);
    for (const Row& row : result.rows) {
        EXPECT_EQ(row.at("status"), "ok") << row.at("label") << ": " << row.at("error");
        EXPECT_EQ(row.at("rays_traced"), row.at("rays")) << row.at("label");
    }
}

// A workgroup smaller than a subgroup (legal config values 1-7 on llvmpipe's subgroups of 8) is a
// failed row naming the key, not a division by zero (SIGFPE) that kills the sweep and its resume.
TEST(PersistentRuns, AWorkgroupBelowTheSubgroupSizeIsAFailedRowNamingTheKey) {
    TempDir dir;
    const std::string path = dir.write("p.toml", "[experiment]\nname = \"p\"\noutput = \"" + dir.file("out") +
                                                     "\"\nrepetitions = 1\nwarmups = 0\n[device]\nname = \"" + testDeviceName() +
                                                     "\"\n[scene]\nsource = \"procedural:christen_a\"\n[camera]\nwidth = 8\n"
                                                     "height = 8\n[strategy]\ntype = \"persistent\"\nworkgroup_size = [1, 4, 7]\n"
                                                     "[output]\nimages = false\n");
    RunnerOptions quiet;
    quiet.quiet = true;
    const ExperimentResult result = runExperiment(loadExperiment(path), quiet);
    ASSERT_EQ(result.rows.size(), 3u);
    for (const Row& row : result.rows) {
        EXPECT_EQ(row.at("status"), "failed");
        EXPECT_THAT(row.at("error"), ::testing::HasSubstr("is not a multiple of the subgroup size")) << row.at("error");
    }
}

// The fetch bound by hand: llvmpipe's budget of 65,535 - 64 iterations over fetches of one round
// whose walks take at most 142 trips: 2 x 142 + 4 = 288 for the round, 2 for the round and fetch
// loops, 290 a fetch, and one more for the last fetch that finds none: (65,471 - 1) / 290 = 225.
// Two rounds: 578 a fetch, 113. A budget of exactly 225 fetches of 290 leaves none for the last
// fetch: 224. No budget, no bound; walks too long for one fetch still get one.
TEST(PersistentCounts, TheFetchBoundKeepsASubgroupUnderTheLoopLimit) {
    EXPECT_EQ(persistentMaxFetches(65471, 142, 1), 225u);
    EXPECT_EQ(persistentMaxFetches(65471, 142, 2), 113u);
    EXPECT_EQ(persistentMaxFetches(225 * 290, 142, 1), 224u);
    EXPECT_EQ(persistentMaxFetches(0, 142, 1), 0u);
    EXPECT_EQ(persistentMaxFetches(65471, 70000, 1), 1u);
    EXPECT_EQ(persistentMaxFetches(65471, 32732, 1), 1u);  // 65,470 a fetch: one, and the last
}

}  // namespace
}  // namespace rtbench

namespace rtbench {
namespace {

// Scene B's own camera at 128 x 128, grid min_dim 16, on 1, 16 and 256 workgroups: unbounded, on
// Mesa 22.3.6's llvmpipe 24, 32 and 15 of the 16,384 records came back as misses, whole subgroups
// stopped at one step (a subgroup's walks over most of the stream passed the loop limit). With the
// bound (one workgroup's 8 subgroups can no longer take all 2,048 batches there: EndToEnd
// covers that refusal), on 2, 16 and 256 workgroups every check of the runner holds on Debian 12's
// lavapipe (PersistentThreads) and on
// lavapipe 25 (PersistentLavapipe25, the *Lavapipe25 suites of tests/CMakeLists.txt): records equal
// to the CPU reference's, records written, the fetch counter's end, timed = counted.
void expectSceneBsCameraRaysRightOnEveryWorkgroupGrid() {
    TempDir dir;
    const std::string path = dir.write(
        "p.toml", "[experiment]\nname = \"p\"\noutput = \"" + dir.file("out") + "\"\nrepetitions = 1\nwarmups = 0\n"
                  "[device]\nname = \"" + testDeviceName() + "\"\nvalidation = true\n[scene]\nsource = \"procedural:christen_b\"\n"
                  "[camera]\nwidth = 128\nheight = 128\n[structure]\nmin_dim = 16\n[strategy]\ntype = \"persistent\"\n"
                  "persistent_workgroups = [2, 16, 256]\n[output]\nimages = false\n");
    RunnerOptions options;
    options.quiet = true;
    const ExperimentResult result = runExperiment(loadExperiment(path), options);
    ASSERT_EQ(result.rows.size(), 3u);
    for (const Row& row : result.rows) {
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        EXPECT_EQ(row.at("rays_traced"), "16384");
        EXPECT_EQ(row.at("cpu_reference_mismatches"), "0");
        if (testDeviceName() == "llvmpipe") {
            EXPECT_NE(row.at("persistent_max_fetches"), "0");
        }
    }
}

using PersistentThreads = VulkanTest;
using PersistentLavapipe25 = VulkanTest;

TEST_F(PersistentThreads, TraceSceneBsCameraRaysRightOnEveryWorkgroupGrid) {
    expectSceneBsCameraRaysRightOnEveryWorkgroupGrid();
}

TEST_F(PersistentLavapipe25, TracesSceneBsCameraRaysRightOnEveryWorkgroupGrid) {
    ASSERT_EQ(vk_->info().driver.find("Mesa 22."), std::string::npos) << vk_->info().driver;
    expectSceneBsCameraRaysRightOnEveryWorkgroupGrid();
}

}  // namespace
}  // namespace rtbench
