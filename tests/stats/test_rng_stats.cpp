// Statistical tests of shaders/shared/rng.h (compiled as C++): the per-sample counter-based
// stream must be uniform on [0,1), never return 1.0, depend only on (pixel, sample, seed), and be
// independent enough between successive draws of a path and between neighbouring pixels, samples
// and seeds. Uniformity and independence are tested with chi-square tests on 1D, 2D and 3D
// histograms, lag correlations (sqrt(n) r ~ N(0,1)) and the balance of every output bit.
// Significance: each test runs at statsAlpha() (stat_suite.h: Sidak-corrected so the whole stats
// suite falsely fails with probability <= 1% for correct code), two-sided (alpha/2 per tail): a
// fit that is too good is as suspicious in a random number generator as one that is too bad (a
// bare LCG, without PCG's output permutation, passes the one-sided 1D and within-path tests here
// but fails the two-sided ones). Keys and seeds are fixed, so the outcome is deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>
#include <vector>

#include "shared/rng.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;

constexpr std::uint32_t kWidth = 512;  // image width used to define "vertical neighbour"
constexpr std::uint32_t kSeed = 0x5eed1234u;

/// The first n draws of the stream of (pixel, sample, seed).
std::vector<float> stream(std::uint32_t pixel, std::uint32_t sample, std::uint32_t seed, int n) {
    std::uint32_t s = gpu::rngInit(pixel, sample, seed);
    std::vector<float> out(static_cast<size_t>(n));
    for (float& v : out) v = gpu::rngNext(s);
    return out;
}

/// Chi-square test of values in [0,1)^dim (flattened tuples) against the uniform density on a
/// grid of `bins` cells per dimension.
Chi2Result uniformityTest(const std::vector<float>& tuples, int dim, int bins) {
    size_t cells = 1;
    for (int d = 0; d < dim; ++d) cells *= static_cast<size_t>(bins);
    std::vector<double> observed(cells, 0.0);
    size_t n = tuples.size() / static_cast<size_t>(dim);
    for (size_t i = 0; i < n; ++i) {
        size_t c = 0;
        for (int d = 0; d < dim; ++d) {
            float v = tuples[i * static_cast<size_t>(dim) + static_cast<size_t>(d)];
            c = c * static_cast<size_t>(bins) +
                static_cast<size_t>(std::min(int(v * bins), bins - 1));
        }
        observed[c] += 1.0;
    }
    return chi2Test(observed, std::vector<double>(cells, double(n) / double(cells)));
}

/// Lag correlation test: Pearson r of the pairs; under independence sqrt(n) r ~ N(0,1), so
/// n r^2 is chi-square with one degree of freedom.
Chi2Result correlationTest(const std::vector<float>& pairs) {
    size_t n = pairs.size() / 2;
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (size_t i = 0; i < n; ++i) {
        double x = pairs[2 * i], y = pairs[2 * i + 1];
        sx += x;
        sy += y;
        sxx += x * x;
        syy += y * y;
        sxy += x * y;
    }
    double cov = sxy / n - (sx / n) * (sy / n);
    double r = cov / std::sqrt((sxx / n - (sx / n) * (sx / n)) * (syy / n - (sy / n) * (sy / n)));
    Chi2Result res;
    res.statistic = double(n) * r * r;
    res.dof = 1;
    res.pValue = chi2PValue(res.statistic, 1);
    res.message = "lag correlation r = " + std::to_string(r) +
                  ", n r^2 = " + std::to_string(res.statistic) +
                  ", p = " + std::to_string(res.pValue);
    return res;
}

// ---- Determinism and range -------------------------------------------------------------------

TEST(RngStats, StreamDependsOnlyOnPixelSampleSeed) {
    // The same (pixel, sample) drawn in two different "dispatch splits" and orders.
    std::vector<std::vector<float>> a, b;
    for (std::uint32_t s = 0; s < 8; ++s)
        for (std::uint32_t p = 0; p < 64; ++p) a.push_back(stream(p, s, kSeed, 16));
    for (std::uint32_t s = 8; s-- > 0;)
        for (std::uint32_t p = 64; p-- > 0;) b.push_back(stream(p, s, kSeed, 16));
    for (std::uint32_t s = 0; s < 8; ++s)
        for (std::uint32_t p = 0; p < 64; ++p) EXPECT_EQ(a[s * 64 + p], b[(7 - s) * 64 + (63 - p)]);
    // Distinct pixels never share an initial state for a fixed (sample, seed): pcgHash is a
    // bijection.
    std::set<std::uint32_t> states;
    for (std::uint32_t p = 0; p < 1u << 16; ++p) states.insert(gpu::rngInit(p, 3u, kSeed));
    EXPECT_EQ(states.size(), size_t{1} << 16);
    EXPECT_NE(stream(0, 0, kSeed, 4), stream(0, 0, kSeed + 1, 4));
}

/// Multiplicative inverse of an odd number modulo 2^32 (Newton's iteration doubles the correct
/// bits).
std::uint32_t inverseMod32(std::uint32_t a) {
    std::uint32_t x = a;
    for (int i = 0; i < 5; ++i) x *= 2u - a * x;
    return x;
}

/// The state whose next draw (rngNextUint) is `out`: inverts the RXS-M-XS output and the LCG step.
std::uint32_t stateBefore(std::uint32_t out) {
    std::uint32_t word = out ^ (out >> 22u);
    std::uint32_t x = word * inverseMod32(277803737u);
    std::uint32_t r = (x >> 28u) + 4u;  // the top 4 bits survive the xorshift
    std::uint32_t s = x;
    for (int i = 0; i < 8; ++i) s = x ^ (s >> r);
    return (s - 2891336453u) * inverseMod32(747796405u);
}

TEST(RngStats, DrawsAreInHalfOpenUnitInterval) {
    std::uint32_t s = stateBefore(0xffffffffu);
    std::uint32_t copy = s;
    ASSERT_EQ(gpu::rngNextUint(copy), 0xffffffffu);
    float top = gpu::rngNext(s);
    EXPECT_LT(top, 1.0f);
    EXPECT_EQ(top, 1.0f - 1.0f / 16777216.0f);
    std::uint32_t z = stateBefore(0u);
    EXPECT_EQ(gpu::rngNext(z), 0.0f);
    std::uint32_t st = gpu::rngInit(1, 2, 3);
    for (int i = 0; i < 1000000; ++i) {
        float v = gpu::rngNext(st);
        ASSERT_TRUE(v >= 0.0f && v < 1.0f);
    }
}

// ---- Uniformity and independence ---------------------------------------------------------------

TEST(RngStats, UniformIn1D) {
    std::vector<float> v;
    for (std::uint32_t p = 0; p < 100000; ++p) {
        auto s = stream(p, 0, kSeed, 10);
        v.insert(v.end(), s.begin(), s.end());
    }
    EXPECT_TRUE(passesChi2TwoSided(uniformityTest(v, 1, 1000)));
}

TEST(RngStats, SuccessiveDrawsOfAPathAreIndependent) {
    std::vector<float> pairs, triples, lag;
    for (std::uint32_t p = 0; p < 40000; ++p) {
        auto s = stream(p, 7, kSeed, 12);
        for (int k = 0; k + 1 < 12; k += 2)
            pairs.insert(pairs.end(), {s[size_t(k)], s[size_t(k) + 1]});
        for (int k = 0; k + 2 < 12; k += 3)
            triples.insert(triples.end(), {s[size_t(k)], s[size_t(k) + 1], s[size_t(k) + 2]});
        for (int k = 0; k + 1 < 12; ++k) lag.insert(lag.end(), {s[size_t(k)], s[size_t(k) + 1]});
    }
    EXPECT_TRUE(passesChi2TwoSided(uniformityTest(pairs, 2, 32)));    // 240k pairs, 1024 cells
    EXPECT_TRUE(passesChi2TwoSided(uniformityTest(triples, 3, 16)));  // 160k triples, 4096 cells
    EXPECT_TRUE(passesChi2TwoSided(correlationTest(lag)));
}

/// Pairs (draw k of key a, draw k of key b) for many neighbouring keys.
std::vector<float> neighbourPairs(
    const std::function<std::pair<std::vector<float>, std::vector<float>>(std::uint32_t)>& keys,
    std::uint32_t count) {
    std::vector<float> pairs;
    for (std::uint32_t i = 0; i < count; ++i) {
        auto [a, b] = keys(i);
        for (size_t k = 0; k < a.size(); ++k) pairs.insert(pairs.end(), {a[k], b[k]});
    }
    return pairs;
}

TEST(RngStats, NeighbouringPixelsAreIndependent) {
    auto horizontal = neighbourPairs(
        [](std::uint32_t i) {
            return std::make_pair(stream(i, 0, kSeed, 4), stream(i + 1, 0, kSeed, 4));
        },
        60000);
    auto vertical = neighbourPairs(
        [](std::uint32_t i) {
            return std::make_pair(stream(i, 5, kSeed, 4), stream(i + kWidth, 5, kSeed, 4));
        },
        60000);
    EXPECT_TRUE(passesChi2TwoSided(uniformityTest(horizontal, 2, 32)));
    EXPECT_TRUE(passesChi2TwoSided(uniformityTest(vertical, 2, 32)));
    EXPECT_TRUE(passesChi2TwoSided(correlationTest(horizontal)));
}

TEST(RngStats, NeighbouringSamplesAndSeedsAreIndependent) {
    auto samples = neighbourPairs(
        [](std::uint32_t i) {
            return std::make_pair(stream(i / 64, i % 64, kSeed, 4),
                                  stream(i / 64, i % 64 + 1, kSeed, 4));
        },
        60000);
    auto seeds = neighbourPairs(
        [](std::uint32_t i) {
            return std::make_pair(stream(i, 0, kSeed, 4), stream(i, 0, kSeed + 1, 4));
        },
        60000);
    EXPECT_TRUE(passesChi2TwoSided(uniformityTest(samples, 2, 32)));
    EXPECT_TRUE(passesChi2TwoSided(uniformityTest(seeds, 2, 32)));
    EXPECT_TRUE(passesChi2TwoSided(correlationTest(samples)));
}

// Every bit of rngNextUint is set half of the time: sum over the 32 bits of z^2 ~ chi2(32).
TEST(RngStats, OutputBitsAreBalanced) {
    std::vector<double> ones(32, 0.0);
    const int n = 200000;
    for (std::uint32_t p = 0; p < n / 4; ++p) {
        std::uint32_t s = gpu::rngInit(p, 1, kSeed);
        for (int k = 0; k < 4; ++k) {
            std::uint32_t v = gpu::rngNextUint(s);
            for (int b = 0; b < 32; ++b) ones[size_t(b)] += (v >> b) & 1u;
        }
    }
    Chi2Result r;
    for (double o : ones) r.statistic += (o - 0.5 * n) * (o - 0.5 * n) / (0.25 * n);
    r.dof = 32;
    r.pValue = chi2PValue(r.statistic, r.dof);
    r.message = "bit balance chi2 = " + std::to_string(r.statistic) +
                " (32 dof), p = " + std::to_string(r.pValue);
    EXPECT_TRUE(passesChi2TwoSided(r));
}

}  // namespace
