// Image-level accuracy: a shaded image against the reference render, as OpenImageIO's idiff
// compares them (ImageBufAlgo::compare, OIIO 2.4): mean and RMS error, PSNR, max error, and the
// pixels that differ by more than a threshold.
#pragma once
#include <cstdint>
#include <vector>

namespace rtbench {

// OIIO's definitions (src/libOpenImageIO/imagebufalgo_compare.cpp, checked against the installed
// 2.4.7 library). Per value, d = |test - reference| is taken in float, then summed in double:
struct ImageComparison {
    std::uint64_t pixels = 0;  // width * height
    // Sum of d / values, values = width * height * channels (one channel here): over channels too.
    double meanError = 0.0;
    double rmsError = 0.0;  // sqrt(sum of d^2 / values)
    // 20 log10(peak / rms), peak = max(1, largest |value| of either image): 20 log10(1 / rms) for
    // a [0, 1] range; +inf when rms == 0 (identical images).
    double psnr = 0.0;
    double maxError = 0.0;  // largest d
    // Pixels (not values) with d > float(threshold): strictly greater, so d == threshold passes;
    // a pixel with d == 0 never counts, even for a negative threshold. idiff's "fail" count (nfail).
    std::uint64_t differing = 0;
};
// Non-finite values, as OIIO: a NaN against a NaN, or an inf against an inf of either sign, adds
// nothing (but counts in the mean's denominator); another non-finite mismatch, while maxError is
// finite, sets maxError to +inf and adds nothing else; otherwise it is taken like any d (the
// means become NaN or inf, a NaN maxError is replaced by the next d) and counts as differing
// unless one side is NaN.
// An empty image (0 pixels) compares as identical: zero errors, PSNR +inf.

// One-channel float images of width x height pixels (row-major), values in [0, 1]. With
// OpenImageIO: ImageBufAlgo::compare; without it: compareImagesDirect. Throws rtbench::Error
// when either image does not hold width * height values, naming both sizes.
ImageComparison compareImages(const std::vector<float>& test, const std::vector<float>& reference,
                              std::uint32_t width, std::uint32_t height, double threshold);

// The direct computation of the definitions above (what a build without OpenImageIO uses, the
// same order of summation as OIIO), exposed so tests can check that both agree.
ImageComparison compareImagesDirect(const std::vector<float>& test, const std::vector<float>& reference,
                                    std::uint32_t width, std::uint32_t height, double threshold);

}  // namespace rtbench
