// Statistics of timing samples, as the benchmark tools researchers use report them (google/
// benchmark's compare.py, nvbench, hyperfine): centre and spread of every sample kept, a
// distribution-free confidence interval of the median, and a rank test for "is B slower than A".
#pragma once
#include <cstddef>
#include <optional>
#include <vector>

namespace rtbench {

// Sample median: the middle value, or the mean of the two middle values.
double median(std::vector<double> samples);

struct Interval {
    double low = 0.0, high = 0.0;
};

// The probability that [x(k), x(n + 1 - k)] (1-based order statistics of n samples) holds the
// median of the distribution they were drawn from: 1 - 2 P(Binomial(n, 1/2) <= k - 1), whatever
// the distribution (continuous). 0 when k is 0 or beyond n / 2 + 1/2.
double orderStatisticCoverage(std::size_t n, std::size_t k);

// The distribution-free interval of the median (Conover, Practical Nonparametric Statistics §3.2):
// [x(k), x(n + 1 - k)] with k the largest rank whose coverage is at least `confidence`. None when
// even [min, max] covers less: fewer than 6 samples at 95%, fewer than 7 at 97.5%.
std::optional<Interval> medianInterval(const std::vector<double>& samples, double confidence = 0.95);

// Half the interval's width over the median it brackets (0 for a median of 0 or less): how
// tightly a median is pinned, what the noise guard and adaptive repetitions judge.
double relativeHalfWidth(const Interval& ci, double median);

struct SampleStats {
    std::size_t n = 0;
    double mean = 0.0, median = 0.0, min = 0.0, max = 0.0;
    std::optional<double> stddev;  // sample standard deviation (n - 1); none for one sample
    std::optional<double> cv;      // stddev / mean; none for one sample
    std::optional<Interval> ci;    // medianInterval at 95%; none below 6 samples
    // Half the interval's width over the median: what adaptive repetitions drive down (infinite
    // without an interval: more samples needed).
    double relativeHalfWidth() const;
};

// All of the above; n = 0 leaves every field 0 or none.
SampleStats summarize(const std::vector<double>& samples);

// An interval of median(numerator) / median(denominator), e.g. a speed ratio, Embree's time over
// the kernel's: each median's 97.5% interval, and the ratio of their far ends. Both hold with 97.5%
// each, so both at once with at least 95% (Bonferroni; no independence assumed). None when either
// has fewer than 7 samples.
std::optional<Interval> ratioOfMediansInterval(const std::vector<double>& numerator,
                                               const std::vector<double>& denominator);

// Two-sided Mann-Whitney U test of two independent samples (what compare.py reports): U of `a`
// (pairs a > b, ties counting one half) and the p-value of "a and b come from one distribution",
// exact (the permutation distribution, by counting) when neither sample has ties and
// a.size() * b.size() <= 400, else the normal approximation with tie correction and continuity
// correction.
struct MannWhitney {
    double u = 0.0;
    double p = 1.0;
    bool exact = false;
};
MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace rtbench
