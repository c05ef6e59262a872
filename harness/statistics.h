// Statistics of timing samples, as the benchmark tools researchers use report them (google/
// benchmark's compare.py, nvbench, hyperfine): centre and spread of every sample kept, a bootstrap
// confidence interval of the median, and a rank test for "is B slower than A".
#pragma once
#include <cstdint>
#include <vector>

namespace rtbench {

// The percentile bootstrap's resamples and the seed of its generator (std::mt19937_64): fixed, so
// the same samples always give the same interval.
constexpr int kBootstrapResamples = 2000;
constexpr std::uint64_t kBootstrapSeed = 20021101;  // Purcell et al., SIGGRAPH 2002

// Sample median: the middle value, or the mean of the two middle values.
double median(std::vector<double> samples);

struct SampleStats {
    std::size_t n = 0;
    double mean = 0.0, median = 0.0, min = 0.0, max = 0.0;
    double stddev = 0.0;  // sample standard deviation (n - 1); 0 for one sample
    double cv = 0.0;      // stddev / mean
    // 95% percentile-bootstrap interval of the median (kBootstrapResamples resamples); the
    // median itself for one sample.
    double ciLow = 0.0, ciHigh = 0.0;
    // Half the interval's width over the median: what adaptive repetitions drive down.
    double relativeHalfWidth() const { return median > 0 ? 0.5 * (ciHigh - ciLow) / median : 0.0; }
};

// All of the above; n = 0 leaves every field 0.
SampleStats summarize(const std::vector<double>& samples);

// 95% percentile-bootstrap interval of median(numerator) / median(denominator), each resampled
// on its own (independent samples), e.g. a speed ratio: Embree's time over the kernel's.
struct Interval {
    double low = 0.0, high = 0.0;
};
Interval bootstrapRatioOfMedians(const std::vector<double>& numerator, const std::vector<double>& denominator);

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
