// Whitted ray tracing (rays.type = "whitted"): Fresnel's split on a glass floor against a second
// formulation (Snell's angles, Born & Wolf's sin and tan form), total internal reflection,
// a mirror's and a diffuse surface's rays and weights by hand, a shadow ray toward each light in
// front, the device's pass equal to the CPU's in every bit of ray and weight; whole runs in a
// described room of glass and mirrors on every structure and strategy against Embree and the
// exact reference, with the weights conserved; the keys' and descriptions' errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "structures/triangle_store.h"
#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/methods/hand_scenes.h"
#include "tests/rays/workload_runs.h"
#include "rays/shading.h"
#include "rays/whitted/whitted_rays.h"

namespace rtbench {
namespace {
using namespace hand;
using ::testing::HasSubstr;

// Fresnel's reflectance for unpolarized light from the angles of incidence and transmission
// (Born & Wolf): r_s = sin(i - t) / sin(i + t), r_p = tan(i - t) / tan(i + t), F = (r_s^2 + r_p^2) / 2.
double fresnelFromAngles(double incidence, double transmission) {
    const double s = std::sin(incidence - transmission) / std::sin(incidence + transmission);
    const double p = std::tan(incidence - transmission) / std::tan(incidence + transmission);
    return 0.5 * (s * s + p * p);
}

using WhittedKernels = VulkanTest;

// The glass floor y = 0 of index 1.5, outside up (tests/rays/test_refraction_rays.cpp), hit
// at (3, 0, 3) by: (0) a ray entering at 45 degrees, (1) one leaving at 30 degrees from below with
// weight 1/2, (2) one leaving at 45 degrees from below (past the critical angle), (3) one straight
// down. Each makes its reflection (weight F) then its refraction (weight 1 - F), (2) its
// reflection alone with all its weight.
TEST_F(WhittedKernels, GlassSplitsEachRayByFresnelsEquations) {
    const TriangleMesh mesh = meshOf({{glm::vec3(-8, 0, -8), glm::vec3(-8, 0, 8), glm::vec3(8, 0, -8)}});
    Surfaces glass;
    glass.materials = {glassMaterial(1.5f)};
    const float u = 11.0f / 16;
    const std::vector<gpu::Ray> rays = {ray({2, 1, 3}, {1, -1, 0}), ray({3, -1, 3}, {0.5f, std::sqrt(3.0f) / 2, 0}),
                                        ray({2, -1, 3}, {1, 1, 0}), ray({3, 1, 3}, {0, -1, 0})};
    const std::vector<gpu::HitRecord> hits(4, hitOn(0, u, u));
    const std::vector<float> weights = {1.0f, 0.5f, 1.0f, 1.0f};
    const ShadedRays out = shadeOnCpu(mesh, glass, {rays, hits, {}, weights}, specularPass());
    ASSERT_EQ(out.rays.size(), 7u);
    EXPECT_EQ(out.parents, (std::vector<std::uint32_t>{0, 0, 1, 1, 2, 3, 3}));
    EXPECT_EQ(out.paths, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 6, 7}));  // parent * 2 + slot
    const double pi = std::acos(-1.0);
    const double entering = fresnelFromAngles(pi / 4, std::asin(std::sin(pi / 4) / 1.5));
    const double leaving = fresnelFromAngles(pi / 6, std::asin(1.5 * std::sin(pi / 6)));
    const double normal = (0.5 / 2.5) * (0.5 / 2.5);  // ((n - 1) / (n + 1))^2 = 0.04
    EXPECT_NEAR(entering, 0.0502, 1e-4);  // the textbook's 5 % at 45 degrees, to be sure of the formula
    const double want[] = {entering, 1 - entering, 0.5 * leaving, 0.5 * (1 - leaving), 1.0, normal, 1 - normal};
    for (std::size_t r = 0; r < 7; ++r) EXPECT_NEAR(out.weights[r], want[r], 3e-7) << "ray " << r;
    // The reflections are rtReflectRay's mirror rays; the refractions go on below the floor.
    EXPECT_EQ(out.rays[0].directionTMax, glm::vec4(1, 1, 0, gpu::kNoHitT));
    EXPECT_LT(out.rays[1].directionTMax.y, 0.0f);
    EXPECT_EQ(out.rays[4].directionTMax, glm::vec4(1, -1, 0, gpu::kNoHitT));
    EXPECT_EQ(out.rays[5].directionTMax, glm::vec4(0, 1, 0, gpu::kNoHitT));
    // The device's pass makes the same rays and weights, bit for bit.
    double ms = 0.0;
    std::string first;
    EXPECT_EQ(shadedMismatches(shadeOnDevice(*vk_, 64, floatTriangles(mesh), glass, {rays, hits, {}, weights}, specularPass(), ms),
                               out, first),
              0u)
        << first;
}

// Floor A (a mirror of reflectance 1/4) and floor B (diffuse), each hit from above at
// (3, 0, 3) and (23, 0, 3); three lights: above, below the floors (behind them: no ray) and at
// (0, 4, 0). A's ray has weight 1/2: its reflection carries 1/8, its shadow rays 3/8; B's
// shadow rays carry 1 and B makes no reflection.
TEST_F(WhittedKernels, MirrorsAndDiffuseSurfacesMakeTheHandComputedRaysAndWeights) {
    const TriangleMesh mesh = meshOf({{glm::vec3(-8, 0, -8), glm::vec3(-8, 0, 8), glm::vec3(8, 0, -8)},
                                      {glm::vec3(12, 0, -8), glm::vec3(12, 0, 8), glm::vec3(28, 0, -8)}});
    Surfaces s;
    s.materials = {diffuseMaterial(), mirrorMaterial(0.25f)};
    s.materialOf = {1, 0};
    s.lights = {glm::vec3(3, 4, 3), glm::vec3(3, -4, 3), glm::vec3(0, 4, 0)};
    const float u = 11.0f / 16, up = 1.0f / 65536;
    const std::vector<gpu::Ray> rays = {ray({3, 1, 3}, {0, -1, 0}), ray({23, 1, 3}, {0, -1, 0})};
    const std::vector<gpu::HitRecord> hits = {hitOn(0, u, u), hitOn(1, u, u)};
    const std::vector<float> weights = {0.5f, 1.0f};
    const ShadedRays specular = shadeOnCpu(mesh, s, {rays, hits, {}, weights}, specularPass());
    ASSERT_EQ(specular.rays.size(), 1u);
    EXPECT_EQ(specular.parents[0], 0u);
    EXPECT_EQ(specular.rays[0].originTMin, glm::vec4(3, up, 3, 0));
    EXPECT_EQ(specular.rays[0].directionTMax, glm::vec4(0, 1, 0, gpu::kNoHitT));
    EXPECT_EQ(specular.weights[0], 0.125f);
    const ShadedRays shadow = shadeOnCpu(mesh, s, {rays, hits, {}, weights}, shadowPass(3));
    ASSERT_EQ(shadow.rays.size(), 4u);
    EXPECT_EQ(shadow.parents, (std::vector<std::uint32_t>{0, 0, 1, 1}));
    EXPECT_EQ(shadow.paths, (std::vector<std::uint32_t>{0, 2, 3, 5}));  // parent * 3 + light
    EXPECT_EQ(shadow.weights, (std::vector<float>{0.375f, 0.375f, 1.0f, 1.0f}));
    EXPECT_EQ(shadow.rays[0].directionTMax, glm::vec4(0, 4 - up, 0, 1));
    EXPECT_EQ(shadow.rays[1].directionTMax, glm::vec4(-3, 4 - up, -3, 1));
    EXPECT_EQ(shadow.rays[2].originTMin, glm::vec4(23, up, 3, 0));
    EXPECT_EQ(shadow.rays[3].directionTMax, glm::vec4(-23, 4 - up, -3, 1));
    double ms = 0.0;
    std::string first;
    const std::vector<gpu::Triangle> triangles = floatTriangles(mesh);
    EXPECT_EQ(shadedMismatches(shadeOnDevice(*vk_, 64, triangles, s, {rays, hits, {}, weights}, specularPass(), ms), specular, first), 0u)
        << first;
    EXPECT_EQ(shadedMismatches(shadeOnDevice(*vk_, 64, triangles, s, {rays, hits, {}, weights}, shadowPass(3), ms), shadow, first), 0u)
        << first;
    // A shadow pass with more rays per hit than lights is refused, on either side.
    EXPECT_THAT(errorOf([&] { shadeOnCpu(mesh, s, {rays, hits, {}, weights}, shadowPass(4)); }), HasSubstr("has 3 lights"));
    EXPECT_THAT(errorOf([&] { shadeOnDevice(*vk_, 64, triangles, s, {rays, hits, {}, weights}, shadowPass(4), ms); }),
                HasSubstr("has 3 lights"));
}

// A weight below the smallest normal float makes no ray, on the CPU and on a device that flushes
// such products to 0 alike: a mirror of reflectance 1/1024 hit by rays of weight 2^-116 and 2^-117
// reflects the first (2^-126, normal) and not the second (2^-127).
TEST_F(WhittedKernels, AWeightBelowTheSmallestNormalFloatMakesNoRay) {
    const TriangleMesh mesh = meshOf({{glm::vec3(-8, 0, -8), glm::vec3(-8, 0, 8), glm::vec3(8, 0, -8)}});
    Surfaces s;
    s.materials = {mirrorMaterial(1.0f / 1024)};
    const float u = 11.0f / 16;
    const std::vector<gpu::Ray> rays(2, ray({3, 1, 3}, {0, -1, 0}));
    const std::vector<gpu::HitRecord> hits(2, hitOn(0, u, u));
    const std::vector<float> weights = {std::ldexp(1.0f, -116), std::ldexp(1.0f, -117)};
    const ShadedRays out = shadeOnCpu(mesh, s, {rays, hits, {}, weights}, specularPass());
    ASSERT_EQ(out.rays.size(), 1u);
    EXPECT_EQ(out.parents[0], 0u);
    EXPECT_EQ(out.weights[0], std::ldexp(1.0f, -126));
    double ms = 0.0;
    std::string first;
    EXPECT_EQ(shadedMismatches(shadeOnDevice(*vk_, 64, floatTriangles(mesh), s, {rays, hits, {}, weights}, specularPass(), ms), out,
                               first),
              0u)
        << first;
}

class WhittedRuns : public WorkloadRuns {
protected:
    // Scene B's room as a mirror of reflectance 1/2 holding two glass spheres, lit by two lights.
    std::string room() {
        return dir_.write("whitted_room.toml",
                          "[[object]]\nmesh = \"procedural:christen_b\"\n[[object]]\nmesh = \"cgal:sphere\"\nsize = 3\n"
                          "translate = [0, 2, 0]\n[[object]]\nmesh = \"cgal:sphere\"\nsize = 2\ntranslate = [3, 4, 2]\n"
                          "[[material]]\nmesh = \"procedural:christen_b\"\ntype = \"mirror\"\nreflectance = 0.5\n"
                          "[[material]]\nmesh = \"cgal:sphere\"\ntype = \"glass\"\nior = 1.5\n"
                          "[[light]]\nposition = [2, 5.5, 2]\n[[light]]\nposition = [-6, 4, 6]\n");
    }
    std::string header(const std::string& sceneKeys = "") {
        return "[scene]\nsource = \"" + room() + "\"\n" + sceneKeys +
               "[camera]\nwidth = 32\nheight = 24\nposition = [0, 3, 9.5]\nlook_at = [0, 2.5, 0]\n[rays]\ntype = \"whitted\"\n";
    }
};

// Generation 2's reflections and refractions and the shadow rays of its hits, on every structure
// and both strategies: every ray agrees with Embree and the exact reference, the device's passes
// with the CPU's; both kinds of secondary ray and both lights occur.
TEST_F(WhittedRuns, RaysAgreeWithEmbreeAndTheExactReferenceOnEveryStructureAndStrategy) {
    const ExperimentResult result =
        run(header() + "[whitted]\ndepth = 2\nrays = [\"secondary\", \"shadow\"]\n[structure]\ntype = [\"uniform_grid\", "
                       "\"bvh\", \"brute_force\"]\n[strategy]\ntype = [\"branching\", \"multipass\"]\n");
    ASSERT_EQ(result.rows.size(), 12u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        for (const char* zero : {"exact_false_misses", "exact_false_hits", "hit_miss_mismatches", "cpu_reference_mismatches",
                                 "shading_device_mismatches"})
            EXPECT_EQ(row.at(zero), "0") << zero;
        EXPECT_EQ(row.at("whitted_lights"), "2");
        EXPECT_EQ(row.at("whitted_materials"), "3");
        EXPECT_EQ(row.at("shading_passes"), row.at("whitted_rays") == "shadow" ? "3" : "2");
        if (row.at("whitted_rays") == "secondary") {
            EXPECT_EQ(row.at("query"), "closest");
            EXPECT_GT(std::stoul(row.at("whitted_reflected")), 0u);
            EXPECT_GT(std::stoul(row.at("whitted_refracted")), 0u);
        } else {
            EXPECT_EQ(row.at("query"), "any");
            EXPECT_LE(std::stoul(row.at("rays")), 2 * std::stoul(row.at("whitted_parent_hits")));
        }
    }
}

// What the weights say, from the rays counted: with every surface glass, each hit's reflection and
// refraction carry its whole weight, so generation 1's weights add up to the camera hits; with
// every surface a mirror of reflectance r, generation 1's add up to r times them, and the shadow
// rays (one light) of generation k's hits carry (1 - r) r^k each.
TEST_F(WhittedRuns, WeightsAreConservedByGlassAndSplitByMirrors) {
    const std::string base = "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 32\nheight = 24\n"
                             "position = [0, 3, 9.5]\nlook_at = [0, 2.5, 0]\n[rays]\ntype = \"whitted\"\n[structure]\n"
                             "type = \"bvh\"\n";
    const ExperimentResult glass = run(base + "[whitted]\nsurface = \"glass\"\n");
    ASSERT_EQ(glass.rows.at(0).at("status"), "ok") << glass.rows.at(0).at("error");
    EXPECT_NEAR(std::stod(glass.rows[0].at("whitted_weight")), std::stod(glass.rows[0].at("whitted_parent_hits")), 1e-3);
    // Every hit on glass reflects (past the critical angle, only reflects); the rest are refractions.
    EXPECT_EQ(glass.rows[0].at("whitted_reflected"), glass.rows[0].at("whitted_parent_hits"));
    EXPECT_EQ(std::stoul(glass.rows[0].at("whitted_reflected")) + std::stoul(glass.rows[0].at("whitted_refracted")),
              std::stoul(glass.rows[0].at("rays")));
    EXPECT_GT(std::stoul(glass.rows[0].at("whitted_refracted")), 0u);
    const ExperimentResult mirror = run(base + "[whitted]\nsurface = \"mirror\"\nreflectance = 0.25\ndepth = [0, 1]\n"
                                               "rays = [\"secondary\", \"shadow\"]\n");
    for (const Row& row : mirror.rows) {
        if (row.at("whitted_depth") == "0" && row.at("whitted_rays") == "secondary") {
            EXPECT_EQ(row.at("status"), "failed");
            EXPECT_THAT(row.at("error"), HasSubstr("whitted.depth = 0 with whitted.rays = secondary"));
            continue;
        }
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        const double rays = std::stod(row.at("rays")), weight = std::stod(row.at("whitted_weight"));
        if (row.at("whitted_rays") == "secondary") {
            EXPECT_EQ(row.at("rays"), row.at("whitted_parent_hits"));  // a mirror ray per hit
            EXPECT_EQ(row.at("whitted_refracted"), "0");
            EXPECT_NEAR(weight, 0.25 * rays, 1e-6 * rays);
        } else {
            // From generation k's hits: (1 - r) r^k.
            const double carried = row.at("whitted_depth") == "0" ? 0.75 : 0.75 * 0.25;
            EXPECT_NEAR(weight, carried * rays, 1e-6 * rays);
        }
    }
}

// The description's lights move with the scene (scene.scale), as the camera does: scaled by 2,
// exactly in float, the room casts the same shadows.
TEST_F(WhittedRuns, TheDescriptionsLightsMoveWithTheScene) {
    const ExperimentResult result = run(header("scale = [1, 2]\n") + "[whitted]\ndepth = 0\nrays = \"shadow\"\n"
                                                   "[structure]\ntype = \"bvh\"\n");
    ASSERT_EQ(result.rows.size(), 2u);
    for (const Row& row : result.rows) ASSERT_EQ(row.at("status"), "ok") << row.at("error");
    EXPECT_EQ(result.rows[0].at("rays"), result.rows[1].at("rays"));
    EXPECT_EQ(result.rows[0].at("hits"), result.rows[1].at("hits"));
    EXPECT_GT(std::stoul(result.rows[0].at("hits")), 0u);
}

TEST_F(WhittedRuns, ErrorsNameTheKey) {
    auto errorRunning = [&](const std::string& body) {
        const ExperimentResult r = run(body);
        return r.rows.empty() ? std::string("(no rows)") : r.rows[0].at("error");
    };
    EXPECT_THAT(errorOf([&] { run(header() + "[whitted]\nsurface = \"glass\"\nior = -1.5\n"); }), HasSubstr("whitted.ior"));
    EXPECT_THAT(errorOf([&] { run(header() + "[whitted]\nsurface = \"glass\"\nreflectance = 0.5\n"); }),
                HasSubstr("whitted.reflectance"));
    EXPECT_THAT(errorRunning(header() + "[light]\nposition = [0, 5, 0]\n"),
                HasSubstr("light.position: the scene description gives 2 [[light]] tables"));
    const std::string missing = dir_.write("missing.toml", "[[object]]\nmesh = \"cgal:sphere\"\n[[material]]\n"
                                                           "mesh = \"cgal:bunny00\"\ntype = \"glass\"\n");
    EXPECT_THAT(errorRunning("[scene]\nsource = \"" + missing + "\"\n[rays]\ntype = \"whitted\"\n"),
                HasSubstr("missing.toml:4: key 'material.mesh': 'cgal:bunny00' is placed by no [[object]]"));
    const std::string dark = dir_.write("dark.toml", "light = []\n[[object]]\nmesh = \"cgal:sphere\"\n");
    EXPECT_THAT(errorRunning("[scene]\nsource = \"" + dark + "\"\n[rays]\ntype = \"whitted\"\n"),
                HasSubstr("dark.toml:1: 'light' is an empty list"));
}

}  // namespace
}  // namespace rtbench
