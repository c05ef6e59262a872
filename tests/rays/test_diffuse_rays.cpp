// Diffuse rays (rays.type = "path" and "ao"): the arithmetic they are made of against second
// formulations (IEEE's square root, the PCG hash written again in Python, the cosine law's
// distribution), a closed box whose every diffuse ray must meet another face, determinism, the
// device's shading pass bit for bit and a tampered ray it catches, whole runs against Embree and
// the exact reference, and the keys' errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <random>
#include <set>

#include "harness/exact_reference.h"
#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/methods/hand_scenes.h"
#include "tests/methods/test_rays.h"
#include "tests/rays/workload_runs.h"
#include "rays/ao/ao_rays.h"
#include "rays/path/path_rays.h"
#include "rays/shading.h"
#include "rays/shading_reference.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;
using ::testing::HasSubstr;

float fromBits(std::uint32_t bits) { return std::bit_cast<float>(bits); }
std::uint32_t bitsOf(float x) { return std::bit_cast<std::uint32_t>(x); }

// rtSqrt against the CPU's IEEE square root (correctly rounded) on every 997th float of the
// positive range, subnormals included; and the correction it relies on where a device's first
// guess is off: guesses up to 4 ulps away on either side give the same root.
TEST(DiffuseRays, SqrtIsTheCorrectlyRoundedSquareRootFromAnyGuessWithinFourUlps) {
    shadingref::ShadingKernels k{};
    for (std::uint32_t bits = 1; bits < 0x7f800000u; bits += 997) {
        const float x = fromBits(bits);
        ASSERT_EQ(bitsOf(k.rtSqrt(x)), bitsOf(std::sqrt(x))) << x;
    }
    for (std::uint32_t bits = 1; bits < 0x7f800000u; bits += 99991) {
        const float x = fromBits(bits), root = std::sqrt(x);
        for (int off = -4; off <= 4; ++off)
            ASSERT_EQ(bitsOf(k.rtSqrtFromGuess(x, fromBits(bitsOf(root) + std::uint32_t(off)))), bitsOf(root)) << x << " " << off;
    }
    EXPECT_EQ(bitsOf(k.rtSqrt(0.0f)), 0u);
    EXPECT_EQ(k.rtSqrt(INFINITY), INFINITY);
    EXPECT_TRUE(std::isnan(k.rtSqrt(-1.0f)));
}

// Values of a Python transcription of Jarzynski & Olano 2020's pcg_hash (integers masked to 32
// bits), and of its chain (seed, path, bounce, draw) scaled by 2^-24.
TEST(DiffuseRays, ThePcgHashAndItsRandomNumbersAreThoseOfASecondTranscription) {
    shadingref::ShadingKernels k{};
    EXPECT_EQ(k.rtPcgHash(0u), 129708002u);
    EXPECT_EQ(k.rtPcgHash(1u), 2831084092u);
    EXPECT_EQ(k.rtPcgHash(2u), 2055130248u);
    EXPECT_EQ(k.rtPcgHash(0xffffffffu), 3861530882u);
    EXPECT_EQ(k.rtRandom(glm::uvec3(0, 0, 1), 0), 0.12513554096221924f);
    EXPECT_EQ(k.rtRandom(glm::uvec3(7, 12345, 3), 5), 0.8576115965843201f);
    double sum = 0.0;
    const int n = 1 << 16;
    for (int i = 0; i < n; ++i) {
        const float r = k.rtRandom(glm::uvec3(1, std::uint32_t(i), 1), 0);
        ASSERT_GE(r, 0.0f);
        ASSERT_LT(r, 1.0f);
        sum += r;
    }
    EXPECT_NEAR(sum / n, 0.5, 0.005);
}

// A diffuse ray's random key is (seed, path * fan-out + slot, bounce): every (path, slot) of a
// generation draws its own numbers, so neighbouring paths never share a direction (a key of
// path + slot would give path 1's slot 0 path 0's slot 1), another bounce or seed draws others,
// and neighbouring paths' draws are uncorrelated.
TEST(DiffuseRays, EveryPathSlotBounceAndSeedDrawsItsOwnDirection) {
    shadingref::ShadingKernels k{};
    const gpu::Material m = diffuseMaterial();
    const glm::vec3 v0(0, 0, 0), v1(1, 0, 0), v2(0, 1, 0), incoming(0.1f, 0.2f, -1.0f);
    auto direction = [&](std::uint32_t path, std::uint32_t slot, std::uint32_t fanOut, std::uint32_t bounce, std::uint32_t seed) {
        gpu::ShadingParams params{};
        params.pass = glm::uvec4(1024, gpu::kShadeDiffuse, fanOut, bounce);
        params.seed = glm::uvec4(seed, 0, 0, 0);
        params.values = glm::vec4(gpu::kNoHitT, 0, 0, 0);
        gpu::Ray made{};
        float weight = 0.0f;
        EXPECT_TRUE(k.rtShade(params, m, glm::vec3(0.0f), v0, v1, v2, 0.25f, 0.25f, incoming, path, slot, 1.0f, made, weight));
        return glm::vec3(made.directionTMax);
    };
    std::set<std::array<float, 3>> seen;
    std::vector<double> zs;
    for (std::uint32_t path = 0; path < 256; ++path)
        for (std::uint32_t slot = 0; slot < 4; ++slot) {
            const glm::vec3 d = direction(path, slot, 4, 1, 7);
            EXPECT_TRUE(seen.insert({d.x, d.y, d.z}).second) << "path " << path << " slot " << slot << " repeats a direction";
            if (slot == 0) zs.push_back(d.z);
        }
    EXPECT_NE(direction(3, 1, 4, 1, 7), direction(3, 1, 4, 2, 7));  // another bounce
    EXPECT_NE(direction(3, 1, 4, 1, 7), direction(3, 1, 4, 1, 8));  // another seed
    // Neighbouring paths' cos(theta): correlation near 0 (|r| < 4 / sqrt(n) ~ 0.25 for 255 pairs).
    double mean = 0.0, cov = 0.0, var = 0.0;
    for (double z : zs) mean += z / double(zs.size());
    for (std::size_t i = 0; i + 1 < zs.size(); ++i) {
        cov += (zs[i] - mean) * (zs[i + 1] - mean);
        var += (zs[i] - mean) * (zs[i] - mean);
    }
    EXPECT_LT(std::abs(cov / var), 0.25);
}

// Duff et al.'s basis of unit normals (the six axes and 1000 random ones): orthonormal and
// right-handed, measured in double.
TEST(DiffuseRays, TheBasisIsOrthonormalAndRightHanded) {
    shadingref::ShadingKernels k{};
    std::vector<glm::vec3> normals = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::mt19937 rng(3);
    std::normal_distribution<float> g;
    for (int i = 0; i < 1000; ++i) normals.push_back(k.rtNormalize(glm::vec3(g(rng), g(rng), g(rng))));
    for (const glm::vec3 n : normals) {
        glm::vec3 t, b;
        k.rtBasis(n, t, b);
        const glm::dvec3 T(t), B(b), N(n);
        EXPECT_NEAR(glm::length(N), 1.0, 1e-6);
        EXPECT_NEAR(glm::length(T), 1.0, 1e-6);
        EXPECT_NEAR(glm::length(B), 1.0, 1e-6);
        EXPECT_NEAR(glm::dot(T, B), 0.0, 1e-6);
        EXPECT_NEAR(glm::dot(T, N), 0.0, 1e-6);
        EXPECT_NEAR(glm::dot(B, N), 0.0, 1e-6);
        EXPECT_NEAR(glm::length(glm::cross(T, B) - N), 0.0, 2e-6);
    }
}

// The cosine law: a direction's cosine c with the normal has density 2c, so c^2 is uniform on
// [0, 1] (a Kolmogorov-Smirnov statistic under its 1% critical value, 1.63 / sqrt(N); the numbers
// are fixed by their keys, so the test cannot flake) and the mean cosine is 2/3 (uniform
// directions would give 1/2); the azimuth is uniform (each quadrant of the tangent plane a quarter).
TEST(DiffuseRays, DirectionsFollowTheCosineLaw) {
    shadingref::ShadingKernels k{};
    const glm::vec3 n = k.rtNormalize(glm::vec3(1, 2, -0.5f));
    glm::vec3 t, b;
    k.rtBasis(n, t, b);
    const int count = 20000;
    std::vector<double> squares;
    double cosines = 0.0;
    int quadrant[4] = {0, 0, 0, 0};
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 d(k.rtCosineDirection(n, glm::uvec3(1, std::uint32_t(i), 1)));
        ASSERT_NEAR(glm::length(d), 1.0, 1e-6);
        const double c = glm::dot(d, glm::dvec3(n));
        ASSERT_GE(c, 0.0);
        cosines += c;
        squares.push_back(c * c);
        ++quadrant[(glm::dot(d, glm::dvec3(t)) < 0.0 ? 1 : 0) + (glm::dot(d, glm::dvec3(b)) < 0.0 ? 2 : 0)];
    }
    std::sort(squares.begin(), squares.end());
    double ks = 0.0;
    for (int i = 0; i < count; ++i)
        ks = std::max({ks, std::abs(squares[i] - double(i) / count), std::abs(squares[i] - double(i + 1) / count)});
    EXPECT_LT(ks, 1.63 / std::sqrt(double(count)));
    EXPECT_NEAR(cosines / count, 2.0 / 3.0, 0.01);
    for (int q : quadrant) EXPECT_NEAR(q, count / 4, count / 40);
}

// The floor of test_reflection_rays.cpp (y = 0, its hit at u = v = 11/16 the point (3, 0, 3)):
// a diffuse ray leaves it on the side the ray came from, by the offset of shadow rays (2^-16
// along y near zero), with a unit direction on that side and the tMax it was given.
TEST(DiffuseRays, ADiffuseRayLeavesTheSurfaceOnTheSideItWasHitFrom) {
    shadingref::ShadingKernels k{};
    const glm::vec3 v0(-8, 0, -8), v1(8, 0, -8), v2(-8, 0, 8);
    const float u = 11.0f / 16;
    for (const float side : {1.0f, -1.0f}) {
        gpu::Ray r{};
        ASSERT_TRUE(k.rtDiffuseRay(v0, v1, v2, u, u, glm::vec3(1, -2 * side, 0.5f), glm::uvec3(1, 2, 3), 0.75f, r));
        EXPECT_EQ(r.originTMin, glm::vec4(3.0f, side / 65536.0f, 3.0f, 0.0f));
        EXPECT_EQ(r.directionTMax.w, 0.75f);
        EXPECT_GT(r.directionTMax.y * side, 0.0f);
        EXPECT_NEAR(glm::length(glm::dvec3(glm::vec3(r.directionTMax))), 1.0, 1e-6);
    }
    gpu::Ray none{};  // a triangle with no normal makes none
    EXPECT_FALSE(k.rtDiffuseRay(v0, v0, v1, u, u, glm::vec3(0, -1, 0), glm::uvec3(1, 2, 3), 1.0f, none));
}

// The inside of the cube [-1, 1]^3, two triangles a face (face f: triangles 2f, 2f + 1).
TriangleMesh insideOfACube() {
    std::vector<Tri> tris;
    for (int axis = 0; axis < 3; ++axis)
        for (const float side : {-1.0f, 1.0f}) {
            auto corner = [&](float a, float b) {
                glm::vec3 p;
                p[axis] = side;
                p[(axis + 1) % 3] = a;
                p[(axis + 2) % 3] = b;
                return p;
            };
            tris.push_back({corner(-1, -1), corner(1, -1), corner(1, 1)});
            tris.push_back({corner(-1, -1), corner(1, 1), corner(-1, 1)});
        }
    return meshOf(tris);
}

std::vector<gpu::Ray> raysFromInside() {
    std::vector<gpu::Ray> rays;
    for (int i = 0; i < 16; ++i)
        rays.push_back(ray({0.1f, -0.2f, 0.3f}, {std::cos(0.7f * float(i)), 0.5f - 0.07f * float(i), std::sin(0.7f * float(i))}));
    return rays;
}

using DiffuseKernels = VulkanTest;

// A flat face cannot see itself: inside a closed box every diffuse ray meets another face. Three
// bounces of two paths per pixel on every structure and strategy: every ray of every bounce hits,
// on another face than the one it left; the paths are numbered pixel x 2 + sample; Embree and
// the exact reference agree; the device's shading passes make the same rays bit for bit.
TEST_F(DiffuseKernels, EveryBounceInsideAClosedBoxHitsAnotherFaceOnEveryStructureAndStrategy) {
    const TriangleMesh mesh = insideOfACube();
    const std::vector<gpu::Ray> camera = raysFromInside();
    RunConfig run;
    run.values["path.bounce"] = std::int64_t(3);
    run.values["path.samples"] = std::int64_t(2);
    run.values["path.seed"] = std::int64_t(5);
    for (const StructureCase& c : {bruteCase(), gridCase({2, 2, 2}), bvhCase(1)}) {
        SCOPED_TRACE(c.name);
        const std::unique_ptr<Structure> s = c.build(mesh, vk_->info());
        const WorkloadInputs inputs{run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }};
        Row row;
        const Workload w = pathRayType().make(inputs, row);
        ASSERT_EQ(w.between.size(), 2u);
        ASSERT_EQ(w.between[0].rays.size(), 32u);
        for (std::uint32_t r = 0; r < 32; ++r) EXPECT_EQ(w.between[0].paths[r], w.between[0].parents[r] * 2 + r % 2);
        EXPECT_EQ(w.between[1].paths, w.between[0].paths);
        EXPECT_EQ(w.paths, w.between[0].paths);
        EXPECT_EQ(row.at("path_parent_hits"), "32");
        ASSERT_EQ(w.batch.rays.size(), 32u);
        const std::vector<gpu::HitRecord> hits = s->trace(w.batch.rays);
        const std::vector<gpu::HitRecord>& before = w.between[1].hits;
        for (std::uint32_t r = 0; r < 32; ++r) {
            ASSERT_NE(hits[r].primitive, kNoHit) << r;
            EXPECT_NE(hits[r].primitive / 2, before[w.parents[r]].primitive / 2) << r;
            EXPECT_NE(w.between[0].hits[r].primitive / 2, w.cameraHits[w.between[0].parents[r]].primitive / 2) << r;
        }
        expectIdentical(runBranching(*vk_, *s, w.batch.rays, {64, 0, 1}).hits, hits);
        expectIdentical(runMultipass(*vk_, *s, w.batch.rays, MultipassOptions{}, {64, 0, 1}).hits, hits);
        std::vector<std::uint32_t> all(32);
        for (std::uint32_t r = 0; r < 32; ++r) all[r] = r;
        const ExactHits exact = ExactReference(mesh).trace(w.batch.rays, all);
        for (std::uint32_t r = 0; r < 32; ++r)
            EXPECT_EQ(exact.judge(r, hits[r].primitive, true), ExactHits::Verdict::Right) << r;
        EXPECT_EQ(checkShadingOnDevice(*vk_, 64, mesh, camera, w, row), "");
        EXPECT_EQ(row.at("shading_passes"), "3");
        EXPECT_EQ(row.at("shading_rays"), "96");
    }
}

// The random numbers are a function of (seed, path, bounce): the same seed makes the same rays,
// bit for bit; another seed other directions; the two samples of a pixel differ.
TEST_F(DiffuseKernels, TheSameSeedMakesTheSameRaysAndAnotherSeedOthers) {
    const TriangleMesh mesh = insideOfACube();
    const std::vector<gpu::Ray> camera = raysFromInside();
    const std::unique_ptr<Structure> s = bruteOf(mesh, vk_->info());
    auto raysOf = [&](std::int64_t seed) {
        RunConfig run;
        run.values["path.bounce"] = std::int64_t(2);
        run.values["path.samples"] = std::int64_t(2);
        run.values["path.seed"] = seed;
        Row row;
        return pathRayType().make({run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }}, row).batch.rays;
    };
    const std::vector<gpu::Ray> a = raysOf(5), again = raysOf(5), other = raysOf(6);
    ASSERT_EQ(a.size(), again.size());
    EXPECT_EQ(std::memcmp(a.data(), again.data(), a.size() * sizeof(gpu::Ray)), 0);
    std::size_t sameDirection = 0, sameAsOtherSample = 0;
    for (std::size_t r = 0; r < a.size(); ++r) {
        sameDirection += a[r].directionTMax == other[r].directionTMax;
        if (r % 2 == 1) sameAsOtherSample += a[r].directionTMax == a[r - 1].directionTMax;
    }
    EXPECT_EQ(sameDirection, 0u);
    EXPECT_EQ(sameAsOtherSample, 0u);
}

// The device check can fail: a batch ray one ulp off, or a path number changed (whose random
// numbers then differ in the next generation), is a mismatch naming the generation.
TEST_F(DiffuseKernels, ARayTheDeviceDidNotMakeIsAShadingMismatch) {
    const TriangleMesh mesh = insideOfACube();
    const std::vector<gpu::Ray> camera = raysFromInside();
    const std::unique_ptr<Structure> s = bruteOf(mesh, vk_->info());
    RunConfig run;
    run.values["path.bounce"] = std::int64_t(2);
    run.values["path.samples"] = std::int64_t(1);
    run.values["path.seed"] = std::int64_t(0);
    Row row;
    const Workload w = pathRayType().make({run, mesh, camera, *s, glm::vec3(0, 1, 0), [](glm::vec3 p) { return p; }}, row);
    EXPECT_EQ(checkShadingOnDevice(*vk_, 64, mesh, camera, w, row), "");
    Workload offByOneUlp = w;
    offByOneUlp.batch.rays[3].directionTMax.x = std::nextafter(offByOneUlp.batch.rays[3].directionTMax.x, 2.0f);
    EXPECT_THAT(checkShadingOnDevice(*vk_, 64, mesh, camera, offByOneUlp, row), HasSubstr("on 1 rays (first: generation 2, ray 3"));
    EXPECT_EQ(row.at("shading_device_mismatches"), "1");
    Workload otherPath = w;
    otherPath.between[0].paths[0] = 99;
    EXPECT_THAT(checkShadingOnDevice(*vk_, 64, mesh, camera, otherPath, row), HasSubstr("first: generation 1, ray 0"));
    EXPECT_EQ(row.at("shading_device_mismatches"), "2");  // its path, then the ray made from it
}

using DiffuseRuns = WorkloadRuns;

// Scene B from inside (every diffuse ray hits a wall): path bounces 1 and 2 and ambient occlusion
// on every structure and both strategies agree with Embree and the exact reference, their device
// shading passes with the CPU's, and every hit makes path.samples (ao.samples) rays.
TEST_F(DiffuseRuns, PathAndAmbientOcclusionRaysAgreeWithEmbreeAndTheExactReferenceEverywhere) {
    const ExperimentResult result =
        run("[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 32\nheight = 24\nposition = [0, 3, 9.5]\n"
            "look_at = [0, 2.5, 0]\n[rays]\ntype = [\"path\", \"ao\"]\n[path]\nbounce = [1, 2]\nsamples = 2\n[ao]\nsamples = 3\n"
            "[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\n[strategy]\ntype = [\"branching\", \"multipass\"]\n");
    ASSERT_EQ(result.rows.size(), 18u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        ASSERT_EQ(row.at("status"), "ok") << row.at("error");
        for (const char* zero : {"exact_false_misses", "exact_false_hits", "hit_miss_mismatches", "cpu_reference_mismatches",
                                 "exact_parent_wrong", "shading_device_mismatches"})
            EXPECT_EQ(row.at(zero), "0") << zero;
        if (row.at("rays_type") == "ao") {
            EXPECT_EQ(row.at("query"), "any");
            EXPECT_EQ(std::stoul(row.at("rays")), 3 * std::stoul(row.at("ao_camera_hits")));
            EXPECT_GT(std::stoul(row.at("hits")), 0u);                         // some occluded
            EXPECT_LT(std::stoul(row.at("hits")), std::stoul(row.at("rays")));  // and some open
        } else {
            EXPECT_EQ(row.at("query"), "closest");
            EXPECT_EQ(row.at("exact_wrong_primitive"), "0");
            EXPECT_EQ(row.at("hits"), row.at("rays"));  // a closed room
            EXPECT_EQ(std::stoul(row.at("rays")),
                      (row.at("path_bounce") == "1" ? 2 : 1) * std::stoul(row.at("path_parent_hits")));
        }
    }
}

// ao.radius is in the scene's own units: under scene.scale = 4 (the camera moves with the scene)
// the rays are 4 x 0.5 = 2 long, and, every coordinate scaled by a power of two, the same rays
// are occluded as at scale 1. A radius left unscaled (0.5 in the 4x scene) would occlude fewer.
TEST_F(DiffuseRuns, AoRadiusScalesWithTheScene) {
    const ExperimentResult result =
        run("[scene]\nsource = \"procedural:christen_b\"\nscale = [1.0, 4.0]\n[camera]\nwidth = 24\nheight = 16\n"
            "position = [0, 3, 9.5]\nlook_at = [0, 2.5, 0]\n[rays]\ntype = \"ao\"\n[ao]\nsamples = 2\nradius = 0.5\n");
    ASSERT_EQ(result.rows.size(), 2u);
    const Row& one = result.rows[0].at("scene_scale") == "1" ? result.rows[0] : result.rows[1];
    const Row& four = &one == &result.rows[0] ? result.rows[1] : result.rows[0];
    ASSERT_EQ(one.at("status"), "ok") << one.at("error");
    ASSERT_EQ(four.at("status"), "ok") << four.at("error");
    EXPECT_EQ(one.at("ao_radius_traced"), "0.5");
    EXPECT_EQ(four.at("ao_radius_traced"), "2");
    EXPECT_EQ(four.at("rays"), one.at("rays"));
    EXPECT_GT(std::stoul(one.at("hits")), 0u);
    EXPECT_LT(std::stoul(one.at("hits")), std::stoul(one.at("rays")));
    EXPECT_EQ(four.at("hits"), one.at("hits"));
}

TEST_F(DiffuseRuns, ZeroSamplesANegativeRadiusOrABounceWithNoRaysIsAnErrorNamingTheKey) {
    const std::string tetrahedron = "[scene]\nsource = \"procedural:tetrahedron\"\n";
    EXPECT_THAT(errorOf([&] { run(tetrahedron + "[rays]\ntype = \"path\"\n[path]\nsamples = 0\n"); }), HasSubstr("path.samples"));
    EXPECT_THAT(errorOf([&] { run(tetrahedron + "[rays]\ntype = \"ao\"\n[ao]\nsamples = 0\n"); }), HasSubstr("ao.samples"));
    EXPECT_THAT(errorOf([&] { run(tetrahedron + "[rays]\ntype = \"ao\"\n[ao]\nradius = -1.0\n"); }), HasSubstr("ao.radius"));
    EXPECT_THAT(errorOf([&] { run(tetrahedron + "[path]\nbounce = 2\n"); }), HasSubstr("path.bounce"));
    // A fan-out past the host's memory is refused before its rays are made: 1024 x 2048 x 256
    // rays (155 GB at 289 bytes a ray, over half the memory of any machine under 310 GB).
    const ExperimentResult tooMany = run(tetrahedron + "[camera]\nwidth = 1024\nheight = 2048\n[rays]\ntype = \"ao\"\n[ao]\nsamples = 256\n");
    ASSERT_EQ(tooMany.rows.size(), 1u);
    EXPECT_EQ(tooMany.rows[0].at("status"), "failed");
    EXPECT_THAT(tooMany.rows[0].at("error"), HasSubstr("536870912 rays need"));
    // From outside a tetrahedron (convex) no diffuse ray meets it again: bounce 2 has no rays.
    const ExperimentResult result = run(tetrahedron + "[camera]\nwidth = 16\nheight = 16\nposition = [0.3, 0.2, -6]\n"
                                                      "look_at = [0, 0, 0]\n[rays]\ntype = \"path\"\n[path]\nbounce = 2\n");
    ASSERT_EQ(result.rows.size(), 1u);
    EXPECT_EQ(result.rows[0].at("status"), "failed");
    EXPECT_THAT(result.rows[0].at("error"), HasSubstr("no rays at path.bounce 2"));
}

}  // namespace
}  // namespace rtbench
