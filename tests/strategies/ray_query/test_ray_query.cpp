// The driver's ray query (methods/ray_query). Two suites:
// - RayQueryRefusal: on any device. Debian 12's lavapipe (Mesa 22.3) lacks VK_KHR_ray_query, so
//   there the run fails at once saying so; the pairing of the driver's structure with its strategy.
// - RayQueryLavapipe25: on lavapipe 24.1 or later, which has the driver's ray tracing. CTest runs
//   this suite alone under VK_ICD_FILENAMES naming Debian's bookworm-backports lavapipe, unpacked
//   into the build folder by scripts/setup.sh (tests/CMakeLists.txt). It fails, never skips,
//   where that device lacks ray query.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "harness/runner.h"
#include "methods/metrics.h"
#include "structures/driver/driver_structure.h"
#include "strategies/ray_query/ray_query_strategy.h"
#include "scene/camera.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"
#include "tests/methods/hand_scenes.h"
#include "tests/harness/test_experiment.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

ExperimentResult runConfig(TempDir& dir, const std::string& body) { return runTestConfig(dir, "rq", body); }

const char* kSceneB = "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 48\nheight = 36\n";

TEST(RayQueryRefusal, NamesWhatTheDeviceLacks) {
    DeviceInfo device;
    device.name = "llvmpipe (LLVM 15.0.6, 256 bits)";
    device.driver = "llvmpipe Mesa 22.3.6";
    device.rayQueryMissing = "VK_KHR_acceleration_structure, VK_KHR_ray_query";
    EXPECT_THAT(rayQueryRefusal(device), HasSubstr("device lacks VK_KHR_ray_query: llvmpipe"));
    EXPECT_THAT(rayQueryRefusal(device), HasSubstr("has no VK_KHR_acceleration_structure, VK_KHR_ray_query"));
    device.rayQuery = true;
    device.rayQueryMissing.clear();
    EXPECT_EQ(rayQueryRefusal(device), "");
}

// The test device as the runner finds it: without ray query (Debian 12's lavapipe) the run is a
// failed row saying why, before any scene is read; with it, an ok row.
TEST(RayQueryRefusal, ARunOnTheTestDeviceFailsAtOnceWithoutRayQuery) {
    TempDir dir;
    const ExperimentResult result =
        runConfig(dir, std::string(kSceneB) + "[structure]\ntype = \"driver\"\n[strategy]\ntype = \"ray_query\"\n");
    ASSERT_EQ(result.rows.size(), 1u);
    const Row& row = result.rows[0];
    const bool rayQuery = VulkanContext(testDeviceName(), false).info().rayQuery;
    if (!rayQuery) {
        EXPECT_EQ(row.at("status"), "failed");
        EXPECT_THAT(row.at("error"), HasSubstr("device lacks VK_KHR_ray_query"));
        EXPECT_EQ(row.count("scene_triangles") ? row.at("scene_triangles") : "", "");  // refused before the scene
    } else {
        EXPECT_EQ(row.at("status"), "ok") << row.at("error");
    }
}

TEST(RayQueryRefusal, TheDriversStructureAndItsRayQueryGoOnlyTogether) {
    TempDir dir;
    const ExperimentResult result = runConfig(
        dir, std::string(kSceneB) + "[structure]\ntype = [\"driver\", \"uniform_grid\"]\n[strategy]\ntype = [\"branching\", \"ray_query\"]\n");
    ASSERT_EQ(result.rows.size(), 4u);
    int refused = 0, ok = 0;
    for (const Row& row : result.rows) {
        const bool driver = row.at("structure_type") == "driver", rayQuery = row.at("strategy_type") == "ray_query";
        if (driver && !rayQuery) {
            EXPECT_THAT(row.at("error"), HasSubstr("structure.type = driver is traced only by strategy.type = ray_query, not branching"));
            ++refused;
        } else if (!driver && rayQuery) {
            EXPECT_THAT(row.at("error"), HasSubstr("strategy.type = ray_query traces only structure.type = driver, not uniform_grid"));
            ++refused;
        }
        if (driver != rayQuery) {
            EXPECT_EQ(row.at("status"), "failed");
        }
        if (!driver && !rayQuery) ok += row.at("status") == "ok";
    }
    EXPECT_EQ(refused, 2);
    EXPECT_EQ(ok, 1);  // the grid with branching runs as ever
}

// A driver's answer outside its ray's [tMin, tMax), or a miss with a distance, cannot be an answer.
TEST(RayQueryRefusal, ImpossibleHitsAreTheOnesOutsideTheirInterval) {
    const glm::vec3 up(0, 0, 1);
    const std::vector<gpu::Ray> rays = {hand::ray({0, 0, 0}, up, 1.0f, 2.0f), hand::ray({0, 0, 0}, up, 1.0f, 2.0f),
                                        hand::ray({0, 0, 0}, up, 1.0f, 2.0f), hand::ray({0, 0, 0}, up, 1.0f, 2.0f),
                                        hand::ray({0, 0, 0}, up, 1.0f, 2.0f)};
    auto at = [](std::uint32_t primitive, float t) {
        gpu::HitRecord h{};
        h.primitive = primitive;
        h.t = t;
        return h;
    };
    EXPECT_EQ(impossibleHits(rays, {at(0, 1.0f), at(0, 1.5f), at(gpu::kNoHit, gpu::kNoHitT), at(0, 1.5f), at(0, 1.5f)}).rays, 0u);
    const ImpossibleHits found =
        impossibleHits(rays, {at(0, 1.5f), at(0, 2.0f), at(0, std::nextafter(1.0f, 0.0f)), at(gpu::kNoHit, 1.5f), at(0, 1.5f)});
    EXPECT_EQ(found.rays, 3u);  // t = tMax, t below tMin, a miss with a distance
    EXPECT_EQ(found.first, 1u);
}

// ---- on a device with ray query (lavapipe 24.1+ from bookworm-backports in CI) ----

class RayQueryLavapipe25 : public VulkanTest {
protected:
    void SetUp() override {
        ASSERT_TRUE(vk_->info().rayQuery) << vk_->info().name << " (" << vk_->info().driver
                                          << ") lacks the driver's ray tracing: " << vk_->info().rayQueryMissing
                                          << "; this suite runs under VK_ICD_FILENAMES naming lavapipe 24.1 or later";
    }
    static std::unique_ptr<DriverStructure> driverOf(const TriangleMesh& mesh) {
        RunConfig run;
        run.values["baseline.embree_config"] = std::string("");
        auto built = driverStructureType().build(mesh, {}, run, vk_->info());
        std::unique_ptr<DriverStructure> driver(static_cast<DriverStructure*>(built.release()));
        driver->buildOnDevice(*vk_);
        return driver;
    }
    static StrategyRun trace(const DriverStructure& driver, const std::vector<gpu::Ray>& rays, std::uint32_t query) {
        RayBatch batch;
        batch.rays = rays;
        batch.query = query;
        Row row;
        TimingOptions timing;
        timing.warmups = timing.repetitions = 0;
        return batchTracer(rayQueryStrategyType())(*vk_, driver, batch, RunConfig{}, timing, row);
    }
};

// Two parallel triangles across the z axis, at z = 1 (triangle 0) and z = 2 (triangle 1):
// v0 (-1, -1), v1 (3, -1), v2 (-1, 3) in x, y. A ray along +z from (x, y, 0) meets triangle 0 at
// t = 1 (direction length 1) with barycentrics u = (x + 1) / 4 (of v1) and v = (y + 1) / 4 (of v2).
TriangleMesh twoPlanes() {
    return hand::meshOf({{glm::vec3(-1, -1, 1), glm::vec3(3, -1, 1), glm::vec3(-1, 3, 1)},
                         {glm::vec3(-1, -1, 2), glm::vec3(3, -1, 2), glm::vec3(-1, 3, 2)}});
}

TEST_F(RayQueryLavapipe25, HandComputedHitsAndTheIntervalsEnds) {
    const auto driver = driverOf(twoPlanes());
    const glm::vec3 up(0, 0, 1);
    const std::vector<gpu::Ray> rays = {
        hand::ray({0, 0, 0}, up),                    // 0: triangle 0 at t 1, u = v = 1/4
        hand::ray({0.5f, -0.5f, 0}, up),             // 1: triangle 0 at t 1, u = 3/8, v = 1/8
        hand::ray({2.5f, 2.5f, 0}, up),              // 2: outside both (x + y = 5 > 2): a miss
        hand::ray({0, 0, 0}, up, 0.0f, 1.0f),        // 3: tMax 1 ends before t 1: [tMin, tMax) misses
        hand::ray({0, 0, 0}, up, 0.0f, 1.0625f),     // 4: tMax past 1: triangle 0
        hand::ray({0, 0, 0}, up, 1.5f),              // 5: tMin 1.5: triangle 1 at t 2
        hand::ray({0, 0, 3}, -up),                   // 6: from above, backwards: triangle 1 at t 1 (no culling)
        hand::ray({0, 0, 0}, 2.0f * up),             // 7: direction length 2: triangle 0 at t 0.5
        // rtbench's [tMin, tMax) at its ends, where the driver's interval is open (tmin < t < tmax):
        hand::ray({0, 0, 0}, up, 1.0f),                           // 8: tMin 1 includes triangle 0 at t 1
        hand::ray({0, 0, 0}, up, 1.0f, 1.5f),                     // 9: [1, 1.5): triangle 0
        hand::ray({0, 0, 0}, up, 0.0f, std::nextafter(1.0f, 2.0f)),  // 10: the float past 1 ends it: triangle 0
        hand::ray({0, 0, 0}, up, 1.0f, 1.0f),                     // 11: [1, 1) is empty: a miss
    };
    const StrategyRun run = trace(*driver, rays, gpu::kQueryClosest);
    ASSERT_EQ(run.hits.size(), rays.size());
    struct Expect { std::uint32_t primitive; float t, u, v; };
    const Expect expected[] = {{0, 1, 0.25f, 0.25f}, {0, 1, 0.375f, 0.125f}, {gpu::kNoHit, gpu::kNoHitT, 0, 0},
                               {gpu::kNoHit, gpu::kNoHitT, 0, 0}, {0, 1, 0.25f, 0.25f}, {1, 2, 0.25f, 0.25f},
                               {1, 1, 0.25f, 0.25f}, {0, 0.5f, 0.25f, 0.25f}, {0, 1, 0.25f, 0.25f},
                               {0, 1, 0.25f, 0.25f}, {0, 1, 0.25f, 0.25f}, {gpu::kNoHit, gpu::kNoHitT, 0, 0}};
    for (std::size_t i = 0; i < rays.size(); ++i) {
        SCOPED_TRACE("ray " + std::to_string(i));
        EXPECT_EQ(run.hits[i].primitive, expected[i].primitive);
        EXPECT_NEAR(run.hits[i].t, expected[i].t, 1e-6f * expected[i].t);
        EXPECT_NEAR(run.hits[i].u, expected[i].u, 1e-6f);
        EXPECT_NEAR(run.hits[i].v, expected[i].v, 1e-6f);
        EXPECT_EQ(run.hits[i].cellsVisited + run.hits[i].trianglesTested + run.hits[i].traversalSteps, 0u);
    }
    EXPECT_EQ(run.metrics.work.hits, 9u);
    EXPECT_FALSE(run.cpuCompared);
    EXPECT_FALSE(run.metrics.countsKnown);
    EXPECT_EQ(run.timer->time(0, 2).ms.size(), 2u);  // timed repetitions, then their hits against the first run's
    EXPECT_NO_THROW(run.timer->checkHits());
}

// Any hit: whether something lies in [tMin, tMax), not which.
TEST_F(RayQueryLavapipe25, AnyHitAnswersWhetherNotWhich) {
    const auto driver = driverOf(twoPlanes());
    const glm::vec3 up(0, 0, 1);
    const std::vector<gpu::Ray> rays = {hand::ray({0, 0, 0}, up), hand::ray({0, 0, 0}, up, 0.0f, 1.0f),
                                        hand::ray({0, 0, 0}, up, 1.5f), hand::ray({2.5f, 2.5f, 0}, up)};
    const StrategyRun run = trace(*driver, rays, gpu::kQueryAny);
    EXPECT_NE(run.hits[0].primitive, gpu::kNoHit);
    EXPECT_EQ(run.hits[1].primitive, gpu::kNoHit);
    EXPECT_EQ(run.hits[2].primitive, 1u);  // only triangle 1 lies past tMin
    EXPECT_EQ(run.hits[3].primitive, gpu::kNoHit);
}

// The driver against rtbench's exact-division BVH on scene B's camera rays: the same hit or miss
// and the same triangle but for rays that graze an edge, distances within float rounding.
TEST_F(RayQueryLavapipe25, SceneBAgreesWithTheCpuReference) {
    const TriangleMesh mesh = proceduralScene("christen_b");
    const auto driver = driverOf(mesh);
    const std::vector<gpu::Ray> rays = generatePrimaryRays(*proceduralCamera("christen_b", 70.0f), 96, 72);
    const StrategyRun run = trace(*driver, rays, gpu::kQueryClosest);
    const Agreement a = compareHits(run.hits, driver->trace(rays), gpu::kQueryClosest);
    EXPECT_GE(a.hitMissAgreement, 0.999);
    EXPECT_GE(a.samePrimitiveAgreement, 0.999);
    EXPECT_LT(a.relDistanceErrorMax, 1e-5);
    EXPECT_GT(a.bothHit, rays.size() / 4);
    EXPECT_GT(driver->memoryBytes, 0u);
    EXPECT_GE(driver->accelerationStructure().scratchBytes(), 1u);
}

// Through the runner: an ok row judged by the exact reference, counts left empty (not zero), the
// driver's build and memory in the structure's columns; shadow rays (any hit) alike.
TEST_F(RayQueryLavapipe25, WholeRunsOfCameraAndShadowRays) {
    TempDir dir;
    const ExperimentResult result = runConfig(
        dir, std::string(kSceneB) +
                 "[structure]\ntype = \"driver\"\n[strategy]\ntype = \"ray_query\"\n[rays]\ntype = [\"primary\", \"shadow\"]\n"
                 "[light]\nposition = [0.5, 0.9, 0.5]\n");
    ASSERT_EQ(result.rows.size(), 2u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("rays_type"));
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        EXPECT_EQ(row.at("cpu_reference_mismatches"), "");
        EXPECT_EQ(row.at("cpu_counts_match"), "");
        EXPECT_EQ(row.count("triangles_per_ray_mean") ? row.at("triangles_per_ray_mean") : "", "");
        EXPECT_GT(std::stoull(row.at("structure_bytes")), 0u);
        EXPECT_GT(std::stoull(row.at("driver_blas_bytes")), 0u);
        EXPECT_LT(std::stod(row.at("exact_wrong_ppm")), 1000.0);  // the exact reference judges the driver's arithmetic
        EXPECT_GE(std::stod(row.at("hit_miss_agreement")), 0.999);
    }
}

}  // namespace
}  // namespace rtbench
