// The strategies that trace a whole path on the device (strategies/whole_path.h): the wavefront, stage
// by stage over queues, and the path megakernel, in one kernel. Capacities by hand; the parallel
// mirrors' hand-computed iterations and a diffuse path of two rays per hit on every structure;
// their checks catching a path that is not the device's; whole runs of every ray type they trace
// against branching's rows and Embree; and what they refuse.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <variant>

#include "strategies/branching/branching_strategy.h"
#include "strategies/path_megakernel/path_megakernel_strategy.h"
#include "strategies/wavefront/wavefront_strategy.h"
#include "strategies/whole_path.h"
#include "core/error.h"
#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/methods/hand_scenes.h"
#include "tests/methods/test_rays.h"
#include "tests/rays/workload_runs.h"
#include "rays/path/path_rays.h"
#include "rays/reflection/reflection_rays.h"
#include "rays/shading.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;
using ::testing::HasSubstr;

TEST(WholePathCapacity, TheQueueHoldsTheLargestGenerationAndTheSlotsTheLargestPass) {
    // 100 camera rays, 4 per hit, then 1 each: at most 400 rays in a generation, 400 slots.
    WholePathCapacity c = wholePathCapacity(100, {4, 1, 1});
    EXPECT_EQ(c.queue, 400u);
    EXPECT_EQ(c.slots, 400u);
    // Camera rays alone: no pass, no slot.
    c = wholePathCapacity(100, {});
    EXPECT_EQ(c.queue, 100u);
    EXPECT_EQ(c.slots, 0u);
    // 3 then 2 per hit: 300, then 600.
    c = wholePathCapacity(100, {3, 2});
    EXPECT_EQ(c.queue, 600u);
    EXPECT_EQ(c.slots, 600u);
    EXPECT_THAT(errorOf([] { wholePathCapacity(1u << 20, {1u << 12, 2}); }), HasSubstr("32-bit ray indices"));
}

// The two levels of the seam are types: the whole-path strategies are TracePath, and a caller that
// hands rays alone (batchTracer) is refused by name; a batch strategy is TraceBatch.
TEST(WholePathStrategies, TraceWholePathsNotABatchAlone) {
    for (const StrategyType* strategy : {&wavefrontStrategyType(), &pathMegakernelStrategyType()}) {
        EXPECT_TRUE(std::holds_alternative<StrategyType::TracePath>(strategy->trace)) << strategy->name;
        EXPECT_THAT(errorOf([&] { batchTracer(*strategy); }),
                    HasSubstr("strategy.type = " + strategy->name + " traces whole paths, not a batch of rays alone"));
    }
    EXPECT_TRUE(std::holds_alternative<StrategyType::TraceBatch>(branchingStrategyType().trace));
    EXPECT_NO_THROW(batchTracer(branchingStrategyType()));
}

using WavefrontKernels = VulkanTest;

// A whole-path strategy's instrumented run of `w`, with the path as the runner hands it (the
// TracePath level of the seam), kept as long as the run: its timer reads it. KeptPath is the
// first base, so the path outlives the timer.
struct KeptPath {
    std::unique_ptr<const BatchPath> path;
};
struct WholePathRun : KeptPath, StrategyRun {};
WholePathRun runWholePath(const StrategyType& strategy, VulkanContext& vk, const Structure& s, Workload& w,
                          const std::vector<gpu::Ray>& camera, const TriangleMesh& mesh, Row& row, unsigned workgroupSize = 64) {
    WholePathRun r;
    r.path = std::make_unique<const BatchPath>(batchPath(w, camera, mesh));
    static_cast<StrategyRun&>(r) =
        std::get<StrategyType::TracePath>(strategy.trace)(vk, s, w.batch, *r.path, RunConfig{}, {workgroupSize, 0, 0}, row);
    return r;
}

const std::vector<const StrategyType*> wholePathStrategies = {&wavefrontStrategyType(), &pathMegakernelStrategyType()};

// Camera ray 0 meets the floor at (2, 0, 0), its reflection the ceiling near x = 6, and iteration 2
// goes down past the floor's edge: a miss. Camera ray 1 goes straight up and bounces between the
// mirrors for ever. Camera ray 2 misses. Iteration 2 is traced from the camera rays on the device
// through three queues (3 rays, 2, 2) and must end at the hand's records: a miss, then the ceiling.
TEST_F(WavefrontKernels, TwoParallelMirrorsEndAtTheHandComputedIterationOnEveryStructure) {
    const TriangleMesh mesh = parallelMirrors();
    const std::vector<gpu::Ray> camera = {ray({0, 2, 0}, {1, -1, 0}), ray({-1, 1, -1}, {0, 1, 0}), ray({0, 2, 0}, {1, 0, 0})};
    for (const StructureCase& c : {bruteCase(), gridCase({2, 2, 2}), bvhCase(1)}) {
        SCOPED_TRACE(c.name);
        const std::unique_ptr<Structure> s = c.build(mesh, vk_->info());
        for (std::int64_t iteration : {1, 2, 4}) {
          for (const StrategyType* strategy : wholePathStrategies) {
            SCOPED_TRACE(strategy->name + " iteration " + std::to_string(iteration));
            RunConfig run;
            run.values["reflection.iteration"] = iteration;
            const WorkloadInputs inputs{run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }};
            Row row;
            Workload w = reflectionRayType().make(inputs, row);
            const WholePathRun r = runWholePath(*strategy, *vk_, *s, w, camera, mesh, row);
            EXPECT_EQ(r.countsMismatch, "");
            EXPECT_EQ(r.cpuMismatches, 0u);
            EXPECT_EQ(r.truncatedRays, 0u);
            EXPECT_TRUE(r.countsCompared);  // llvmpipe: the lane model's counts equal the ballots' (else countsMismatch)
            expectIdentical(r.hits, s->trace(w.batch.rays));
            EXPECT_EQ(row.at("whole_path_generations"), std::to_string(iteration + 1));
            if (iteration == 2) {
                ASSERT_EQ(r.hits.size(), 2u);
                EXPECT_EQ(r.hits[0].primitive, kNoHit);  // past the floor's edge
                EXPECT_GE(r.hits[1].primitive, 2u);      // the ceiling again
                EXPECT_EQ(row.at("whole_path_rays"), "7");  // 3 camera rays, 2 of iteration 1, 2 of iteration 2
            }
            if (iteration == 4) {
                ASSERT_EQ(r.hits.size(), 1u);  // only camera ray 1's path is still between the mirrors
                EXPECT_GE(r.hits[0].primitive, 2u);
                EXPECT_EQ(row.at("whole_path_rays"), "9");  // 3 + 2 + 2 + 1 + 1
            }
            // The timer's repetition ends where the instrumented run did.
            const TimedBatch timed = r.timer->time(1, 2);
            EXPECT_EQ(timed.ms.size(), 2u);
            EXPECT_EQ(timed.parts.size(), strategy == wholePathStrategies[0] ? 3u : 0u);
            EXPECT_NO_THROW(r.timer->checkHits());
          }
        }
    }
}

// Diffuse path tracing inside a closed box, two paths per camera hit then one ray each: every
// generation the device makes is the CPU's ray for ray (the stable compaction keeps the CPU's
// order), and the batch's records are the structure's. Workgroups of one subgroup: the wavefront's
// scan then runs over 300 / 8 = 38 workgroups' counts in chunks of one workgroup (a carry between
// chunks), and its compaction's workgroups each start where the scan says.
TEST_F(WavefrontKernels, ADiffusePathOfTwoRaysPerHitInsideABoxIsTheCpusGenerationByGeneration) {
    // The cube [-1, 1]^3 from inside: 12 triangles, every diffuse ray hits another face.
    std::vector<std::array<glm::vec3, 3>> faces;
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            auto corner = [&](float a, float b) {
                glm::vec3 p(0.0f);
                p[axis] = side;
                p[(axis + 1) % 3] = a;
                p[(axis + 2) % 3] = b;
                return p;
            };
            faces.push_back({corner(-1, -1), corner(1, -1), corner(1, 1)});
            faces.push_back({corner(-1, -1), corner(1, 1), corner(-1, 1)});
        }
    const TriangleMesh mesh = meshOf(faces);
    std::vector<gpu::Ray> camera;
    for (int i = 0; i < 150; ++i)
        camera.push_back(ray({0.1f * float(i % 7) - 0.3f, 0.05f * float(i % 5), 0.0f}, {std::cos(0.3f * float(i)), 0.4f, std::sin(0.3f * float(i))}));
    for (const StructureCase& c : {bruteCase(), gridCase({3, 3, 3}), bvhCase(2)}) {
      for (const StrategyType* strategy : wholePathStrategies) {
        SCOPED_TRACE(c.name + " " + strategy->name);
        const std::unique_ptr<Structure> s = c.build(mesh, vk_->info());
        RunConfig run;
        run.values["path.bounce"] = std::int64_t(3);
        run.values["path.samples"] = std::int64_t(2);
        run.values["path.seed"] = std::int64_t(7);
        const WorkloadInputs inputs{run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }};
        Row row;
        Workload w = pathRayType().make(inputs, row);
        ASSERT_EQ(w.batch.rays.size(), 300u);  // every ray hits a face: 150 x 2, then one each
        const WholePathRun r = runWholePath(*strategy, *vk_, *s, w, camera, mesh, row, vk_->info().subgroupSize);
        EXPECT_EQ(r.countsMismatch, "");
        EXPECT_EQ(r.cpuMismatches, 0u);
        expectIdentical(r.hits, s->trace(w.batch.rays));
        EXPECT_EQ(row.at("whole_path_rays"), "1050");  // 150 + 300 + 300 + 300
        if (strategy == wholePathStrategies[0]) {
            EXPECT_EQ(row.at("wavefront_queue_capacity"), "300");
        } else {
            EXPECT_EQ(row.at("path_megakernel_rays_traced"), "1050");
        }
      }
    }
}

// The parallel mirrors' reflection iteration 2 on brute force, made afresh for each tampering.
struct MirrorsIteration2 {
    TriangleMesh mesh = parallelMirrors();
    std::vector<gpu::Ray> camera = {ray({0, 2, 0}, {1, -1, 0}), ray({-1, 1, -1}, {0, 1, 0}), ray({0, 2, 0}, {1, 0, 0})};
    std::unique_ptr<Structure> s;
    RunConfig run;
    explicit MirrorsIteration2(const DeviceInfo& device) : s(bruteOf(mesh, device)) {
        run.values["reflection.iteration"] = std::int64_t(2);
    }
    Workload make(Row& row) {
        return reflectionRayType().make({run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }}, row);
    }
};

// The generation check can disagree: a path whose generation 1 the CPU made otherwise than the
// device (its rays swapped, a parent changed, a weight changed) fails the run naming generation 1,
// and the batch's records are judged all the same.
TEST_F(WavefrontKernels, AGenerationThatIsNotTheDevicesIsNamed) {
    MirrorsIteration2 m(vk_->info());
    for (int tamper = 0; tamper < 3; ++tamper) {
        SCOPED_TRACE(tamper);
        Row row;
        Workload w = m.make(row);
        ASSERT_EQ(w.between.size(), 1u);
        Generation& g = w.between[0];
        if (tamper == 0) std::swap(g.rays[0], g.rays[1]);
        if (tamper == 1) g.parents[1] = 2;
        if (tamper == 2) g.weights[0] = 0.5f;
        const WholePathRun r = runWholePath(wavefrontStrategyType(), *vk_, *m.s, w, m.camera, m.mesh, row);
        EXPECT_THAT(r.countsMismatch, HasSubstr(tamper == 0 ? "generation 1 (2 of 2 rays" : "generation 1 (1 of 2 rays"));
        EXPECT_THAT(r.countsMismatch, HasSubstr(tamper == 0 ? "ray 0's ray" : tamper == 1 ? "ray 1's parent" : "ray 0's weight"));
    }
}

// The megakernel keeps no generation but the batch: a batch that is not the device's (a ray
// changed, a weight changed, a path the device did not follow to the end) fails it by name.
TEST_F(WavefrontKernels, APathMegakernelBatchThatIsNotTheDevicesIsNamed) {
    MirrorsIteration2 m(vk_->info());
    for (int tamper = 0; tamper < 3; ++tamper) {
        SCOPED_TRACE(tamper);
        Row row;
        Workload w = m.make(row);
        ASSERT_EQ(w.batch.rays.size(), 2u);
        if (tamper == 0) w.batch.rays[1].originTMin.x += 1.0f;
        if (tamper == 1) w.weights[0] = 0.5f;
        if (tamper == 2) w.paths[1] = 2;  // camera ray 2 misses: its path never reaches the batch
        const WholePathRun r = runWholePath(pathMegakernelStrategyType(), *vk_, *m.s, w, m.camera, m.mesh, row);
        EXPECT_THAT(r.countsMismatch, HasSubstr("batch (1 of 2 rays; first: "));
        EXPECT_THAT(r.countsMismatch, HasSubstr(tamper == 0 ? "ray 1's ray" : tamper == 1 ? "ray 0's weight" : "ray 1's path that never reached"));
    }
}

using WavefrontRuns = WorkloadRuns;

std::string cellText(const Row& row, const std::string& key) { return row.count(key) ? row.at(key) : std::string(); }

// The runs of `result` (scene B, every structure, branching and both whole-path strategies) by a
// whole-path strategy: each batch is branching's (the same rays and hits); it traced every
// generation: `cameraRays` camera rays plus each earlier iteration's rays, which the branching
// rows of those iterations count; Embree traced them too, and the rates count them. Returns the
// rows checked.
int expectWholePathsEndAtBranchingsBatch(const ExperimentResult& result, std::uint64_t cameraRays) {
    std::map<std::string, const Row*> branching;  // structure + rays -> branching's row
    auto key = [](const Row& row) {
        return row.at("structure_type") + " " + row.at("rays_type") + " " + row.at("query") + " " +
               cellText(row, "reflection_iteration") + cellText(row, "path_bounce") + cellText(row, "refraction_iteration");
    };
    for (const Row& row : result.rows) {
        EXPECT_EQ(row.at("status"), "ok") << row.at("label") << ": " << row.at("error");
        if (row.at("strategy_type") == "branching") {
            branching[key(row)] = &row;
            EXPECT_EQ(row.at("embree_rays"), row.at("rays"));
        }
    }
    int checked = 0;
    for (const Row& row : result.rows) {
        if (row.at("strategy_type") == "branching") continue;
        const bool wavefront = row.at("strategy_type") == "wavefront";
        SCOPED_TRACE(row.at("label"));
        if (!branching.count(key(row))) {
            ADD_FAILURE() << "no branching row for " << key(row);
            continue;
        }
        const Row& b = *branching.at(key(row));
        for (const char* same : {"rays", "hits", "query", "voxels_per_ray_mean", "triangles_per_ray_mean", "triangles_per_ray_max"})
            EXPECT_EQ(cellText(row, same), cellText(b, same)) << same;
        if (wavefront) {  // the batch's trace is branching's dispatch
            for (const char* same : {"lanes_model_active", "lanes_model_slots", "simd_lane_utilisation"})
                EXPECT_EQ(cellText(row, same), cellText(b, same)) << same;
        }
        for (const char* zero : {"cpu_reference_mismatches", "hit_miss_mismatches", "rays_cut_short", "exact_false_misses", "exact_false_hits"})
            EXPECT_EQ(cellText(row, zero), "0") << zero;
        // The rays before the batch: the camera rays and the rays of every earlier iteration or bounce.
        std::uint64_t before = cameraRays;
        std::string type = row.at("rays_type"), column = type == "path" ? "path_bounce" : type + "_iteration";
        const int k = type == "primary" ? 0 : std::stoi(row.at(column));
        for (int earlier = 1; earlier < k; ++earlier) {
            Row probe = row;
            probe[column] = std::to_string(earlier);
            probe["query"] = "closest";
            before += std::stoull(branching.at(key(probe))->at("rays"));
        }
        const std::uint64_t traced = (type == "primary" ? 0 : before) + std::stoull(row.at("rays"));
        EXPECT_EQ(row.at("whole_path_rays"), std::to_string(traced));
        EXPECT_EQ(row.at("embree_rays"), std::to_string(traced));  // Embree traced what the kernel did
        EXPECT_EQ(row.at("whole_path_generations"), std::to_string(k + 1));
        // The rates count every ray traced: one repetition, so the median is that repetition.
        const double ms = std::stod(row.at("kernel_ms_median"));
        EXPECT_NEAR(std::stod(row.at("kernel_mrays_s")), double(traced) / (ms * 1e3), 1e-3 * double(traced) / (ms * 1e3));
        if (wavefront) {
            EXPECT_NEAR(std::stod(row.at("kernel_ms_trace")) + std::stod(row.at("kernel_ms_shade")) + std::stod(row.at("kernel_ms_queue")),
                        ms, 1e-3 * ms + 1e-6);
        } else {
            EXPECT_EQ(row.at("path_megakernel_rays_traced"), std::to_string(traced));
        }
        ++checked;
    }
    return checked;
}

const std::string kSceneBRuns =
    "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 16\nheight = 8\nposition = [0, 3, 9.5]\n"
    "look_at = [0, 2.5, 0]\n[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\n"
    "[strategy]\ntype = [\"branching\", \"wavefront\", \"path_megakernel\"]\n[output]\nimages = false\n";

// Scene B: primary rays and reflection iterations 1 to 3 (the last also as any-hit queries).
TEST_F(WavefrontRuns, ReflectionsEndAtBranchingsBatchOnEveryStructure) {
    const ExperimentResult result = run(
        kSceneBRuns + "[[sweep]]\nname = \"primary\"\nrays.type = \"primary\"\n"
        "[[sweep]]\nname = \"reflection\"\nrays.type = \"reflection\"\nreflection.iteration = [1, 2, 3]\n"
        "[[sweep]]\nname = \"any\"\nrays.type = \"reflection\"\nreflection.iteration = 3\nrays.query = \"any\"\n");
    ASSERT_EQ(result.rows.size(), 3u * 3u * 5u);
    EXPECT_EQ(expectWholePathsEndAtBranchingsBatch(result, 16 * 8), 30);
}

// Scene B: path bounces 1 and 2 of two samples, refraction iterations 1 and 2.
TEST_F(WavefrontRuns, PathsAndRefractionsEndAtBranchingsBatchOnEveryStructure) {
    const ExperimentResult result = run(
        kSceneBRuns + "[[sweep]]\nname = \"path\"\nrays.type = \"path\"\npath.bounce = [1, 2]\npath.samples = 2\n"
        "[[sweep]]\nname = \"refraction\"\nrays.type = \"refraction\"\nrefraction.iteration = [1, 2]\n");
    ASSERT_EQ(result.rows.size(), 3u * 3u * 4u);
    EXPECT_EQ(expectWholePathsEndAtBranchingsBatch(result, 16 * 8), 24);
}

TEST_F(WavefrontRuns, RaysOfLightsOrMaterialsAndTiledCameraRaysAreRefusedByName) {
    const ExperimentResult result = run(
        "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 16\nheight = 8\nposition = [0, 3, 9.5]\n"
        "look_at = [0, 2.5, 0]\n[strategy]\ntype = [\"wavefront\", \"path_megakernel\"]\n[output]\nimages = false\n"
        "[[sweep]]\nname = \"shadow\"\nrays.type = \"shadow\"\n"
        "[[sweep]]\nname = \"tiled\"\nrays.type = \"primary\"\ncamera.tile = 4\n");
    ASSERT_EQ(result.rows.size(), 4u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        EXPECT_EQ(row.at("status"), "failed");
        EXPECT_THAT(row.at("error"), HasSubstr(row.at("rays_type") == "shadow"
                                                   ? "strategy.type = " + row.at("strategy_type") + " traces paths over one material and no light, and this ray type's shading passes read lights"
                                                   : "camera.tile: strategy.type = " + row.at("strategy_type")));
    }
}

}  // namespace
}  // namespace rtbench
