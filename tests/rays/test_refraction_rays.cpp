// Refraction rays (rays.type = "refraction"): Snell's law and total internal reflection computed
// by hand on a glass floor, from either side; the device's shading pass makes the same floats;
// whole runs of scene B's iterations against Embree and the exact reference; the keys' errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/methods/hand_scenes.h"
#include "tests/rays/workload_runs.h"
#include "rays/refraction/refraction_rays.h"
#include "structures/triangle_store.h"
#include "rays/shading.h"

namespace rtbench {
namespace {
using namespace hand;
using ::testing::HasSubstr;

void expectDirection(const gpu::Ray& r, glm::dvec3 want) {
    EXPECT_NEAR(r.directionTMax.x, want.x, 2e-7);
    EXPECT_NEAR(r.directionTMax.y, want.y, 2e-7);
    EXPECT_NEAR(r.directionTMax.z, want.z, 2e-7);
}

using RefractionKernels = VulkanTest;

// A glass floor y = 0 of index 1.5 whose outside is up (v0 = (-8,0,-8), e1 = (0,0,16), e2 =
// (16,0,0): e1 x e2 = (0,256,0)), hit at u = v = 11/16, the point (3, 0, 3). By Snell's law:
// - entering at 45 degrees, d = (1,-1,0): sin t = sin 45 / 1.5 = sqrt(2)/3, so t = (sqrt(2)/3,
//   -sqrt(7)/3, 0), leaving below the floor (y = -2^-16);
// - leaving at 30 degrees, d = (1/2, sqrt(3)/2, 0) from below: sin t = 1.5 / 2 = 3/4, so
//   t = (3/4, sqrt(7)/4, 0), above it;
// - leaving at 45 degrees from below, past the critical angle asin(1/1.5) = 41.8 degrees: total
//   internal reflection, the mirror ray (1, -1, 0) of the same length, staying below;
// - straight down: straight on, (0, -1, 0).
TEST_F(RefractionKernels, SnellsLawAndTotalInternalReflectionAreTheHandComputedRays) {
    const TriangleMesh mesh = meshOf({{glm::vec3(-8, 0, -8), glm::vec3(-8, 0, 8), glm::vec3(8, 0, -8)}});
    const float u = 11.0f / 16, up = 1.0f / 65536;
    const std::vector<gpu::Ray> rays = {ray({2, 1, 3}, {1, -1, 0}), ray({3, -1, 3}, {0.5f, std::sqrt(3.0f) / 2, 0}),
                                        ray({2, -1, 3}, {1, 1, 0}), ray({3, 1, 3}, {0, -1, 0})};
    const std::vector<gpu::HitRecord> hits(4, hitOn(0, u, u));
    const ShadedRays out = shadeOnCpu(mesh, Surfaces{}, {rays, hits, {}, {}}, refractPass(1.5f));
    ASSERT_EQ(out.rays.size(), 4u);
    expectDirection(out.rays[0], {std::sqrt(2.0) / 3, -std::sqrt(7.0) / 3, 0});
    EXPECT_EQ(out.rays[0].originTMin, glm::vec4(3, -up, 3, 0));
    expectDirection(out.rays[1], {0.75, std::sqrt(7.0) / 4, 0});
    EXPECT_EQ(out.rays[1].originTMin, glm::vec4(3, up, 3, 0));
    EXPECT_EQ(out.rays[2].directionTMax, glm::vec4(1, -1, 0, gpu::kNoHitT));  // reflected, exactly
    EXPECT_EQ(out.rays[2].originTMin, glm::vec4(3, -up, 3, 0));
    expectDirection(out.rays[3], {0, -1, 0});
    EXPECT_EQ(out.rays[3].originTMin, glm::vec4(3, -up, 3, 0));
    // Index 1: no bending, the direction only normalised.
    const ShadedRays same = shadeOnCpu(mesh, Surfaces{}, {std::vector<gpu::Ray>{rays[0]}, std::vector<gpu::HitRecord>{hits[0]}, {}, {}}, refractPass(1.0f));
    expectDirection(same.rays[0], {std::sqrt(0.5), -std::sqrt(0.5), 0});
    // The device's shading pass makes the same floats.
    double ms = 0.0;
    std::string first;
    EXPECT_EQ(shadedMismatches(shadeOnDevice(*vk_, 64, floatTriangles(mesh), Surfaces{}, {rays, hits, {}, {}}, refractPass(1.5f), ms), out, first), 0u) << first;
    // The workload's count of reflected rays finds ray 2 alone.
    Workload w;
    w.cameraHits = hits;
    w.batch.rays = out.rays;
    w.parents = out.parents;
    EXPECT_EQ(countTotalInternalReflections(mesh, rays, w), 1u);
}

using RefractionRuns = WorkloadRuns;

// Scene B's first two refraction iterations (every cube glass) on every structure and both
// strategies: every ray agrees with Embree and the exact reference, the device's shading passes
// with the CPU's; inside the cubes some rays are past the critical angle.
TEST_F(RefractionRuns, IterationsAgreeWithEmbreeAndTheExactReferenceOnEveryStructureAndStrategy) {
    const ExperimentResult result =
        run("[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 32\nheight = 24\nposition = [0, 3, 9.5]\n"
            "look_at = [0, 2.5, 0]\n[rays]\ntype = \"refraction\"\n[refraction]\niteration = [1, 2]\n"
            "[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\n[strategy]\ntype = [\"branching\", \"multipass\"]\n");
    ASSERT_EQ(result.rows.size(), 12u);
    std::uint64_t reflected = 0;
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        for (const char* zero : {"exact_false_misses", "exact_false_hits", "exact_wrong_primitive", "hit_miss_mismatches",
                                 "cpu_reference_mismatches", "exact_parent_wrong", "shading_device_mismatches"})
            EXPECT_EQ(row.at(zero), "0") << zero;
        EXPECT_EQ(row.at("rays"), row.at("refraction_parent_hits"));
        reflected += std::stoul(row.at("refraction_total_internal"));
    }
    EXPECT_GT(reflected, 0u);
}

TEST_F(RefractionRuns, ANegativeIndexOfRefractionIsAnErrorNamingTheKey) {
    EXPECT_THAT(errorOf([&] {
                    run("[scene]\nsource = \"procedural:tetrahedron\"\n[rays]\ntype = \"refraction\"\n[refraction]\nior = -1.5\n");
                }),
                HasSubstr("refraction.ior"));
}

}  // namespace
}  // namespace rtbench
