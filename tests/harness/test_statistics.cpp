// Statistics of timing samples against values computed by hand, and the bootstrap against a
// second formulation (the distribution-free order-statistic interval of the median).
#include <gtest/gtest.h>

#include <cmath>

#include "harness/statistics.h"

namespace rtbench {
namespace {

TEST(Statistics, CentreAndSpreadOfFourSamples) {
    const SampleStats s = summarize({4.0, 1.0, 3.0, 2.0});
    EXPECT_EQ(s.n, 4u);
    EXPECT_DOUBLE_EQ(s.median, 2.5);  // the mean of the middle two
    EXPECT_DOUBLE_EQ(s.min, 1.0);
    EXPECT_DOUBLE_EQ(s.max, 4.0);
    EXPECT_DOUBLE_EQ(s.mean, 2.5);
    // (1.5^2 + 0.5^2 + 0.5^2 + 1.5^2) / 3 = 5/3
    EXPECT_NEAR(s.stddev, std::sqrt(5.0 / 3.0), 1e-12);
    EXPECT_NEAR(s.cv, std::sqrt(5.0 / 3.0) / 2.5, 1e-12);
    EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
}

TEST(Statistics, OneSampleHasNoSpreadAndAPointInterval) {
    const SampleStats s = summarize({7.0});
    EXPECT_DOUBLE_EQ(s.stddev, 0.0);
    EXPECT_DOUBLE_EQ(s.cv, 0.0);
    EXPECT_DOUBLE_EQ(s.ciLow, 7.0);
    EXPECT_DOUBLE_EQ(s.ciHigh, 7.0);
    EXPECT_DOUBLE_EQ(s.relativeHalfWidth(), 0.0);
    EXPECT_EQ(summarize({}).n, 0u);
}

TEST(Statistics, BootstrapIntervalOfTinySamplesSpansTheirRange) {
    // Two samples {1, 3}: a resample's median is 1, 2 or 3 with probability 1/4, 1/2, 1/4, so
    // the 2.5% and 97.5% points of 2000 resamples are 1 and 3.
    SampleStats s = summarize({3.0, 1.0});
    EXPECT_DOUBLE_EQ(s.ciLow, 1.0);
    EXPECT_DOUBLE_EQ(s.ciHigh, 3.0);
    // Three {1, 2, 3}: P(median = 1) = P(at least two 1s) = 7/27.
    s = summarize({2.0, 3.0, 1.0});
    EXPECT_DOUBLE_EQ(s.ciLow, 1.0);
    EXPECT_DOUBLE_EQ(s.ciHigh, 3.0);
    // Equal samples: no spread, a point.
    s = summarize({5.0, 5.0, 5.0, 5.0});
    EXPECT_DOUBLE_EQ(s.ciLow, 5.0);
    EXPECT_DOUBLE_EQ(s.ciHigh, 5.0);
}

TEST(Statistics, BootstrapIntervalAgreesWithTheOrderStatisticInterval) {
    // 101 distinct samples 1..101: the distribution-free 95% interval of the median is
    // [x(k), x(102 - k)] with k the largest rank where P(Binomial(101, 1/2) < k) <= 2.5%: k = 41,
    // so [41, 61]. The percentile bootstrap must land near it.
    std::vector<double> samples;
    for (int i = 101; i >= 1; --i) samples.push_back(double(i));
    const SampleStats s = summarize(samples);
    EXPECT_DOUBLE_EQ(s.median, 51.0);
    EXPECT_GE(s.ciLow, 38.0);
    EXPECT_LE(s.ciLow, 45.0);
    EXPECT_GE(s.ciHigh, 57.0);
    EXPECT_LE(s.ciHigh, 64.0);
    // The same samples give the same interval (a fixed seed).
    const SampleStats again = summarize(samples);
    EXPECT_EQ(again.ciLow, s.ciLow);
    EXPECT_EQ(again.ciHigh, s.ciHigh);
}

TEST(Statistics, RatioOfMediansInterval) {
    Interval r = bootstrapRatioOfMedians({10.0, 10.0, 10.0}, {5.0, 5.0});
    EXPECT_DOUBLE_EQ(r.low, 2.0);
    EXPECT_DOUBLE_EQ(r.high, 2.0);
    // Numerator {2, 4}: its resampled median is 2, 3 or 4; the denominator is always 1.
    r = bootstrapRatioOfMedians({2.0, 4.0}, {1.0});
    EXPECT_DOUBLE_EQ(r.low, 2.0);
    EXPECT_DOUBLE_EQ(r.high, 4.0);
}

TEST(Statistics, MannWhitneyExactPValuesByCounting) {
    // {1,2,3} against {4,5,6}: U = 0, the one arrangement of C(6,3) = 20 as extreme on each side,
    // so p = 2/20.
    MannWhitney t = mannWhitneyU({1, 2, 3}, {4, 5, 6});
    EXPECT_TRUE(t.exact);
    EXPECT_DOUBLE_EQ(t.u, 0.0);
    EXPECT_NEAR(t.p, 0.1, 1e-12);
    // Five against five, fully separated: 2 / C(10,5) = 2/252.
    t = mannWhitneyU({6, 7, 8, 9, 10}, {1, 2, 3, 4, 5});
    EXPECT_DOUBLE_EQ(t.u, 25.0);
    EXPECT_NEAR(t.p, 2.0 / 252.0, 1e-12);
    // Interleaved {1,3,5} and {2,4,6}: U = 0+1+2 = 3. U's distribution for 3 and 3 has counts
    // 1,1,2,3,3,3,3,2,1,1 for U = 0..9: P(U <= 3) = 7/20, P(U >= 3) = 16/20, so p = 14/20.
    t = mannWhitneyU({1, 3, 5}, {2, 4, 6});
    EXPECT_DOUBLE_EQ(t.u, 3.0);
    EXPECT_NEAR(t.p, 0.7, 1e-12);
    // U = 1 ({1,2,4} against {3,5,6}): P(U <= 1) = 2/20: p = 0.2.
    t = mannWhitneyU({1, 2, 4}, {3, 5, 6});
    EXPECT_DOUBLE_EQ(t.u, 1.0);
    EXPECT_NEAR(t.p, 0.2, 1e-12);
}

TEST(Statistics, MannWhitneyWithTiesUsesTheCorrectedNormalApproximation) {
    // a = {1,1,2}, b = {2,3,3}: U = 0.5 (the tie 2 = 2); ties of 2 at each of 3 values: sum of
    // t^3 - t = 18; N = 6, mn = 9: variance = 9/12 (7 - 18/30) = 4.8;
    // z = (|0.5 - 4.5| - 0.5) / sqrt(4.8) = 1.59752; p = erfc(z / sqrt 2) = 0.11014.
    const MannWhitney t = mannWhitneyU({1, 1, 2}, {2, 3, 3});
    EXPECT_FALSE(t.exact);
    EXPECT_DOUBLE_EQ(t.u, 0.5);
    EXPECT_NEAR(t.p, 0.11014, 1e-4);
    // All equal: no evidence.
    EXPECT_DOUBLE_EQ(mannWhitneyU({2, 2}, {2, 2, 2}).p, 1.0);
}

}  // namespace
}  // namespace rtbench
