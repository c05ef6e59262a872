// The CPU running the same traversal (methods/cpu): its records are the device's, bit for bit, on
// every structure (the GPU's kernels and the C++ compile of their source are different programs);
// through the runner it is judged and timed as the kernels are, on the threads it is given.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "strategies/branching/branching_strategy.h"
#include "strategies/cpu/cpu_strategy.h"
#include "scene/procedural.h"
#include "tests/error_of.h"
#include "tests/harness/test_experiment.h"
#include "tests/methods/hand_scenes.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

using CpuStrategy = VulkanTest;

TEST_F(CpuStrategy, ItsRecordsAreTheDevicesOnEveryStructure) {
    const TriangleMesh mesh = christenSceneB();
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 4000, 29);
    DeviceInfo device;
    device.maxStorageBufferRange = 1u << 27;
    for (const hand::StructureCase& c : {hand::gridCase({20, 20, 20}), hand::bvhCase(4), hand::bruteCase()}) {
        SCOPED_TRACE(c.name);
        const auto structure = c.build(mesh, device);
        for (const std::uint32_t query : {gpu::kQueryClosest, gpu::kQueryAny}) {
            RayBatch batch;
            batch.rays = rays;
            batch.query = query;
            RunConfig config;
            config.values["strategy.threads"] = std::int64_t(2);
            Row row;
            const StrategyRun cpu = batchTracer(cpuStrategyType())(*vk_, *structure, batch, config, {64, 0, 1}, row);
            expectIdentical(runBranching(*vk_, *structure, rays, {64, 0, 0}, query).hits, cpu.hits);
            EXPECT_EQ(row.at("host_threads"), "2");
            EXPECT_FALSE(cpu.cpuCompared);  // its records are the CPU reference's: no check of itself
        }
    }
}

// Through the runner: ok rows with the work counted and the time taken on the host, the threads
// given; strategy.threads is refused where no cpu run reads it.
TEST(CpuStrategyRuns, AreJudgedAndTimedAsTheKernelsAre) {
    TempDir dir;
    const ExperimentResult result = runTestConfig(
        dir, "cpu",
        "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 40\nheight = 30\n"
        "[structure]\ntype = [\"uniform_grid\", \"bvh\"]\nmin_dim = 8\n[strategy]\ntype = \"cpu\"\nthreads = 2\n"
        "[rays]\ntype = [\"primary\", \"shadow\"]\n");
    ASSERT_EQ(result.rows.size(), 4u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(cellText(row, "label"));
        EXPECT_EQ(cellText(row, "status"), "ok") << cellText(row, "error");
        EXPECT_EQ(cellText(row, "host_threads"), "2");
        EXPECT_EQ(cellText(row, "cpu_reference_mismatches"), "");
        EXPECT_NE(cellText(row, "work_per_ray_mean"), "");
        EXPECT_EQ(cellText(row, "simd_lane_utilisation"), "");
        EXPECT_GT(std::stod(cellText(row, "kernel_ms_median")), 0.0);
        EXPECT_EQ(cellText(row, "exact_wrong_ppm"), "0");
    }
    EXPECT_THAT(errorOf([&] {
                    runTestConfig(dir, "threads", "[scene]\nsource = \"procedural:christen_a\"\n[strategy]\ntype = \"branching\"\nthreads = 2\n");
                }),
                HasSubstr("strategy.threads"));
}

// More threads than TBB runs at once: host_threads records what traced the rays, and the row says so.
TEST(CpuStrategyRuns, HostThreadsRecordsTheThreadsThatRan) {
    TempDir dir;
    const ExperimentResult result = runTestConfig(
        dir, "many", "[scene]\nsource = \"procedural:christen_a\"\n[camera]\nwidth = 8\nheight = 8\n"
                     "[strategy]\ntype = \"cpu\"\nthreads = 1000\n[output]\nimages = false\n");
    ASSERT_EQ(result.rows.size(), 1u);
    const Row& row = result.rows[0];
    EXPECT_EQ(cellText(row, "status"), "ok") << cellText(row, "error");
    const int limit = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    ASSERT_LT(limit, 1000) << "this machine runs 1000 threads at once: the case does not arise";
    EXPECT_EQ(cellText(row, "host_threads"), std::to_string(limit));
    EXPECT_THAT(cellText(row, "warnings"), HasSubstr("strategy.threads 1000: TBB runs at most " + std::to_string(limit)));
}

}  // namespace
}  // namespace rtbench
