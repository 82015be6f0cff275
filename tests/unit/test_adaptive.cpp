// Adaptive sampling's decisions (host/render/adaptive.h): the error estimate, the 3x3 rule, the
// packed pixel list, and a simulation showing that judging a pixel by a separate decision stream
// keeps its mean unbiased where judging it by its own image samples does not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/adaptive.h"

namespace vkp {
namespace {

TEST(Adaptive, StreamsSplitOneSampleInFour) {
    EXPECT_FALSE(isDecisionSample(0));
    EXPECT_TRUE(isDecisionSample(3));
    EXPECT_TRUE(isDecisionSample(7));
    std::uint32_t image = 0;
    for (std::uint32_t i = 0; i < 101; ++i) image += !isDecisionSample(i);
    EXPECT_EQ(imageSamplesBefore(101), image);
    EXPECT_EQ(imageSamplesBefore(64), 48u);
}

TEST(Adaptive, ErrorEstimateIsTheRelativeStandardErrorOfTheImageMean) {
    // Decision samples 1, 3 (twice each) in every channel: mean 2, sample variance 4/3.
    const float sum[4] = {8, 8, 8, 4}, sq[4] = {20, 20, 20, 0};
    const double expected = std::sqrt((4.0 / 3.0) / 100.0 / (4.0 + 0.01));
    EXPECT_NEAR(estimatedRelativeError(sum, sq, 100), expected, 1e-12);
    const float few[4] = {1, 1, 1, 3};
    EXPECT_TRUE(std::isinf(estimatedRelativeError(few, sq, 100)));  // < 4 decision samples: not judged
}

/// Decision sums of a pixel whose decision samples are all `v` (n of them): error 0 for any v.
void setConstant(std::vector<float>& d, std::size_t i, float v, float n) {
    for (int c = 0; c < 3; ++c) {
        d[8 * i + c] = v * n;
        d[8 * i + 4 + c] = v * v * n;
    }
    d[8 * i + 3] = n;
}

TEST(Adaptive, APixelStopsOnlyWithItsWholeNeighbourhood) {
    const std::uint32_t w = 7, h = 5;
    std::vector<float> d(8 * w * h);
    for (std::size_t i = 0; i < w * h; ++i) setConstant(d, i, 0.5f, 16);
    // Pixel (3, 2) is noisy: samples 0 and 1.
    const std::size_t noisy = 2 * w + 3;
    for (int c = 0; c < 3; ++c) {
        d[8 * noisy + c] = 8;
        d[8 * noisy + 4 + c] = 8;
    }
    std::vector<std::uint8_t> active(w * h, 1);
    EXPECT_EQ(updateActivePixels(active, d, w, h, 0.01, 64), 9u);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x)
            EXPECT_EQ(active[y * w + x], (x >= 2 && x <= 4 && y >= 1 && y <= 3) ? 1 : 0) << x << "," << y;
    // Stopped pixels never restart, even when their decision sums would say "noisy" now.
    for (int c = 0; c < 3; ++c) d[8 * 0 + c] = 1000;
    EXPECT_EQ(updateActivePixels(active, d, w, h, 0.01, 64), 9u);
    EXPECT_EQ(active[0], 0);
    // Once the noisy pixel converges, its neighbourhood stops with it.
    setConstant(d, noisy, 0.5f, 16);
    EXPECT_EQ(updateActivePixels(active, d, w, h, 0.01, 64), 0u);
}

TEST(Adaptive, ListIsTileOrderedAndHoldsExactlyTheActivePixels) {
    const std::uint32_t w = 20, h = 11;
    std::vector<std::uint8_t> active(w * h, 0);
    std::mt19937 rng(3);
    std::size_t count = 0;
    for (auto& a : active) count += (a = rng() % 3 == 0);
    const auto list = activePixelList(active, w, h);
    ASSERT_EQ(list.size(), count);
    auto tileKey = [&](std::uint32_t p) {
        const std::uint32_t x = p % w, y = p / w;
        return ((y / 8) * ((w + 7) / 8) + x / 8) * 64 + (y % 8) * 8 + x % 8;
    };
    for (std::size_t i = 0; i < list.size(); ++i) {
        EXPECT_TRUE(active[list[i]]);
        if (i) EXPECT_LT(tileKey(list[i - 1]), tileKey(list[i]));
    }
}

// One pixel whose samples are 50 with probability 0.002 and 0.1 otherwise (mean 0.1998): a
// firefly pixel. 20,000 independent copies, each rendered adaptively (first decision at 64
// samples, then every 16, at most 1024, threshold 0.05) under two protocols:
//  - split (what vkpath does): decisions from the decision stream, image = the other samples;
//  - own: decisions and image from the same samples (every sample in both).
// Split: the average of the pixel estimates is within 4 standard errors of the true mean (a
// false failure has probability 6e-5 for correct code; fixed seed). Own: biased low by more than
// 10 standard errors (a pixel that has not met a firefly yet looks converged and stops dark).
TEST(Adaptive, DecisionStreamKeepsTheMeanUnbiased) {
    constexpr double kP = 0.002, kHi = 50.0, kLo = 0.1, kMu = kP * kHi + (1 - kP) * kLo;
    constexpr int kPixels = 20000;
    constexpr std::uint32_t kMin = 64, kStep = 16, kMax = 1024;
    std::mt19937_64 rng(12345);
    std::bernoulli_distribution firefly(kP);
    double est[2][2] = {{0, 0}, {0, 0}};  // [protocol][sum, sum of squares]
    double meanSpp[2] = {0, 0};
    for (int own = 0; own < 2; ++own) {
        for (int p = 0; p < kPixels; ++p) {
            float dsum[4] = {0, 0, 0, 0}, dsq[4] = {0, 0, 0, 0};
            double isum = 0;
            std::uint32_t in = 0, i = 0;
            while (i < kMax) {
                const float x = float(firefly(rng) ? kHi : kLo);
                const bool decision = own || isDecisionSample(i);
                const bool image = own || !isDecisionSample(i);
                if (decision)
                    for (int c = 0; c < 4; ++c) {
                        dsum[c] += c < 3 ? x : 1.0f;
                        dsq[c] += c < 3 ? x * x : 0.0f;
                    }
                if (image) {
                    isum += x;
                    ++in;
                }
                ++i;
                if (i >= kMin && (i - kMin) % kStep == 0 &&
                    estimatedRelativeError(dsum, dsq, own ? i : imageSamplesBefore(i)) <= 0.05)
                    break;
            }
            const double e = isum / in;
            est[own][0] += e;
            est[own][1] += e * e;
            meanSpp[own] += i;
        }
        const double m = est[own][0] / kPixels;
        const double se = std::sqrt((est[own][1] / kPixels - m * m) / (kPixels - 1));
        const double z = (m - kMu) / se;
        std::printf("%s: mean %.5f (true %.5f), z = %.2f, mean spp %.1f\n", own ? "own samples" : "decision stream", m,
                    kMu, z, meanSpp[own] / kPixels);
        if (own)
            EXPECT_LT(z, -10.0) << "judging pixels by their own samples should be visibly biased here";
        else
            EXPECT_LT(std::abs(z), 4.0);
    }
}

}  // namespace
}  // namespace vkp
