// rtDivide (kernels/ray_math.glsl), both exact ways (intersection.division), against what could
// disagree with them: IEEE float division on the CPU, and for the integer correction an
// independent formulation of the rounded significand quotient by 64-bit integer division. On the
// device: the branching kernel dividing each way, against the other and the CPU reference.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "strategies/branching/branching_strategy.h"
#include "structures/uniform_grid/grid_reference.h"
#include "structures/uniform_grid/grid_structure.h"
#include "methods/metrics.h"
#include "scene/camera.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"

namespace rtbench {
namespace {

float fromBits(std::uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

std::uint32_t bitsOf(float f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    return bits;
}

// The CPU's own IEEE float division, the reference. A zero divisor is defined by IEEE 754 (+-infinity
// or NaN), which C++ leaves undefined, so UBSan's float-divide-by-zero is off here alone.
__attribute__((no_sanitize("float-divide-by-zero"))) float ieeeQuotient(float a, float b) {
    const volatile float q = a / b;
    return q;
}

// Equal bit for bit, or both NaN (IEEE leaves a NaN's payload open).
bool sameQuotient(float ours, float ieee) {
    return bitsOf(ours) == bitsOf(ieee) || (ours != ours && ieee != ieee);
}

gridref::GridKernels kernelsDividing(std::uint32_t division) {
    gridref::GridKernels k{};
    k.division = division;
    return k;
}

// round(A 2^s / B) by 64-bit integer division, rounding half up (no half occurs).
std::uint32_t roundedQuotient(std::uint32_t A, std::uint32_t B, std::uint32_t s) {
    return std::uint32_t(((std::uint64_t(A) << (s + 1)) + B) / (2 * std::uint64_t(B)));
}

TEST(ExactDivision, QuotientSignificandFromAnyGuessWithin127OfIt) {
    // Every dividend significand against divisors at both ends and in between, from guesses up to
    // 127 off (a conforming device's is at most 8 off) and reciprocals 2^23 / B up to 4 ULP off
    // (OpFDiv may err by 2.5).
    gridref::GridKernels k{};
    std::mt19937 rng(5);
    std::vector<std::uint32_t> divisors = {0x800000u, 0x800001u, 0xffffffu, 0xfffffeu, 0xc00000u, 0xaaaaabu};
    for (int i = 0; i < 4; ++i) divisors.push_back(0x800000u | (rng() & 0x7fffffu));
    std::uint64_t wrong = 0;
    for (std::uint32_t B : divisors) {
        std::vector<float> reciprocals;  // 2^23 / B, and 4 ULP either side
        for (int ulps : {-4, 0, 4})
            reciprocals.push_back(fromBits(std::uint32_t(std::int64_t(bitsOf(8388608.0f / float(B))) + ulps)));
        for (std::uint32_t A = 0x800000u; A < 0x1000000u; ++A) {
            const std::uint32_t s = A >= B ? 23u : 24u;
            const std::uint32_t expected = roundedQuotient(A, B, s);
            ASSERT_GE(expected, 0x800000u);
            ASSERT_LT(expected, 0x1000000u);
            for (int offset : {-127, -6, -1, 0, 1, 6, 127})
                for (float reciprocal : reciprocals)
                    wrong += k.rtQuotientSignificand(A, B, s, std::uint32_t(std::int64_t(expected) + offset), reciprocal) !=
                             expected;
        }
    }
    EXPECT_EQ(wrong, 0u);
}

TEST(ExactDivision, EveryReciprocalOfASignificandEqualsIeee) {
    // 1 / b for every float significand, at three exponents (the Moller-Trumbore test's 1 / det).
    for (std::uint32_t division : {gpu::kDivisionInteger, gpu::kDivisionDouble}) {
        SCOPED_TRACE("division " + std::to_string(division));
        gridref::GridKernels k = kernelsDividing(division);
        std::uint64_t wrong = 0;
        for (std::uint32_t exponent : {1u, 127u, 253u})
            for (std::uint32_t m = 0; m < 0x800000u; ++m) {
                const float b = fromBits((exponent << 23) | m);
                const volatile float ieee = 1.0f / b;
                wrong += !sameQuotient(k.rtDivide(1.0f, b), ieee);
            }
        EXPECT_EQ(wrong, 0u);
    }
}

TEST(ExactDivision, EqualsIeeeOnRandomPairsOverTheWholeRange) {
    // Random bit patterns, so zeros, subnormals, infinities, NaNs and quotients that overflow or
    // fall subnormal all occur; then pairs of normal floats, whose quotient is mostly normal.
    for (std::uint32_t division : {gpu::kDivisionInteger, gpu::kDivisionDouble}) {
        SCOPED_TRACE("division " + std::to_string(division));
        gridref::GridKernels k = kernelsDividing(division);
        std::mt19937 rng(11);
        std::uniform_int_distribution<std::uint32_t> normal(0x00800000u, 0x7f7fffffu);
        std::uint64_t wrong = 0;
        for (int i = 0; i < 2000000; ++i) {
            const bool anyBits = i % 2 == 0;
            const float a = fromBits(anyBits ? rng() : normal(rng) | (rng() & 0x80000000u));
            const float b = fromBits(anyBits ? rng() : normal(rng) | (rng() & 0x80000000u));
            const float ieee = ieeeQuotient(a, b);
            if (!sameQuotient(k.rtDivide(a, b), ieee) && ++wrong <= 3)
                ADD_FAILURE() << std::hexfloat << a << " / " << b << ": " << k.rtDivide(a, b) << ", IEEE " << ieee;
        }
        EXPECT_EQ(wrong, 0u);
        const float inf = std::numeric_limits<float>::infinity(), largest = std::numeric_limits<float>::max();
        EXPECT_EQ(k.rtDivide(1.0f, 1e-39f), inf);           // a subnormal divisor
        EXPECT_EQ(k.rtDivide(-largest, 0.5f), -inf);        // overflow
        EXPECT_EQ(k.rtDivide(largest, 1.0f), largest);
        EXPECT_EQ(k.rtDivide(1e-30f, 1e10f), 1e-30f / 1e10f);  // a subnormal quotient
        EXPECT_EQ(bitsOf(k.rtDivide(-0.0f, 3.0f)), bitsOf(-0.0f));
        EXPECT_EQ(k.rtDivide(1.0f, 3.0f), 1.0f / 3.0f);
        EXPECT_TRUE(k.rtDivide(0.0f, 0.0f) != k.rtDivide(0.0f, 0.0f));  // NaN
        const float nan = std::numeric_limits<float>::quiet_NaN();
        for (float a : {1.0f, -1.0f, 0.0f, -0.0f, inf, -inf, nan, 1e-39f})  // zero divisors (the bits are 2 in 2^32)
            for (float zero : {0.0f, -0.0f})
                EXPECT_TRUE(sameQuotient(k.rtDivide(a, zero), ieeeQuotient(a, zero))) << a << " / " << zero;
        EXPECT_EQ(k.rtDivide(-2.0f, 0.0f), -inf);
        EXPECT_EQ(k.rtDivide(2.0f, -0.0f), -inf);
    }
}

// A hand-checked value: 1 / 3 in float is 0x3eaaaaab (0.333333343...): 2^25 / 3 = 11184810.67
// rounds up to 11184811 = 0xaaaaab, exponent -2.
TEST(ExactDivision, OneThirdByHand) {
    gridref::GridKernels k{};
    EXPECT_EQ(bitsOf(k.rtDivideByIntegers(1.0f, 3.0f)), 0x3eaaaaabu);
    EXPECT_EQ(k.rtQuotientSignificand(0x800000u, 0xc00000u, 24u, 0xaaaaaau, 2.0f / 3.0f), 0xaaaaabu);
}

using ExactDivisionOnDevice = VulkanTest;

TEST_F(ExactDivisionOnDevice, BothDivisionsTraceTheSameRecordsAsTheCpu) {
    // The branching kernel over a grid of Christen's scene B (a room of 166 cubes), both triangle tests (the
    // watertight one divides only for a hit), each way of dividing: identical records.
    const TriangleMesh mesh = christenSceneB();
    GridResolutionRule rule;
    rule.minDim = 32;
    const UniformGrid grid = buildUniformGrid(mesh, rule);
    const std::vector<gpu::Ray> rays = generatePrimaryRays(fitCamera(mesh.bounds()), 96, 96);
    for (std::uint32_t test : {gpu::kTriangleTestMollerTrumbore, gpu::kTriangleTestWatertight}) {
        SCOPED_TRACE("triangle test " + std::to_string(test));
        std::vector<std::vector<gpu::HitRecord>> byDivision;
        for (std::uint32_t division : {gpu::kDivisionInteger, gpu::kDivisionDouble}) {
            const std::unique_ptr<Structure> structure = gridStructure(grid);
            structure->setArithmetic({test, division});
            byDivision.push_back(runBranching(*vk_, *structure, rays, {64, 0, 1}).hits);
            const std::vector<gpu::HitRecord> cpu = structure->trace(rays);
            EXPECT_EQ(std::memcmp(byDivision.back().data(), cpu.data(), cpu.size() * sizeof(gpu::HitRecord)), 0);
        }
        EXPECT_EQ(std::memcmp(byDivision[0].data(), byDivision[1].data(), rays.size() * sizeof(gpu::HitRecord)), 0);
        EXPECT_GT(workStats(byDivision[0]).hits, 1000u);
    }
}

}  // namespace
}  // namespace rtbench
