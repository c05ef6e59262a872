#include "image_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

#ifdef RTBENCH_WITH_OIIO
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#endif

namespace rtbench {

namespace {

// Both images must hold width * height values; returns that count.
std::uint64_t checkSizes(const std::vector<float>& test, const std::vector<float>& reference,
                         std::uint32_t width, std::uint32_t height) {
    const std::uint64_t pixels = std::uint64_t(width) * height;
    if (test.size() != pixels || reference.size() != pixels)
        throw Error("image comparison: the test image has " + std::to_string(test.size()) +
                    " values and the reference image " + std::to_string(reference.size()) + ", but " +
                    std::to_string(width) + "x" + std::to_string(height) + " needs " + std::to_string(pixels));
    return pixels;
}

ImageComparison emptyComparison() {
    ImageComparison result;
    result.psnr = std::numeric_limits<double>::infinity();
    return result;
}

}  // namespace

// OIIO 2.4's compare_() and compare_value() for one channel, failrelative = warnrelative = 0, in
// the same order and types: float differences, double sums per batch of 4096 pixels.
ImageComparison compareImagesDirect(const std::vector<float>& test, const std::vector<float>& reference,
                                    std::uint32_t width, std::uint32_t height, double threshold) {
    const std::uint64_t pixels = checkSizes(test, reference, width, height);
    if (pixels == 0) return emptyComparison();
    const float failThreshold = static_cast<float>(threshold);  // OIIO takes a float threshold
    const float failRelative = 0.0f;
    ImageComparison result;
    result.pixels = pixels;
    double totalError = 0.0, totalSquaredError = 0.0;
    float peak = 1.0f;  // PSNR's "max possible value", raised by any larger |value|
    constexpr std::uint64_t kBatch = 4096;
    for (std::uint64_t begin = 0; begin < pixels; begin += kBatch) {
        double batchError = 0.0, batchSquaredError = 0.0;
        const std::uint64_t end = std::min(pixels, begin + kBatch);
        for (std::uint64_t i = begin; i < end; ++i) {
            const float a = test[i], b = reference[i];
            if (!std::isfinite(a) || !std::isfinite(b)) {
                if (std::isnan(a) == std::isnan(b) && std::isinf(a) == std::isinf(b)) continue;
                if (std::isfinite(result.maxError)) {
                    result.maxError = std::numeric_limits<float>::infinity();
                    continue;
                }
            }
            const float aAbs = std::abs(a), bAbs = std::abs(b);
            const float meanAbs = static_cast<float>(aAbs * (1.0 - 0.5) + bAbs * 0.5);  // OIIO's lerp
            peak = std::max(peak, std::max(aAbs, bAbs));
            const double d = std::abs(a - b);  // in float, as OIIO
            const double relative = meanAbs > 0.0 ? d / meanAbs : 0.0;
            batchError += d;
            batchSquaredError += d * d;
            // !(x <= y): NaN differences count, as in OIIO.
            if (!(d <= result.maxError)) result.maxError = d;
            if (!(d <= failThreshold) && !(relative <= failRelative)) ++result.differing;
        }
        totalError += batchError;
        totalSquaredError += batchSquaredError;
    }
    const double values = static_cast<double>(pixels);  // one channel: values = pixels
    result.meanError = totalError / values;
    result.rmsError = std::sqrt(totalSquaredError / values);
    // +inf for identical images, as OIIO's log10(peak / 0) gives (without dividing by zero here).
    result.psnr = result.rmsError == 0.0 ? std::numeric_limits<double>::infinity()
                                         : 20.0 * std::log10(peak / result.rmsError);
    return result;
}

ImageComparison compareImages(const std::vector<float>& test, const std::vector<float>& reference,
                              std::uint32_t width, std::uint32_t height, double threshold) {
#ifdef RTBENCH_WITH_OIIO
    const std::uint64_t pixels = checkSizes(test, reference, width, height);
    if (pixels == 0) return emptyComparison();
    const OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 1, OIIO::TypeDesc::FLOAT);
    // Wrapped, not copied: compare only reads them.
    const OIIO::ImageBuf a(spec, const_cast<float*>(test.data())), b(spec, const_cast<float*>(reference.data()));
    const float t = static_cast<float>(threshold);
    const OIIO::ImageBufAlgo::CompareResults r = OIIO::ImageBufAlgo::compare(a, b, t, t);
    // Not r.error: OIIO 2.4 sets it whenever a pixel fails the threshold.
    if (a.has_error() || b.has_error())
        throw Error("image comparison: OpenImageIO: " + a.geterror() + b.geterror());
    ImageComparison result;
    result.pixels = pixels;
    result.meanError = r.meanerror;
    result.rmsError = r.rms_error;
    result.psnr = r.PSNR;
    result.maxError = r.maxerror;
    result.differing = r.nfail;
    return result;
#else
    return compareImagesDirect(test, reference, width, height, threshold);
#endif
}

}  // namespace rtbench
