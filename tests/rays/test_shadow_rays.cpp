// Shadow rays (rays.type = "shadow"): the rule they leave a surface by (Wachter & Binder 2019),
// computed by hand; a hand-built scene whose occlusion is known; Embree's rtcOccluded and the
// exact reference give the same answers as every structure and strategy; whole runs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "harness/embree_reference.h"
#include "harness/exact_reference.h"
#include "harness/runner.h"
#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/methods/hand_scenes.h"
#include "tests/methods/test_rays.h"
#include "tests/temp_dir.h"
#include "tests/rays/workload_runs.h"
#include "rays/shading_reference.h"
#include "structures/triangle_store.h"
#include "rays/shading.h"
#include "rays/shadow/shadow_rays.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;
using ::testing::HasSubstr;

// `steps` ulps from x toward `to`, one std::nextafter at a time: the offset's second formulation.
float ulpsToward(float x, int steps, float to) {
    for (int i = 0; i < steps; ++i) x = std::nextafter(x, to);
    return x;
}

// n = (1, 0, -0.5): x moves int(256 * 1) = 256 ulps up, z int(256 * -0.5) = -128 ulps, i.e. 128
// toward zero, since z > 0; y has no normal component and stays. Near the origin (|p| < 1/32) the
// offset is a distance instead: p + n / 65536.
TEST(ShadowRays, TheOffsetMovesEachCoordinateByUlpsOfItsOwnOrByAFixedStepNearZero) {
    shadingref::ShadingKernels k{};
    const glm::vec3 far = k.rtOffsetRay(glm::vec3(1.0f, -2.0f, 3.0f), glm::vec3(1.0f, 0.0f, -0.5f));
    EXPECT_EQ(far.x, ulpsToward(1.0f, 256, 2.0f));
    EXPECT_EQ(far.y, -2.0f);
    EXPECT_EQ(far.z, ulpsToward(3.0f, 128, 0.0f));
    const glm::vec3 negative = k.rtOffsetRay(glm::vec3(-1.0f, -2.0f, -3.0f), glm::vec3(1.0f, -1.0f, 0.0f));
    EXPECT_EQ(negative.x, ulpsToward(-1.0f, 256, 0.0f));   // along +x: toward zero
    EXPECT_EQ(negative.y, ulpsToward(-2.0f, 256, -3.0f));  // along -y: away from zero
    const glm::vec3 near = k.rtOffsetRay(glm::vec3(0.0f, 0.01f, -0.02f), glm::vec3(0.0f, 1.0f, -1.0f));
    EXPECT_EQ(near.x, 0.0f);
    EXPECT_EQ(near.y, 0.01f + 1.0f / 65536.0f);
    EXPECT_EQ(near.z, -0.02f - 1.0f / 65536.0f);
}

// A floor, y = 0 over x, z in [-2, 2] (triangles 0 and 1), and above it a blocker at y = 1
// (triangle 2: (0,1,0) (2,1,0) (0,1,2)); the light at (0.5, 4, 0.5).
//   camera ray 0 comes down to the floor at (0.5, 0, 0.5) (o = (0.5, 0.5, 3), d = (0, -0.5, -2.5),
//     t = 1; it stays below the blocker); triangle 1 there, v0 = (2,0,-2), e1 = (0,0,4),
//     e2 = (-4,0,4): u = 0.25, v = 0.375, and the normal e1 x e2 = (0,-16,0) scales to (0,-1,0)
//     and flips to face the ray: (0,1,0). x and z get no offset, y = 0 gets 2^-16. The shadow ray
//     is o = (0.5, 2^-16, 0.5), d = (0, 4 - 2^-16, 0) (exact in float), tMax 1: straight up through
//     the blocker at t = (1 - 2^-16) / (4 - 2^-16): occluded.
//   camera ray 1 comes to (-1, 0, -1) (o = (-1, 0.5, 2), d = (0, -0.5, -3)): o = (-1, 2^-16, -1),
//     d = (1.5, 4 - 2^-16, 1.5); at y = 1 it is near (-0.625, 1, -0.625), outside the blocker: lit.
//   camera ray 2 comes up from below to (0.5, 0, 0.5): the light is on the floor's other side:
//     unlit, no shadow ray.
TriangleMesh floorAndBlocker() {
    return meshOf({{glm::vec3(-2, 0, -2), glm::vec3(2, 0, -2), glm::vec3(-2, 0, 2)},
                   {glm::vec3(2, 0, -2), glm::vec3(2, 0, 2), glm::vec3(-2, 0, 2)},
                   {glm::vec3(0, 1, 0), glm::vec3(2, 1, 0), glm::vec3(0, 1, 2)}});
}
const glm::vec3 kLight(0.5f, 4.0f, 0.5f);
std::vector<gpu::Ray> floorCameraRays() {
    return {ray({0.5f, 0.5f, 3}, {0, -0.5f, -2.5f}), ray({-1, 0.5f, 2}, {0, -0.5f, -3}), ray({0.5f, -1, 0.5f}, {0, 1, 0})};
}

using ShadowKernels = VulkanTest;

TEST_F(ShadowKernels, AHandBuiltSceneCastsTheShadowsComputedByHand) {
    const TriangleMesh mesh = floorAndBlocker();
    const std::vector<gpu::Ray> camera = floorCameraRays();
    const std::vector<gpu::HitRecord> cameraHits = bruteOf(mesh, vk_->info())->trace(camera);
    ASSERT_EQ(cameraHits[0].primitive, 1u);
    ASSERT_EQ(cameraHits[1].primitive, 0u);
    ASSERT_EQ(cameraHits[2].primitive, 1u);
    Surfaces lit;
    lit.lights = {kLight};
    const ShadedRays shadow = shadeOnCpu(mesh, lit, {camera, cameraHits, {}, {}}, shadowPass(1));
    ASSERT_EQ(shadow.rays.size(), 2u);  // hit 2 is unlit
    EXPECT_EQ(shadow.parents, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(shadow.paths, (std::vector<std::uint32_t>{0, 1}));
    const float up = 1.0f / 65536.0f;
    EXPECT_EQ(shadow.rays[0].originTMin, glm::vec4(0.5f, up, 0.5f, 0.0f));
    EXPECT_EQ(shadow.rays[0].directionTMax, glm::vec4(0.0f, 4.0f - up, 0.0f, 1.0f));
    EXPECT_EQ(shadow.rays[1].originTMin, glm::vec4(-1.0f, up, -1.0f, 0.0f));
    EXPECT_EQ(shadow.rays[1].directionTMax, glm::vec4(1.5f, 4.0f - up, 1.5f, 1.0f));
    // The device's shading pass makes the same floats.
    double ms = 0.0;
    const ShadedRays device = shadeOnDevice(*vk_, 64, floatTriangles(mesh), lit, {camera, cameraHits, {}, {}}, shadowPass(1), ms);
    std::string first;
    EXPECT_EQ(shadedMismatches(device, shadow, first), 0u) << first;

    // Every structure and strategy: ray 0 occluded by the blocker, ray 1 lit.
    for (const StructureCase& c : {bruteCase(), gridCase({2, 2, 2}), bvhCase(1)}) {
        SCOPED_TRACE(c.name);
        const std::unique_ptr<Structure> s = c.build(mesh, vk_->info());
        const std::vector<gpu::HitRecord> cpu = s->trace(shadow.rays, gpu::kQueryAny);
        EXPECT_EQ(cpu[0].primitive, 2u);
        EXPECT_EQ(cpu[1].primitive, kNoHit);
        expectIdentical(runBranching(*vk_, *s, shadow.rays, {64, 0, 1}, gpu::kQueryAny).hits, cpu);
        expectIdentical(runMultipass(*vk_, *s, shadow.rays, MultipassOptions{}, {64, 0, 1}, gpu::kQueryAny).hits, cpu);
    }
    // Embree's occlusion queries and the exact reference agree.
    EmbreeReference embree(mesh, "threads=1");
    for (EmbreeMode mode : {EmbreeMode::Intersect1, EmbreeMode::Intersect16}) {
        std::vector<gpu::HitRecord> occluded;
        embree.trace(shadow.rays, mode, occluded, gpu::kQueryAny);
        EXPECT_EQ(occluded[0].primitive, kOccluded);
        EXPECT_EQ(occluded[1].primitive, kNoHit);
    }
    const ExactHits exact = ExactReference(mesh).trace(shadow.rays, {0u, 1u});
    EXPECT_EQ(exact.hits[0].primitive, 2u);
    EXPECT_EQ(exact.hits[1].primitive, kNoHit);
}

TEST(ShadowRays, TheDefaultLightIsOneBoxDiagonalAboveTheCentreAlongUp) {
    Bounds3 box;
    box.extend(glm::vec3(-1, 0, -1));
    box.extend(glm::vec3(1, 2, 1));
    // Centre (0, 1, 0); diagonal sqrt(4 + 4 + 4) = 2 sqrt(3); up (0, 2, 0) normalised.
    const glm::vec3 light = defaultLight(box, glm::vec3(0, 2, 0));
    EXPECT_FLOAT_EQ(light.x, 0.0f);
    EXPECT_FLOAT_EQ(light.y, 1.0f + 2.0f * std::sqrt(3.0f));
    EXPECT_FLOAT_EQ(light.z, 0.0f);
    EXPECT_THAT(errorOf([&] { defaultLight(box, glm::vec3(0.0f)); }), HasSubstr("camera.up"));
}

// A shadow ray's direction is light - point: a light beyond 2^24 of the scene's box along an axis
// is named with the axis, not left to fail as "ray 0 direction out of range".
TEST(ShadowRays, ALightTooFarForAShadowRaysDirectionIsNamed) {
    Bounds3 box;
    box.extend(glm::vec3(-1, 0, -1));
    box.extend(glm::vec3(1, 2, 1));
    const glm::vec3 near(0, 16777214, 0);  // 2^24 - 2: its farthest corner is 2^24 away along y
    EXPECT_EQ(reachableLight(near, box, "light.position"), near);
    const std::string error = errorOf([&] { reachableLight(glm::vec3(1e10f, 0, 0), box, "light.position"); });
    EXPECT_THAT(error, HasSubstr("light.position (1e+10, 0, 0"));
    EXPECT_THAT(error, HasSubstr("along x"));
    EXPECT_THAT(errorOf([&] { reachableLight(glm::vec3(0, 16777220, 0), box, "[[light]] 2"); }), HasSubstr("[[light]] 2"));
}

using ShadowRuns = WorkloadRuns;

// Christen's scene B (a room of 166 cubes) lit from inside, on every structure and both
// strategies: each shadow ray's answer equals Embree's rtcOccluded1 and the exact reference's,
// and the rays account for every camera hit (a shadow ray, or unlit).
TEST_F(ShadowRuns, EveryStructureAndStrategyAgreesWithEmbreeAndTheExactReference) {
    const ExperimentResult result =
        run("[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 64\nheight = 48\n[rays]\ntype = [\"primary\", \"shadow\"]\n"
            "[light]\nposition = [2, 5.5, 2]\n"
            "[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\n[strategy]\ntype = [\"branching\", \"multipass\"]\n");
    ASSERT_EQ(result.rows.size(), 12u);
    std::string cameraHits;
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        EXPECT_EQ(row.at("exact_false_misses"), "0");
        EXPECT_EQ(row.at("exact_false_hits"), "0");
        EXPECT_EQ(row.at("hit_miss_mismatches"), "0");
        EXPECT_EQ(row.at("cpu_reference_mismatches"), "0");
        if (row.at("rays_type") == "primary") {
            EXPECT_EQ(row.at("query"), "closest");
            cameraHits = row.at("hits");
            continue;
        }
        EXPECT_EQ(row.at("query"), "any");
        EXPECT_EQ(row.at("camera_rays_hit"), cameraHits);  // the primary run just before, same structure
        EXPECT_EQ(std::stoul(row.at("rays")) + std::stoul(row.at("shadow_unlit")), std::stoul(cameraHits));
        EXPECT_GT(std::stoul(row.at("hits")), 0u);                         // some shadow
        EXPECT_LT(std::stoul(row.at("hits")), std::stoul(row.at("rays")));  // and some light
        EXPECT_EQ(row.at("exact_parent_wrong"), "0");
        EXPECT_EQ(row.count("same_primitive_agreement") ? row.at("same_primitive_agreement") : "", "");
    }
}

TEST_F(ShadowRuns, ALightGivenToCameraRaysIsAnErrorNamingTheKey) {
    EXPECT_THAT(errorOf([&] { run("[scene]\nsource = \"procedural:tetrahedron\"\n[light]\nposition = [0, 5, 0]\n"); }),
                HasSubstr("light.position"));
}

}  // namespace
}  // namespace rtbench
