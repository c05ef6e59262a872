// Image-level accuracy as idiff computes it: hand-computed errors, the threshold rule, OIIO's
// quirks (float threshold, peak from the values, non-finite values), and the direct computation
// against ImageBufAlgo::compare on random images when built with OpenImageIO.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "harness/image_compare.h"
#include "tests/error_of.h"

namespace rtbench {
namespace {

using Compare = ImageComparison (*)(const std::vector<float>&, const std::vector<float>&, std::uint32_t,
                                    std::uint32_t, double);

// Every expectation holds for both paths (without OpenImageIO both are the direct one).
class ImageCompare : public ::testing::TestWithParam<Compare> {};

std::vector<float> randomImage(std::uint32_t n, std::uint32_t seed, float lo = 0.0f, float hi = 1.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> value(lo, hi);
    std::vector<float> image(n);
    for (float& v : image) v = value(rng);
    return image;
}

// Equal to ~1e-9 relative, NaN equal to NaN, inf to inf of the same sign.
void expectClose(double expected, double actual, const char* what) {
    if (std::isnan(expected) || std::isinf(expected)) {
        if (std::isnan(expected))
            EXPECT_TRUE(std::isnan(actual)) << what << ": " << actual;
        else
            EXPECT_EQ(expected, actual) << what;
        return;
    }
    EXPECT_NEAR(expected, actual, 1e-9 * std::abs(expected)) << what;
}

void expectSame(const ImageComparison& expected, const ImageComparison& actual) {
    EXPECT_EQ(expected.pixels, actual.pixels);
    expectClose(expected.meanError, actual.meanError, "meanError");
    expectClose(expected.rmsError, actual.rmsError, "rmsError");
    expectClose(expected.psnr, actual.psnr, "psnr");
    expectClose(expected.maxError, actual.maxError, "maxError");
    EXPECT_EQ(expected.differing, actual.differing);
}

TEST_P(ImageCompare, IdenticalImagesHaveNoErrorAndInfinitePsnr) {
    const std::vector<float> image = randomImage(8 * 6, 7);
    const ImageComparison r = GetParam()(image, image, 8, 6, 0.0);
    EXPECT_EQ(r.pixels, 48u);
    EXPECT_EQ(r.meanError, 0.0);
    EXPECT_EQ(r.rmsError, 0.0);
    EXPECT_EQ(r.maxError, 0.0);
    EXPECT_EQ(r.psnr, std::numeric_limits<double>::infinity());
    EXPECT_EQ(r.differing, 0u);  // d == 0 never counts, even against a zero threshold
}

TEST_P(ImageCompare, OnePixelOffByAHalf) {
    std::vector<float> reference(16, 0.25f), test = reference;
    test[2 * 4 + 1] = 0.75f;  // (x 1, y 2)
    const ImageComparison r = GetParam()(test, reference, 4, 4, 0.1);
    EXPECT_EQ(r.pixels, 16u);
    EXPECT_DOUBLE_EQ(r.meanError, 0.5 / 16);             // 0.03125
    EXPECT_DOUBLE_EQ(r.rmsError, std::sqrt(0.25 / 16));  // 0.125
    EXPECT_NEAR(r.psnr, 20.0 * std::log10(8.0), 1e-12);  // 18.0618 dB
    EXPECT_EQ(r.maxError, 0.5);
    EXPECT_EQ(r.differing, 1u);
}

TEST_P(ImageCompare, ADifferenceEqualToTheThresholdDoesNotCount) {
    std::vector<float> reference(16, 0.25f), test = reference;
    test[5] = 0.5f;    // d = 0.25 exactly
    test[9] = 0.375f;  // d = 0.125
    EXPECT_EQ(GetParam()(test, reference, 4, 4, 0.25).differing, 0u);
    EXPECT_EQ(GetParam()(test, reference, 4, 4, 0.2499).differing, 1u);
    EXPECT_EQ(GetParam()(test, reference, 4, 4, 0.125).differing, 1u);
    EXPECT_EQ(GetParam()(test, reference, 4, 4, 0.0).differing, 2u);
    // A negative threshold counts every pixel that differs at all, not the equal ones.
    EXPECT_EQ(GetParam()(test, reference, 4, 4, -1.0).differing, 2u);
}

TEST_P(ImageCompare, TheThresholdIsRoundedToFloat) {
    // d = 0.1f = 0.100000001490116... > 0.1 in double, but OIIO compares against float(0.1).
    std::vector<float> reference(4, 0.0f), test = reference;
    test[3] = 0.1f;
    EXPECT_EQ(GetParam()(test, reference, 2, 2, 0.1).differing, 0u);
    EXPECT_EQ(GetParam()(test, reference, 2, 2, 0.0999999).differing, 1u);
}

TEST_P(ImageCompare, PsnrPeakIsTheLargestMagnitudeAboveOne) {
    // Values outside [0, 1]: the peak is max(1, largest |value|); -1 (a miss in a shaded image) is
    // within the unit peak.
    std::vector<float> reference = {-1.0f, 0.0f, 0.0f, 0.0f}, test = {-1.0f, 0.5f, 0.0f, 0.0f};
    EXPECT_NEAR(GetParam()(test, reference, 2, 2, 0.0).psnr, 20.0 * std::log10(1.0 / 0.25), 1e-12);
    reference[0] = test[0] = -2.0f;
    EXPECT_NEAR(GetParam()(test, reference, 2, 2, 0.0).psnr, 20.0 * std::log10(2.0 / 0.25), 1e-12);
    reference[0] = test[0] = 3.0f;
    EXPECT_NEAR(GetParam()(test, reference, 2, 2, 0.0).psnr, 20.0 * std::log10(3.0 / 0.25), 1e-12);
}

TEST_P(ImageCompare, MatchingNonFiniteValuesAreSkipped) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<float> test = {nan, inf, -inf, 0.5f}, reference = {nan, -inf, inf, 0.0f};
    const ImageComparison r = GetParam()(test, reference, 2, 2, 0.0);
    EXPECT_EQ(r.meanError, 0.5 / 4);  // the skipped values still count in the denominator
    EXPECT_EQ(r.maxError, 0.5);
    EXPECT_EQ(r.differing, 1u);
}

TEST_P(ImageCompare, ANonFiniteMismatchMakesTheMaxErrorInfinite) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> test = {nan, 0.5f, 0.0f, 0.0f}, reference = {0.0f, 0.0f, 0.0f, 0.0f};
    const ImageComparison r = GetParam()(test, reference, 2, 2, 0.0);
    EXPECT_EQ(r.maxError, std::numeric_limits<double>::infinity());
    EXPECT_EQ(r.meanError, 0.5 / 4);
    EXPECT_EQ(r.differing, 1u);  // the NaN pixel itself is not counted
}

TEST_P(ImageCompare, AnEmptyImageComparesAsIdentical) {
    const ImageComparison r = GetParam()({}, {}, 0, 5, 0.0);
    EXPECT_EQ(r.pixels, 0u);
    EXPECT_EQ(r.meanError, 0.0);
    EXPECT_EQ(r.psnr, std::numeric_limits<double>::infinity());
    EXPECT_EQ(r.differing, 0u);
}

TEST_P(ImageCompare, ASizeMismatchNamesBothSizes) {
    const std::vector<float> fifteen(15, 0.0f), sixteen(16, 0.0f);
    const std::string message = errorOf([&] { GetParam()(fifteen, sixteen, 4, 4, 0.0); });
    EXPECT_NE(message.find("test image has 15 values"), std::string::npos) << message;
    EXPECT_NE(message.find("reference image 16"), std::string::npos) << message;
    EXPECT_NE(message.find("4x4 needs 16"), std::string::npos) << message;
    EXPECT_NE(errorOf([&] { GetParam()(sixteen, fifteen, 4, 4, 0.0); }).find("reference image 15"), std::string::npos);
    EXPECT_NE(errorOf([&] { GetParam()(sixteen, sixteen, 4, 3, 0.0); }).find("4x3 needs 12"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Paths, ImageCompare, ::testing::Values(&compareImages, &compareImagesDirect),
                         [](const ::testing::TestParamInfo<Compare>& info) {
                             return std::string(info.param == &compareImages ? "Library" : "Direct");
                         });

// ImageBufAlgo::compare against the direct computation on random images (fixed seeds): counts
// exactly, errors to ~1e-9 relative. 100x50 spans two of OIIO's 4096-pixel batches. Without
// OpenImageIO compareImages is the direct path and this only checks that it is deterministic.
TEST(ImageCompareAgreement, LibraryEqualsDirectOnRandomImages) {
    struct Case {
        std::uint32_t width, height, seed;
        float lo, hi;
    };
    for (const Case c : {Case{64, 48, 1, 0.0f, 1.0f}, Case{64, 48, 2, 0.0f, 1.0f}, Case{100, 50, 3, 0.0f, 1.0f},
                         Case{64, 48, 4, -1.0f, 1.5f}}) {
        const std::uint32_t n = c.width * c.height;
        const std::vector<float> reference = randomImage(n, c.seed, c.lo, c.hi);
        // A test image close to the reference: most pixels off by a little, some by a lot.
        std::vector<float> test = reference;
        const std::vector<float> noise = randomImage(n, c.seed + 100, -0.05f, 0.05f);
        const std::vector<float> jumps = randomImage(n, c.seed + 200, 0.0f, 1.0f);
        for (std::uint32_t i = 0; i < n; ++i) test[i] = jumps[i] < 0.05f ? jumps[i] * 20.0f : test[i] + noise[i];
        for (const double threshold : {0.0, 0.001, 0.01, 0.04, 0.1, 0.5}) {
            SCOPED_TRACE(::testing::Message() << c.width << "x" << c.height << " seed " << c.seed
                                              << " threshold " << threshold);
            const ImageComparison library = compareImages(test, reference, c.width, c.height, threshold);
            const ImageComparison direct = compareImagesDirect(test, reference, c.width, c.height, threshold);
            expectSame(library, direct);
            EXPECT_GT(direct.differing, 0u);
            if (threshold > 0.0) {
                EXPECT_LT(direct.differing, n);
            }
        }
    }
}

TEST(ImageCompareAgreement, LibraryEqualsDirectOnNonFiniteValues) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<std::pair<std::vector<float>, std::vector<float>>> cases = {
        {{nan, nan, 0.0f, 0.25f}, {0.0f, 0.0f, 0.0f, 0.0f}},  // NaN sums; maxError back to 0 after
        {{inf, inf, 0.0f, 0.25f}, {0.0f, 0.0f, 0.0f, 0.0f}},  // inf sums, inf peak: PSNR NaN
        {{nan, inf, 0.5f, 0.25f}, {inf, 0.0f, 0.0f, nan}},
        {{0.5f, nan, 0.25f, 0.0f}, {-inf, nan, inf, 0.0f}},
    };
    for (const auto& [test, reference] : cases)
        for (const double threshold : {0.0, 0.3})
            expectSame(compareImages(test, reference, 2, 2, threshold),
                       compareImagesDirect(test, reference, 2, 2, threshold));
}

}  // namespace
}  // namespace rtbench
