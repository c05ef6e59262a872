#include "statistics.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

namespace rtbench {

namespace {

// The q-quantile of sorted values, linearly interpolated (R's type 7, numpy's default).
double quantile(const std::vector<double>& sorted, double q) {
    const double position = q * double(sorted.size() - 1);
    const std::size_t below = std::size_t(std::floor(position));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    return sorted[below] + (position - double(below)) * (sorted[above] - sorted[below]);
}

double sortedMedian(const std::vector<double>& sorted) {
    const std::size_t n = sorted.size();
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

// The median of a resample of `samples` (with replacement), in `scratch`.
double resampledMedian(const std::vector<double>& samples, std::mt19937_64& generator, std::vector<double>& scratch) {
    std::uniform_int_distribution<std::size_t> pick(0, samples.size() - 1);
    scratch.resize(samples.size());
    for (double& v : scratch) v = samples[pick(generator)];
    std::sort(scratch.begin(), scratch.end());
    return sortedMedian(scratch);
}

Interval percentileInterval(std::vector<double> statistics) {
    std::sort(statistics.begin(), statistics.end());
    return {quantile(statistics, 0.025), quantile(statistics, 0.975)};
}

}  // namespace

double median(std::vector<double> samples) {
    if (samples.empty()) return 0.0;
    std::sort(samples.begin(), samples.end());
    return sortedMedian(samples);
}

SampleStats summarize(const std::vector<double>& samples) {
    SampleStats s;
    s.n = samples.size();
    if (samples.empty()) return s;
    std::vector<double> sorted = samples;
    std::sort(sorted.begin(), sorted.end());
    s.median = sortedMedian(sorted);
    s.min = sorted.front();
    s.max = sorted.back();
    s.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / double(s.n);
    if (s.n > 1) {
        double squares = 0.0;
        for (double v : sorted) squares += (v - s.mean) * (v - s.mean);
        s.stddev = std::sqrt(squares / double(s.n - 1));
    }
    s.cv = s.mean > 0 ? s.stddev / s.mean : 0.0;
    std::mt19937_64 generator(kBootstrapSeed);
    std::vector<double> medians(kBootstrapResamples), scratch;
    for (double& m : medians) m = resampledMedian(samples, generator, scratch);
    const Interval ci = percentileInterval(std::move(medians));
    s.ciLow = ci.low;
    s.ciHigh = ci.high;
    return s;
}

Interval bootstrapRatioOfMedians(const std::vector<double>& numerator, const std::vector<double>& denominator) {
    if (numerator.empty() || denominator.empty()) return {};
    std::mt19937_64 generator(kBootstrapSeed);
    std::vector<double> ratios(kBootstrapResamples), scratch;
    for (double& r : ratios) {
        const double top = resampledMedian(numerator, generator, scratch);
        const double bottom = resampledMedian(denominator, generator, scratch);
        r = bottom > 0 ? top / bottom : 0.0;
    }
    return percentileInterval(std::move(ratios));
}

MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b) {
    MannWhitney result;
    const std::size_t m = a.size(), n = b.size();
    if (m == 0 || n == 0) return result;
    // U of a: pairs (x in a, y in b) with x > y, a tie counting 1/2.
    for (double x : a)
        for (double y : b) result.u += x > y ? 1.0 : x == y ? 0.5 : 0.0;
    // Ties across the pooled samples.
    std::map<double, std::size_t> counts;
    for (double v : a) ++counts[v];
    for (double v : b) ++counts[v];
    double tieTerm = 0.0;
    for (const auto& [value, t] : counts) tieTerm += double(t) * double(t) * double(t) - double(t);
    const double mn = double(m) * double(n);
    if (tieTerm == 0.0 && m * n <= 400) {
        // Exact: f(i, j, k) arrangements of i a's and j b's with U = k. The largest of them is an
        // a (it exceeds all j b's: U gains j) or a b (U gains 0).
        const std::size_t K = m * n;
        std::vector<std::vector<std::vector<double>>> f(m + 1, std::vector<std::vector<double>>(n + 1));
        for (std::size_t i = 0; i <= m; ++i)
            for (std::size_t j = 0; j <= n; ++j) {
                f[i][j].assign(i * j + 1, 0.0);
                if (i == 0 || j == 0) {
                    f[i][j][0] = 1.0;
                    continue;
                }
                for (std::size_t k = 0; k <= i * j; ++k) {
                    double ways = 0.0;
                    if (k >= j && k - j <= (i - 1) * j) ways += f[i - 1][j][k - j];
                    if (k <= i * (j - 1)) ways += f[i][j - 1][k];
                    f[i][j][k] = ways;
                }
            }
        const std::vector<double>& dist = f[m][n];
        const double total = std::accumulate(dist.begin(), dist.end(), 0.0);
        const std::size_t u = std::size_t(result.u);
        double below = 0.0, above = 0.0;  // P(U <= u), P(U >= u)
        for (std::size_t k = 0; k <= K; ++k) {
            if (k <= u) below += dist[k];
            if (k >= u) above += dist[k];
        }
        result.p = std::min(1.0, 2.0 * std::min(below, above) / total);
        result.exact = true;
        return result;
    }
    const double N = double(m + n);
    const double variance = mn / 12.0 * ((N + 1.0) - tieTerm / (N * (N - 1.0)));
    if (variance <= 0.0) return result;  // every value equal: no evidence of a difference
    const double z = std::max(0.0, std::abs(result.u - mn / 2.0) - 0.5) / std::sqrt(variance);
    result.p = std::min(1.0, std::erfc(z / std::sqrt(2.0)));
    return result;
}

}  // namespace rtbench
