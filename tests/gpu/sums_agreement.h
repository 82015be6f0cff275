// Two renders that must compute the same samples (another kernel variant, workgroup size, light
// sampling switch, ...): the same bits on a device that rounds as the host (device_rounding.h),
// else the same up to rounding. Rounding moves a sample in its last bits, and now and then turns a
// decision (a ray grazing an edge, a roulette draw at its threshold), so the rounding-tolerant
// form allows each pixel a relative difference of kPixelRelative and a few pixels more; another
// sample stream, or a term lost or doubled, moves nearly every lit pixel by its noise (per cent).
// The GPU test GpuRender.RoundingTolerantComparisonSeparatesRoundingFromOtherSamples measures both
// on lavapipe (docs/accuracy.md "Exact and rounding-tolerant comparisons").
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>

#include "device_rounding.h"
#include "render/renderer.h"

namespace vkp::test {

/// A pixel agrees when every channel of its sum and sum of squares (and its sample count) is
/// within this fraction of the larger of the two, plus kPixelFloor per sample.
inline constexpr double kPixelRelative = 1e-3;
inline constexpr double kPixelFloor = 1e-6;
/// At most this fraction of the pixels (and at least one) may disagree.
inline constexpr double kPixelsBeyondFraction = 0.005;
/// The image's total (every channel of every pixel) within this fraction.
inline constexpr double kTotalRelative = 1e-4;

struct SumsAgreement {
    std::size_t pixels = 0;
    std::size_t beyond = 0;    ///< pixels that do not agree (kPixelRelative)
    double totalRelative = 0;  ///< |total a - total b| / |total a| of the radiance sums
    bool identical = false;    ///< every bit of sum and sumSq equal

    /// Pixels that may disagree: kPixelsBeyondFraction of them, at least one.
    std::size_t allowedBeyond() const { return std::max<std::size_t>(1, std::size_t(kPixelsBeyondFraction * double(pixels))); }
    /// Within the rounding tolerance above (identical sums always are).
    bool withinRounding() const { return identical || (beyond <= allowedBeyond() && totalRelative <= kTotalRelative); }
};

/// Compares two renders' sums (same size: else nothing agrees).
inline SumsAgreement compareSums(const PixelSums& a, const PixelSums& b) {
    SumsAgreement g;
    g.pixels = a.sum.size() / 4;
    if (a.sum.size() != b.sum.size() || a.sumSq.size() != b.sumSq.size()) {
        g.beyond = g.pixels;
        g.totalRelative = INFINITY;
        return g;
    }
    g.identical = std::memcmp(a.sum.data(), b.sum.data(), a.sum.size() * sizeof(double)) == 0 &&
                  std::memcmp(a.sumSq.data(), b.sumSq.data(), a.sumSq.size() * sizeof(double)) == 0;
    double totalA = 0.0, totalB = 0.0;
    for (std::size_t i = 0; i < g.pixels; ++i) {
        const double n = std::max(a.sum[4 * i + 3], b.sum[4 * i + 3]);
        auto close = [n](double x, double y) {
            return std::abs(x - y) <= kPixelRelative * std::max(std::abs(x), std::abs(y)) + kPixelFloor * n;
        };
        bool agrees = a.sum[4 * i + 3] == b.sum[4 * i + 3];  // the sample counts
        for (int c = 0; c < 3; ++c) {
            const std::size_t k = 4 * i + c;
            agrees = agrees && close(a.sum[k], b.sum[k]) && close(a.sumSq[k], b.sumSq[k]);
            totalA += a.sum[4 * i + c];
            totalB += b.sum[4 * i + c];
        }
        g.beyond += !agrees;
    }
    g.totalRelative = totalA != 0.0 ? std::abs(totalA - totalB) / std::abs(totalA) : (totalB == 0.0 ? 0.0 : INFINITY);
    return g;
}

/// EXPECT_TRUE(sameSamples(dev, a, b, what)): bit-identical sums where `dev` rounds as the host,
/// else sums within the rounding tolerance (withinRounding).
inline ::testing::AssertionResult sameSamples(VulkanDevice& dev, const PixelSums& a, const PixelSums& b,
                                              const std::string& what) {
    const SumsAgreement g = compareSums(a, b);
    const bool exact = roundsLikeTheHost(dev);
    if (exact ? g.identical : g.withinRounding()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << what << ": " << (exact ? "sums not bit-identical" : "sums differ beyond rounding") << " (" << g.beyond
           << " of " << g.pixels << " pixels beyond " << kPixelRelative << " relative, total " << g.totalRelative
           << " relative); this device " << probeRounding(dev).describe();
}

}  // namespace vkp::test
