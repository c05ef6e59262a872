#include "statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

namespace rtbench {

namespace {

double sortedMedian(const std::vector<double>& sorted) {
    const std::size_t n = sorted.size();
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

// P(Binomial(n, 1/2) = i), from logarithms (2^-n underflows beyond n = 1074).
double binomialHalf(std::size_t n, std::size_t i) {
    return std::exp(std::lgamma(double(n) + 1.0) - std::lgamma(double(i) + 1.0) - std::lgamma(double(n - i) + 1.0) -
                    double(n) * std::log(2.0));
}

}  // namespace

double median(std::vector<double> samples) {
    if (samples.empty()) return 0.0;
    std::sort(samples.begin(), samples.end());
    return sortedMedian(samples);
}

double orderStatisticCoverage(std::size_t n, std::size_t k) {
    if (k == 0 || 2 * k > n + 1) return 0.0;
    double below = 0.0;  // P(B <= k - 1)
    for (std::size_t i = 0; i < k; ++i) below += binomialHalf(n, i);
    return std::max(0.0, 1.0 - 2.0 * below);
}

std::optional<Interval> medianInterval(const std::vector<double>& samples, double confidence) {
    const std::size_t n = samples.size();
    // The coverage falls as k grows: the largest k whose coverage holds, adding P(B = k - 1) a step.
    std::size_t k = 0;
    double below = 0.0;
    while (2 * (k + 1) <= n + 1) {
        below += binomialHalf(n, k);
        if (1.0 - 2.0 * below < confidence) break;
        ++k;
    }
    if (k == 0) return std::nullopt;
    std::vector<double> sorted = samples;
    std::sort(sorted.begin(), sorted.end());
    return Interval{sorted[k - 1], sorted[n - k]};
}

double relativeHalfWidth(const Interval& ci, double median) { return median > 0 ? 0.5 * (ci.high - ci.low) / median : 0.0; }

double SampleStats::relativeHalfWidth() const {
    if (!ci) return std::numeric_limits<double>::infinity();
    return rtbench::relativeHalfWidth(*ci, median);
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
        s.cv = s.mean > 0 ? *s.stddev / s.mean : 0.0;
    }
    s.ci = medianInterval(sorted);
    return s;
}

std::optional<Interval> ratioOfMediansInterval(const std::vector<double>& numerator,
                                               const std::vector<double>& denominator) {
    const std::optional<Interval> top = medianInterval(numerator, 0.975), bottom = medianInterval(denominator, 0.975);
    if (!top || !bottom || bottom->low <= 0.0) return std::nullopt;
    return Interval{top->low / bottom->high, top->high / bottom->low};
}

MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b) {
    MannWhitney result;
    const std::size_t m = a.size(), n = b.size();
    if (m == 0 || n == 0) return result;
    // U of a, the pairs (x in a, y in b) with x > y, a tie counting 1/2, from the ranks of the
    // pooled samples (a run of ties shares its mean rank): U = R_a - m(m + 1)/2, in
    // O((m + n) log(m + n)) rather than a pass over every pair (100,000 samples a side). Every
    // term is a multiple of 1/2 below 2^53: exact in double.
    std::vector<std::pair<double, bool>> pooled;  // (value, from a)
    pooled.reserve(m + n);
    for (double v : a) pooled.emplace_back(v, true);
    for (double v : b) pooled.emplace_back(v, false);
    std::sort(pooled.begin(), pooled.end());
    double rankSumA = 0.0, tieTerm = 0.0;
    for (std::size_t i = 0; i < pooled.size();) {
        std::size_t j = i, fromA = 0;
        for (; j < pooled.size() && pooled[j].first == pooled[i].first; ++j) fromA += pooled[j].second;
        const double t = double(j - i);
        rankSumA += double(fromA) * (double(i + 1) + double(j)) / 2.0;  // ranks i+1 .. j, their mean
        tieTerm += t * t * t - t;
        i = j;
    }
    result.u = rankSumA - double(m) * double(m + 1) / 2.0;
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
