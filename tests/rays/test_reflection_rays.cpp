// Reflection rays (rays.type = "reflection", Christen 2005 §5.2.1): mirror directions and origins
// computed by hand; two parallel mirrors whose iterations are known, traced by every structure and
// strategy; whole runs of scene B's iterations against Embree and the exact reference.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "harness/exact_reference.h"
#include "harness/path_check.h"
#include "harness/runner.h"
#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/methods/hand_scenes.h"
#include "tests/methods/test_rays.h"
#include "tests/temp_dir.h"
#include "tests/rays/workload_runs.h"
#include "rays/reflection/reflection_rays.h"
#include "rays/shading.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;
using ::testing::HasSubstr;

// A floor y = 0 (triangle 0: v0 = (-8,0,-8), e1 = (16,0,0), e2 = (0,0,16); e1 x e2 = (0,-256,0)
// scales to (0,-1,0) and flips toward a ray from above: n = (0,1,0)). At u = v = 11/16 the point
// is (3, 0, 3) exactly. d = (1, -2, 0.5): 2 d.n / n.n = -4, so the mirror direction is
// d + 4 n = (1, 2, 0.5); x and z get no offset (n has none there), y = 0 lies within 1/32 of zero
// and moves by 2^-16.
// A 45-degree mirror (triangle 1: v0 = (2,2,0), e1 = (1,1,0), e2 = (0,0,1); e1 x e2 = (1,-1,0),
// already scaled; d = (-1,0,0) meets it from +x, d.n = -1 < 0, so n stays): 2 d.n / n.n = -1,
// direction d + n = (0,-1,0), -x turned into -y. At u = 0.5, v = 0.25 the point is (2.5, 2.5,
// 0.25): x moves 256 ulps up (ulp(2.5) = 2^-22: + 2^-14), y 256 ulps down, z stays.
TEST(ReflectionRays, MirrorDirectionsAndOriginsAreTheHandComputedFloats) {
    const TriangleMesh mesh = meshOf({{glm::vec3(-8, 0, -8), glm::vec3(8, 0, -8), glm::vec3(-8, 0, 8)},
                                      {glm::vec3(2, 2, 0), glm::vec3(3, 3, 0), glm::vec3(2, 2, 1)}});
    const std::vector<gpu::Ray> rays = {ray({1, 6, 2}, {1, -2, 0.5f}), ray({9, 2.5f, 0.25f}, {-1, 0, 0}),
                                        ray({0, 1, 0}, {0, 1, 0})};
    const std::vector<gpu::HitRecord> hits = {hitOn(0, 11.0f / 16, 11.0f / 16), hitOn(1, 0.5f, 0.25f), hitOn(kNoHit, 0, 0)};
    const ShadedRays out = shadeOnCpu(mesh, Surfaces{}, {rays, hits, {}, {}}, mirrorPass());
    ASSERT_EQ(out.rays.size(), 2u);  // the miss makes none
    EXPECT_EQ(out.parents, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(out.rays[0].originTMin, glm::vec4(3.0f, 1.0f / 65536.0f, 3.0f, 0.0f));
    EXPECT_EQ(out.rays[0].directionTMax, glm::vec4(1.0f, 2.0f, 0.5f, gpu::kNoHitT));
    EXPECT_EQ(out.rays[1].originTMin, glm::vec4(2.5f + 1.0f / 16384, 2.5f - 1.0f / 16384, 0.25f, 0.0f));
    EXPECT_EQ(out.rays[1].directionTMax, glm::vec4(0.0f, -1.0f, 0.0f, gpu::kNoHitT));
}

// Two parallel mirrors, a floor y = 0 (triangles 0, 1) and a ceiling y = 4 (2, 3), both over
// x, z in [-8, 8]. Camera ray 0 from (0, 2, 0) along (1, -1, 0) meets the floor at (2, 0, 0);
// iteration 1 leaves it at y = 2^-16 along (1, 1, 0) and meets the ceiling near x = 6; iteration
// 2 goes down along (1, -1, 0) and reaches y = 0 near x = 10, past the floor's edge: a miss.
// Camera ray 1 goes straight up, meets the ceiling, and iteration 1 comes straight back to the floor.
// Camera ray 2 misses: it has no iterations.
// (hand::parallelMirrors)

using ReflectionKernels = VulkanTest;

TEST_F(ReflectionKernels, TwoParallelMirrorsGiveTheHandComputedIterationsOnEveryStructureAndStrategy) {
    const TriangleMesh mesh = parallelMirrors();
    const std::vector<gpu::Ray> camera = {ray({0, 2, 0}, {1, -1, 0}), ray({-1, 1, -1}, {0, 1, 0}), ray({0, 2, 0}, {1, 0, 0})};
    for (const StructureCase& c : {bruteCase(), gridCase({2, 2, 2}), bvhCase(1)}) {
        SCOPED_TRACE(c.name);
        const std::unique_ptr<Structure> s = c.build(mesh, vk_->info());
        RunConfig run;
        run.values["reflection.iteration"] = std::int64_t(2);
        const WorkloadInputs inputs{run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }};
        Row row;
        const Workload w = reflectionRayType().make(inputs, row);
        // Iteration 1: ray 0's reflection hits the ceiling, ray 1's the floor; ray 2 made none.
        ASSERT_EQ(w.between.size(), 1u);
        EXPECT_EQ(w.between[0].parents, (std::vector<std::uint32_t>{0, 1}));
        EXPECT_EQ(w.between[0].rays[0].directionTMax, glm::vec4(1, 1, 0, gpu::kNoHitT));
        EXPECT_EQ(w.between[0].rays[1].directionTMax, glm::vec4(0, -1, 0, gpu::kNoHitT));
        EXPECT_GE(w.between[0].hits[0].primitive, 2u);
        EXPECT_LE(w.between[0].hits[1].primitive, 1u);
        EXPECT_EQ(row.at("reflection_parent_rays"), "2");
        EXPECT_EQ(row.at("reflection_parent_hits"), "2");
        // Iteration 2: both back down or up again; each ray remembers its camera pixel.
        ASSERT_EQ(w.batch.rays.size(), 2u);
        EXPECT_EQ(w.pixels, (std::vector<std::uint32_t>{0, 1}));
        EXPECT_EQ(w.batch.rays[0].directionTMax, glm::vec4(1, -1, 0, gpu::kNoHitT));
        EXPECT_EQ(w.batch.rays[1].directionTMax, glm::vec4(0, 1, 0, gpu::kNoHitT));
        const std::vector<gpu::HitRecord> cpu = s->trace(w.batch.rays);
        EXPECT_EQ(cpu[0].primitive, kNoHit);  // past the floor's edge
        EXPECT_GE(cpu[1].primitive, 2u);      // the ceiling again
        expectIdentical(runBranching(*vk_, *s, w.batch.rays, {64, 0, 1}).hits, cpu);
        expectIdentical(runMultipass(*vk_, *s, w.batch.rays, MultipassOptions{}, {64, 0, 1}).hits, cpu);
        // Iteration 3 follows only ray 1; iteration 4 of ray 1 is... still between the mirrors.
        run.values["reflection.iteration"] = std::int64_t(4);
        const Workload four = reflectionRayType().make(inputs, row);
        EXPECT_EQ(four.pixels, (std::vector<std::uint32_t>{1}));
        EXPECT_EQ(four.between.size(), 3u);
    }
}

// The path check on the parallel mirrors' iteration 2 (rays 0 and 1, from camera rays 0 and 1):
// with the structure's true hits no ray left from a wrong hit; a camera hit claimed on the wrong
// mirror (ray 0's: the floor, not the ceiling) marks ray 0, and an iteration-1 hit claimed as a
// miss (ray 1's: it meets the floor) marks ray 1, however right its camera ray was; on a
// simplified scene (sameTriangles false) a wrong triangle that is still a hit does not count.
TEST_F(ReflectionKernels, ARayIsCountedWhenAnyEarlierRayOnItsPathLeftFromAWrongHit) {
    const TriangleMesh mesh = parallelMirrors();
    const std::vector<gpu::Ray> camera = {ray({0, 2, 0}, {1, -1, 0}), ray({-1, 1, -1}, {0, 1, 0}), ray({0, 2, 0}, {1, 0, 0})};
    const std::unique_ptr<Structure> s = bruteOf(mesh, vk_->info());
    RunConfig run;
    run.values["reflection.iteration"] = std::int64_t(2);
    const WorkloadInputs inputs{run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }};
    Row row;
    const Workload truth = reflectionRayType().make(inputs, row);
    ASSERT_EQ(truth.batch.rays.size(), 2u);
    const ExactReference reference(mesh);
    const std::vector<std::uint32_t> both = {0, 1};
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, truth, both, true), 0u);

    Workload wrongCamera = truth;
    ASSERT_LE(wrongCamera.cameraHits[0].primitive, 1u);  // the floor: 0 or 1
    wrongCamera.cameraHits[0].primitive = 1u - wrongCamera.cameraHits[0].primitive;  // the other floor half
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, wrongCamera, both, true), 1u);
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, wrongCamera, {1}, true), 0u);
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, wrongCamera, both, false), 0u);  // still a hit

    Workload wrongIteration = truth;
    wrongIteration.between[0].hits[1].primitive = kNoHit;
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, wrongIteration, both, true), 1u);
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, wrongIteration, {0}, true), 0u);
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, wrongIteration, both, false), 1u);  // a false miss

    wrongIteration.cameraHits[0].primitive = 1u - wrongIteration.cameraHits[0].primitive;
    EXPECT_EQ(pathsLeavingWrongHits(reference, camera, wrongIteration, both, true), 2u);
}

using ReflectionRuns = WorkloadRuns;

// Scene B's first three reflection iterations on every structure and both strategies: every ray
// agrees with Embree and with the exact reference, and iteration k + 1 has a ray for each hit of
// iteration k on the same structure.
TEST_F(ReflectionRuns, IterationsAgreeWithEmbreeAndTheExactReferenceOnEveryStructureAndStrategy) {
    const ExperimentResult result =
        run("[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 48\nheight = 32\n[rays]\ntype = \"reflection\"\n"
            "[reflection]\niteration = [1, 2, 3]\n"
            "[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\n[strategy]\ntype = [\"branching\", \"multipass\"]\n");
    ASSERT_EQ(result.rows.size(), 18u);
    std::map<std::string, std::string> hitsBefore;  // structure x strategy -> the last iteration's hits
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        EXPECT_EQ(row.at("query"), "closest");
        EXPECT_EQ(row.at("exact_false_misses"), "0");
        EXPECT_EQ(row.at("exact_false_hits"), "0");
        EXPECT_EQ(row.at("exact_wrong_primitive"), "0");
        EXPECT_EQ(row.at("hit_miss_mismatches"), "0");
        EXPECT_EQ(row.at("cpu_reference_mismatches"), "0");
        EXPECT_EQ(row.at("exact_parent_wrong"), "0");
        const std::string method = row.at("structure_type") + "/" + row.at("strategy_type");
        if (row.at("reflection_iteration") != "1") {
            EXPECT_EQ(row.at("reflection_parent_hits"), hitsBefore.at(method));
            EXPECT_EQ(row.at("rays"), hitsBefore.at(method));  // every face of scene B has a normal
        }
        hitsBefore[method] = row.at("hits");
    }
}

TEST_F(ReflectionRuns, AnIterationOutOfRangeOrWithNoRaysIsAnErrorNamingTheKey) {
    EXPECT_THAT(errorOf([&] {
                    run("[scene]\nsource = \"procedural:tetrahedron\"\n[rays]\ntype = \"reflection\"\n[reflection]\niteration = 0\n");
                }),
                HasSubstr("reflection.iteration"));
    // From outside a tetrahedron (convex) every reflection leaves it: iteration 2 has no rays.
    const ExperimentResult result = run(
        "[scene]\nsource = \"procedural:tetrahedron\"\n[camera]\nwidth = 32\nheight = 32\nposition = [0.3, 0.2, -6]\n"
        "look_at = [0, 0, 0]\n[rays]\ntype = \"reflection\"\n[reflection]\niteration = 2\n");
    ASSERT_EQ(result.rows.size(), 1u);
    EXPECT_EQ(result.rows[0].at("status"), "failed");
    EXPECT_THAT(result.rows[0].at("error"), HasSubstr("reflection.iteration 2"));
}

}  // namespace
}  // namespace rtbench
