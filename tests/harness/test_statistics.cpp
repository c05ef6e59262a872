// Statistics of timing samples against values computed by hand (binomial sums, order statistics),
// and the interval's coverage against a simulation of a known distribution.
#include <gtest/gtest.h>


#include <cmath>
#include <numeric>
#include <random>

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
    ASSERT_TRUE(s.stddev && s.cv);
    EXPECT_NEAR(*s.stddev, std::sqrt(5.0 / 3.0), 1e-12);
    EXPECT_NEAR(*s.cv, std::sqrt(5.0 / 3.0) / 2.5, 1e-12);
    EXPECT_FALSE(s.ci) << "four samples: even [min, max] covers the median with 1 - 2/16 = 87.5% only";
    EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
}

TEST(Statistics, OneSampleHasNoSpreadAndNoInterval) {
    const SampleStats s = summarize({7.0});
    EXPECT_DOUBLE_EQ(s.median, 7.0);
    EXPECT_FALSE(s.stddev);
    EXPECT_FALSE(s.cv);
    EXPECT_FALSE(s.ci);
    EXPECT_TRUE(std::isinf(s.relativeHalfWidth())) << "adaptive timing must take more samples";
    EXPECT_EQ(summarize({}).n, 0u);
}

// Coverage of [x(k), x(n + 1 - k)]: 1 - 2 P(Binomial(n, 1/2) <= k - 1), by hand.
TEST(Statistics, OrderStatisticCoverageByHand) {
    EXPECT_DOUBLE_EQ(orderStatisticCoverage(3, 1), 1.0 - 2.0 / 8.0);    // 0.75
    EXPECT_DOUBLE_EQ(orderStatisticCoverage(5, 1), 1.0 - 2.0 / 32.0);   // 0.9375
    EXPECT_NEAR(orderStatisticCoverage(6, 1), 1.0 - 2.0 / 64.0, 1e-12);  // 0.96875
    // n = 10, k = 2: P(B <= 1) = (1 + 10) / 1024.
    EXPECT_NEAR(orderStatisticCoverage(10, 2), 1.0 - 22.0 / 1024.0, 1e-12);
    // n = 20, k = 6: P(B <= 5) = (1 + 20 + 190 + 1140 + 4845 + 15504) / 2^20 = 21700 / 1048576.
    EXPECT_NEAR(orderStatisticCoverage(20, 6), 1.0 - 2.0 * 21700.0 / 1048576.0, 1e-12);
    EXPECT_NEAR(orderStatisticCoverage(20, 7), 1.0 - 2.0 * (21700.0 + 38760.0) / 1048576.0, 1e-12);
    EXPECT_EQ(orderStatisticCoverage(4, 3), 0.0) << "beyond the middle: no interval";
}

// The ranks each n gets at 95%: the largest k whose coverage is at least 0.95.
TEST(Statistics, MedianIntervalRanksForThreeFiveTenTwenty) {
    auto ranks = [](int n) {
        std::vector<double> samples;
        for (int i = n; i >= 1; --i) samples.push_back(double(i));  // x(i) = i, given unsorted
        return medianInterval(samples);
    };
    EXPECT_FALSE(ranks(3)) << "0.75 < 0.95";
    EXPECT_FALSE(ranks(5)) << "0.9375 < 0.95";
    ASSERT_TRUE(ranks(6));
    EXPECT_EQ(ranks(6)->low, 1.0);
    EXPECT_EQ(ranks(6)->high, 6.0);
    // n = 10: k = 2 covers 0.9785; k = 3 covers 1 - 2 * 56 / 1024 = 0.8906.
    ASSERT_TRUE(ranks(10));
    EXPECT_EQ(ranks(10)->low, 2.0);
    EXPECT_EQ(ranks(10)->high, 9.0);
    // n = 20: k = 6 covers 0.9586; k = 7 covers 0.8847.
    ASSERT_TRUE(ranks(20));
    EXPECT_EQ(ranks(20)->low, 6.0);
    EXPECT_EQ(ranks(20)->high, 15.0);
    // n = 101: k = 41 (P(B <= 40) = 0.0218 <= 2.5%, P(B <= 41) = 0.0314): [41, 61].
    ASSERT_TRUE(ranks(101));
    EXPECT_EQ(ranks(101)->low, 41.0);
    EXPECT_EQ(ranks(101)->high, 61.0);
    // 97.5%: n = 6 no longer suffices (0.96875), n = 7 does with [min, max] (0.984).
    EXPECT_FALSE(medianInterval({1, 2, 3, 4, 5, 6}, 0.975));
    EXPECT_TRUE(medianInterval({1, 2, 3, 4, 5, 6, 7}, 0.975));
}

// The coverage holds, simulated: samples of a skewed distribution (exponential, median ln 2), the
// share of intervals that hold the true median at least 95% at n = 6, 10, 20 (the bootstrap's fell
// to about 80-88% here at n = 3-5).
TEST(Statistics, MedianIntervalCoverageHoldsInSimulation) {
    std::mt19937_64 generator(2002);
    std::exponential_distribution<double> draw(1.0);
    const double trueMedian = std::log(2.0);
    for (int n : {6, 10, 20}) {
        int held = 0;
        const int trials = 4000;
        for (int t = 0; t < trials; ++t) {
            std::vector<double> samples(n);
            for (double& v : samples) v = draw(generator);
            const std::optional<Interval> ci = medianInterval(samples);
            ASSERT_TRUE(ci);
            held += ci->low <= trueMedian && trueMedian <= ci->high;
        }
        // Expected coverage 0.96875, 0.9785, 0.9586; 4000 trials: sd about 0.003.
        EXPECT_GE(double(held) / trials, 0.945) << "n = " << n;
        EXPECT_NEAR(double(held) / trials, orderStatisticCoverage(n, n == 6 ? 1 : n == 10 ? 2 : 6), 0.012) << "n = " << n;
    }
}

TEST(Statistics, RatioOfMediansInterval) {
    // Equal samples: a point. Seven each: the 97.5% intervals are [min, max].
    std::optional<Interval> r = ratioOfMediansInterval(std::vector<double>(7, 10.0), std::vector<double>(7, 5.0));
    ASSERT_TRUE(r);
    EXPECT_DOUBLE_EQ(r->low, 2.0);
    EXPECT_DOUBLE_EQ(r->high, 2.0);
    // Numerator 1..7 over the constant 1: [1, 7] / [1, 1].
    r = ratioOfMediansInterval({7, 6, 5, 4, 3, 2, 1}, std::vector<double>(7, 1.0));
    ASSERT_TRUE(r);
    EXPECT_DOUBLE_EQ(r->low, 1.0);
    EXPECT_DOUBLE_EQ(r->high, 7.0);
    // Denominator 2..8: the far ends, 1/8 and 7/2.
    r = ratioOfMediansInterval({7, 6, 5, 4, 3, 2, 1}, {2, 3, 4, 5, 6, 7, 8});
    ASSERT_TRUE(r);
    EXPECT_DOUBLE_EQ(r->low, 1.0 / 8.0);
    EXPECT_DOUBLE_EQ(r->high, 7.0 / 2.0);
    EXPECT_FALSE(ratioOfMediansInterval({1, 2, 3, 4, 5, 6}, std::vector<double>(7, 1.0))) << "6 samples: no 97.5% interval";
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

// U from the ranks equals U counted pair by pair (x > y: 1, a tie: 1/2), ties included; and two
// samples of 100,000 (which a pass over every pair took 110 s for) give the hand-counted U.
TEST(Statistics, MannWhitneyUFromRanksEqualsThePairCount) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<double> a(1 + rng() % 30), b(1 + rng() % 30);
        for (double& v : a) v = double(rng() % 12);  // few values: many ties
        for (double& v : b) v = double(rng() % 12);
        double pairs = 0.0;
        for (double x : a)
            for (double y : b) pairs += x > y ? 1.0 : x == y ? 0.5 : 0.0;
        ASSERT_EQ(mannWhitneyU(a, b).u, pairs) << "trial " << trial;
    }
    // a = b = 0 .. N-1: N(N-1)/2 pairs with x > y and N ties, U = N^2 / 2.
    const std::size_t n = 100000;
    std::vector<double> same(n);
    std::iota(same.begin(), same.end(), 0.0);
    EXPECT_EQ(mannWhitneyU(same, same).u, double(n) * double(n) / 2.0);
}

// The exact distribution up to m n = 400, the normal approximation beyond: 20 against 20 fully
// apart is exact, p = 2 / C(40, 20) = 2 / 137,846,528,820; 20 against 21 is not exact, and its
// continuity-corrected z = (210 - 0.5) / sqrt(20 21 42 / 12) = 5.4642 gives p = 4.65e-8.
TEST(Statistics, MannWhitneyIsExactUpTo400PairsAndNormalBeyond) {
    std::vector<double> low(20), high(20), higher(21);
    std::iota(low.begin(), low.end(), 0.0);
    std::iota(high.begin(), high.end(), 100.0);
    std::iota(higher.begin(), higher.end(), 100.0);
    const MannWhitney exact = mannWhitneyU(low, high);
    EXPECT_TRUE(exact.exact);
    EXPECT_DOUBLE_EQ(exact.u, 0.0);
    EXPECT_NEAR(exact.p / (2.0 / 137846528820.0), 1.0, 1e-9);
    const MannWhitney normal = mannWhitneyU(low, higher);
    EXPECT_FALSE(normal.exact);
    EXPECT_DOUBLE_EQ(normal.u, 0.0);
    EXPECT_NEAR(normal.p / std::erfc(((210.0 - 0.5) / std::sqrt(20.0 * 21.0 * 42.0 / 12.0)) / std::sqrt(2.0)), 1.0, 1e-9);
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
