// The denoiser (host/render/denoiser.h, shaders/denoise.comp) on synthetic inputs with a closed
// form (denoise_scenes.h): unchanged where there is no noise, no blur across albedo, normal and
// depth edges, no halo around a small bright region, convergence to the raw image as spp grows, a
// 10x lower relMSE with the checker texture kept, bands bit-identical to one pass, bad inputs
// refused; each for both filters (DenoiseFilter: non-local means first, the default, and the
// a-trous filter alone).
//
// Statistics: every noisy input is drawn from a fixed seed, so a given build always passes or
// always fails; each statistical check's comment gives the probability that a correct denoiser
// fails it for an unlucky seed (the checks compare with margins of several standard deviations).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "core/errors.h"
#include "denoise_scenes.h"
#include "gpu_env.h"
#include "render/denoiser.h"

namespace vkp::test {
namespace {

/// Every property test runs for both filters (DenoiseFilter): the default, non-local means as the
/// first level, and the a-trous filter alone.
class GpuDenoise : public ::testing::TestWithParam<DenoiseFilter> {
protected:
    bool nlm() const { return GetParam() == DenoiseFilter::NonLocalMeans; }
    /// The default options of the filter under test.
    DenoiseOptions options() const {
        DenoiseOptions o;
        o.filter = GetParam();
        return o;
    }
    /// The filter under test with its defaults, one per filter for the whole run.
    Denoiser& denoiser(VulkanDevice& dev) const {
        static std::unique_ptr<Denoiser> d[2];
        std::unique_ptr<Denoiser>& slot = d[nlm() ? 0 : 1];
        if (!slot) slot = std::make_unique<Denoiser>(dev, options());
        return *slot;
    }
};

std::string filterName(const ::testing::TestParamInfo<DenoiseFilter>& info) {
    return info.param == DenoiseFilter::NonLocalMeans ? "NonLocalMeans" : "ATrous";
}

DenoiseInput inputOf(const CleanScene& s, const NoisyRender& r) {
    return DenoiseInput{&r.color, &r.variance, &s.albedo, &s.normal, &s.depth};
}

float luminance(const Image& img, std::uint32_t x, std::uint32_t y) {
    return 0.2126f * img.at(x, y, 0) + 0.7152f * img.at(x, y, 1) + 0.0722f * img.at(x, y, 2);
}

TEST_P(GpuDenoise, NoiseFreeConstantImageUnchanged) {
    VKP_REQUIRE_DEVICE(dev);
    // 70 x 45: neither a multiple of the 8x8 workgroup.
    const HalfSide side{{0.5f, 0.4f, 0.3f}, 1.2f, {0.0f, 0.0f, 1.0f}, 3.0f};
    const CleanScene s = twoHalves(70, 45, side, side);
    const NoisyRender r{s.radiance, Image(70, 45)};
    const Image out = denoiser(dev).run(inputOf(s, r));
    double worst = 0.0;
    for (std::size_t i = 0; i < out.rgb.size(); ++i)
        worst = std::max(worst, std::abs(double(out.rgb[i]) - r.color.rgb[i]) / r.color.rgb[i]);
    std::printf("  constant image: largest relative change %.3g\n", worst);
    // A few float roundings of a local linear fit through equal values (measured: 5.0e-7 for the
    // a-trous filter alone, 2.2e-6 with non-local means first). Non-local means sums 81 taps at
    // offsets up to 4 pixels, the a-trous level 25 at up to 2, and the plane's slope terms cancel
    // (e . (1, u1, u2) = 1) in sums that grow with both: about 4x the roundings.
    EXPECT_LE(worst, nlm() ? 4e-6 : 1e-6);
}

TEST_P(GpuDenoise, ZeroVarianceReturnsTheInput) {
    VKP_REQUIRE_DEVICE(dev);
    // The whole piecewise scene (gradients, texture, edges, sky) with variance 0: every tap that
    // differs from the centre weighs 0, so each pixel is the mean of equal values: itself.
    const CleanScene s = piecewiseScene(96, 80);
    const NoisyRender r{s.radiance, Image(96, 80)};
    const Image out = denoiser(dev).run(inputOf(s, r));
    double worst = 0.0;
    for (std::size_t i = 0; i < out.rgb.size(); ++i)
        worst = std::max(worst, std::abs(double(out.rgb[i]) - r.color.rgb[i]) / (std::abs(r.color.rgb[i]) + 1e-6));
    std::printf("  zero variance: largest relative change %.3g\n", worst);
    EXPECT_LE(worst, 1e-6);
}

/// The mean over the rows of column x, channel c.
double columnMean(const Image& img, std::uint32_t x, int c) {
    double sum = 0.0;
    for (std::uint32_t y = 0; y < img.height; ++y) sum += img.at(x, y, c);
    return sum / img.height;
}

/// Denoises a two-halves scene at `spp` and checks that the two columns on each side of the edge
/// keep their side's value: |column mean - reference| <= 5 standard deviations of a raw column
/// mean (sigma_pixel / sqrt(rows)). A denoised column mean is a weighted mean of raw pixels of
/// many rows and columns, so its noise is at most that; false-failure probability <= 5.7e-7 per
/// check, 12 checks per scene: < 1e-5.
void expectEdgeKept(Denoiser& denoiser, const char* what, const HalfSide& left, const HalfSide& right, std::uint32_t spp,
                    std::uint32_t seed) {
    const std::uint32_t w = 64, h = 256;
    const CleanScene s = twoHalves(w, h, left, right);
    const NoisyRender r = renderNoisy(s, spp, seed);
    const Image out = denoiser.run(inputOf(s, r));
    double worst = 0.0;
    for (std::uint32_t x : {w / 2 - 2, w / 2 - 1, w / 2, w / 2 + 1})
        for (int c = 0; c < 3; ++c) {
            const double ref = s.radiance.at(x, 0, c);
            const double sigmaColumn = kNoisePerSample * ref / std::sqrt(double(spp)) / std::sqrt(double(h));
            const double z = (columnMean(out, x, c) - ref) / sigmaColumn;
            worst = std::max(worst, std::abs(z));
            EXPECT_LE(std::abs(z), 5.0) << what << ": column " << x << " channel " << c << ": denoised mean "
                                        << columnMean(out, x, c) << ", reference " << ref << " (raw "
                                        << columnMean(r.color, x, c) << ")";
        }
    std::printf("  %s at %u spp: largest |column mean - reference| %.2f sigma of a raw column mean\n", what, spp, worst);
}

TEST_P(GpuDenoise, NoBlurAcrossAlbedoEdge) {
    VKP_REQUIRE_DEVICE(dev);
    // Same irradiance, normal and depth; albedo 0.8 grey against a dark blue.
    expectEdgeKept(denoiser(dev), "albedo edge", {{0.8f, 0.8f, 0.8f}, 1.0f, {0, 0, 1}, 4.0f},
                   {{0.05f, 0.1f, 0.3f}, 1.0f, {0, 0, 1}, 4.0f}, 4, 11);
}

TEST_P(GpuDenoise, NoBlurAcrossNormalEdge) {
    VKP_REQUIRE_DEVICE(dev);
    // A fold: two planes at 90 degrees, depth continuous, same albedo, irradiance 1 and 0.4.
    const float k = 1.0f / std::sqrt(2.0f);
    expectEdgeKept(denoiser(dev), "normal edge", {{0.6f, 0.6f, 0.6f}, 1.0f, {k, 0, k}, 4.0f},
                   {{0.6f, 0.6f, 0.6f}, 0.4f, {-k, 0, k}, 4.0f}, 4, 12);
}

TEST_P(GpuDenoise, NoBlurAcrossDepthEdge) {
    VKP_REQUIRE_DEVICE(dev);
    // Same normal and albedo, one face 3 units behind the other, irradiance 1 and 0.4.
    expectEdgeKept(denoiser(dev), "depth edge", {{0.6f, 0.6f, 0.6f}, 1.0f, {0, 0, 1}, 2.0f},
                   {{0.6f, 0.6f, 0.6f}, 0.4f, {0, 0, 1}, 5.0f}, 4, 13);
}

TEST_P(GpuDenoise, ShortMeanNormalsOfRandomDirectionDoNotStopTheFilter) {
    VKP_REQUIRE_DEVICE(dev);
    // A pixel whose samples found surfaces facing many ways, or mostly none (fog inside a glass
    // sphere, seen through its refraction), has a short mean normal of random direction. Made
    // unit, such normals would stop the filter between any two pixels (sigmaNormal 128); below
    // minNormalLength they count as no normal, and pixels without one mix. A constant scene
    // whose normals are all of length 0.2 and random direction: the default denoiser must take
    // off at least 80 % of the relMSE, while the same filter with every normal trusted
    // (minNormalLength 0, the rule before) takes off under 30 %.
    const std::uint32_t w = 64, h = 64;
    const HalfSide side{{0.5f, 0.5f, 0.5f}, 1.0f, {0.0f, 0.0f, 1.0f}, 4.0f};
    CleanScene s = twoHalves(w, h, side, side);
    GaussianSource g(7);
    for (std::size_t i = 0; i < s.normal.pixelCount(); ++i) {
        glm::dvec3 d(g.next(), g.next(), g.next());
        d = 0.2 * glm::normalize(d);
        for (int c = 0; c < 3; ++c) s.normal.rgb[3 * i + std::size_t(c)] = float(d[c]);
    }
    const NoisyRender r = renderNoisy(s, 4, 21);
    DenoiseOptions trusting = options();
    trusting.minNormalLength = 0.0f;
    Denoiser old(dev, trusting);
    const double raw = relMse(r.color, s.radiance), kept = relMse(denoiser(dev).run(inputOf(s, r)), s.radiance),
                 stopped = relMse(old.run(inputOf(s, r)), s.radiance);
    std::printf("  short random normals: relMSE raw %.4g, denoised %.4g, with every normal trusted %.4g\n", raw, kept,
                stopped);
    // 4096 pixels x 3 channels: the relMSE's own relative spread is ~2 %, far inside the margins.
    // Over 8 seeds (renderNoisy's seed + 1000 k, k = 0..7) the trusting filter left 0.78-0.80 of
    // the raw error (a-trous) and 0.57-0.61 (non-local means, whose 81 taps include more whose
    // random normals happen to agree); the default 0.006-0.008 and 0.021-0.026.
    EXPECT_LT(kept, 0.2 * raw);
    EXPECT_GT(stopped, (nlm() ? 0.45 : 0.7) * raw);
}

TEST_P(GpuDenoise, NoisyMeanNormalsOfMixedPixelsDoNotStopTheFilter) {
    VKP_REQUIRE_DEVICE(dev);
    // Every pixel straddles a fold (depth of field, a small object): each of its 16 samples finds
    // the face (0,0,1) or (1,0,0) at even odds, so its mean normal is (0.5, 0, 0.5) plus the
    // noise of 16 draws: its direction's standard deviation is 14 degrees (normalNoise). At
    // SVGF's sigmaNormal 128 two such normals mix only where their draws nearly agree (20 degrees
    // apart weigh 1e-3). A constant scene: with the samples given, the default filter must take
    // off at least 95 % of the relMSE; and at sigmaNormal 128, where the rule matters most, the
    // noise-aware exponent must leave at most a quarter of what the same filter leaves with every
    // normal taken as exact (normalNoise 0, SVGF's rule). (The default sigmaNormal, 16, mixes such
    // normals by itself: 20 degrees apart weigh 0.37.)
    const std::uint32_t w = 64, h = 64, spp = 16;
    const HalfSide side{{0.5f, 0.5f, 0.5f}, 1.0f, {0.0f, 0.0f, 1.0f}, 4.0f};
    CleanScene s = twoHalves(w, h, side, side);
    std::mt19937 rng(5);
    for (std::size_t i = 0; i < s.normal.pixelCount(); ++i) {
        glm::vec3 sum(0.0f);
        for (std::uint32_t k = 0; k < spp; ++k) sum += (rng() & 1u) ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
        for (int c = 0; c < 3; ++c) s.normal.rgb[3 * i + std::size_t(c)] = sum[c] / float(spp);
    }
    const std::vector<float> samples(s.normal.pixelCount(), float(spp));
    const NoisyRender r = renderNoisy(s, spp, 22);
    DenoiseInput in = inputOf(s, r);
    in.samples = &samples;
    DenoiseOptions aware = options();
    aware.sigmaNormal = 128.0f;
    DenoiseOptions exact = aware;
    exact.normalNoise = 0.0f;
    Denoiser awareFilter(dev, aware), svgf(dev, exact);
    const double raw = relMse(r.color, s.radiance), byDefault = relMse(denoiser(dev).run(in), s.radiance),
                 kept = relMse(awareFilter.run(in), s.radiance), stopped = relMse(svgf.run(in), s.radiance);
    std::printf("  noisy mixed normals: relMSE raw %.4g, denoised %.4g; at sigmaNormal 128 %.4g, with every normal exact %.4g\n",
                raw, byDefault, kept, stopped);
    // 4096 pixels x 3 channels: the relMSE's own relative spread is ~2 %, far inside the margins.
    // Over 8 seeds (as above) kept / stopped was 0.09-0.11 (a-trous) and 0.25-0.29 (non-local
    // means: its patch weights already mix some pixels whose exact normals differ).
    EXPECT_LT(byDefault, 0.05 * raw);
    EXPECT_LT(kept, 0.05 * raw);
    EXPECT_LT(kept, (nlm() ? 0.4 : 0.25) * stopped);
}

TEST_P(GpuDenoise, AGradientAgainstAnEdgeKeepsItsValue) {
    VKP_REQUIRE_DEVICE(dev);
    // The left half's irradiance rises linearly towards a normal edge at x = 48, so its windows
    // near the edge reach only leftwards, into lower values: a weighted mean (SVGF's level) is
    // pulled down there; the local linear fit (DenoiseOptions::localLinearRidge) is not.
    const std::uint32_t w = 96, h = 4096;
    CleanScene s = twoHalves(w, h, HalfSide{{0.6f, 0.6f, 0.6f}, 1.0f, {0.0f, 0.0f, 1.0f}, 3.0f},
                             HalfSide{{0.6f, 0.6f, 0.6f}, 1.0f, {1.0f, 0.0f, 0.0f}, 3.0f});
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w / 2; ++x)
            for (int c = 0; c < 3; ++c) s.radiance.at(x, y, c) = 0.6f * (0.2f + 4.8f * float(x) / float(w / 2));
    const NoisyRender r = renderNoisy(s, 16, 11);
    DenoiseOptions meanOnly = options();
    meanOnly.localLinearRidge = -1.0f;
    Denoiser weightedMean(dev, meanOnly);
    const Image fit = denoiser(dev).run(inputOf(s, r)), mean = weightedMean.run(inputOf(s, r));
    // Bias: the three columns beside the edge, averaged over the rows, against the clean ramp.
    const auto bias = [&](const Image& img) {
        double sum = 0.0;
        for (std::uint32_t y = 0; y < h; ++y)
            for (std::uint32_t x = w / 2 - 3; x < w / 2; ++x) sum += luminance(img, x, y) - luminance(s.radiance, x, y);
        return sum / (3.0 * h);
    };
    const double bFit = bias(fit), bMean = bias(mean), bRaw = bias(r.color);
    std::printf("  ramp against an edge: bias of the fit %.4f, of the weighted mean %.4f, raw %.4f (values 1.5-2.9)\n", bFit, bMean,
                bRaw);
    // Each average is over 3 x 4096 pixels of relative noise 1/4 (16 spp, values about 2.9 beside
    // the edge): its standard deviation is about 0.006 (raw), less once denoised. The weighted
    // mean's bias is checked to be beyond -0.08 and the fit's to be a third of it or less. Over 8 seeds (renderNoisy's seed + 1000 k,
    // k = 0..7) the weighted mean's bias was -0.120 to -0.135 (a-trous) and -0.105 to -0.122
    // (non-local means), the fit's share of it 0.04-0.19 (mean 0.11, sd 0.05) and 0.06-0.20
    // (mean 0.13, sd 0.05): the 1/3 is 4 sd away, so an unlucky seed fails a correct denoiser
    // with probability of about 2e-5 (the sd itself estimated from 8 seeds: 1e-4 at worst).
    EXPECT_LT(bMean, -0.08);
    EXPECT_LT(std::abs(bFit), std::abs(bMean) / 3.0);
}

/// The background of the firefly and bright-region tests: a 48x48 constant scene rendered at 16 spp.
struct Background {
    CleanScene s;
    NoisyRender r;
    float luminance = 0.0f;  ///< the clean scene's
};
Background constantAt16Spp(std::uint32_t seed) {
    const HalfSide side{{0.5f, 0.4f, 0.3f}, 1.0f, {0.0f, 0.0f, 1.0f}, 3.0f};
    Background b{twoHalves(48, 48, side, side), {}, 0.0f};
    b.r = renderNoisy(b.s, 16, seed);
    b.luminance = luminance(b.s.radiance, 24, 24);
    return b;
}

/// The largest luminance of `out` and of `raw` over the square [lo, hi]^2 of pixels, leaving out
/// those `skip(x, y)` names.
template <class Skip>
std::pair<float, float> brightest(const Image& out, const Image& raw, std::uint32_t lo, std::uint32_t hi, Skip skip) {
    float o = 0.0f, r = 0.0f;
    for (std::uint32_t y = lo; y <= hi; ++y)
        for (std::uint32_t x = lo; x <= hi; ++x) {
            if (skip(x, y)) continue;
            o = std::max(o, luminance(out, x, y));
            r = std::max(r, luminance(raw, x, y));
        }
    return {o, r};
}

/// A pixel of a constant scene made a firefly at 16 spp: one of its 16 samples carries `extra`
/// more radiance in every channel (mean + extra / 16, variance of the mean (extra / 16)^2, as
/// for 15 equal samples and one bright one). `sure`: instead a converged highlight, the same
/// mean with the variance of its neighbours.
void addFirefly(NoisyRender& r, std::uint32_t x, std::uint32_t y, float extra, bool sure) {
    for (int c = 0; c < 3; ++c) {
        const float neighbour = r.variance.at(x + 1, y, c);
        r.color.at(x, y, c) += extra / 16.0f;
        r.variance.at(x, y, c) = sure ? neighbour : (extra / 16.0f) * (extra / 16.0f);
    }
}

TEST_P(GpuDenoise, AFireflyTheFilterCannotReachIsBoundedAConvergedHighlightKept) {
    VKP_REQUIRE_DEVICE(dev);
    // 48x48 constant scene at 16 spp (seed 31) with two one-pixel facets whose normal differs
    // from every neighbour's by 90 degrees, so the filter's normal weight keeps each to itself
    // (as in final-scene-book2, whose fireflies sit among the edges of small boxes): a firefly
    // of 200x the radiance in one sample at (16, 24), and a converged highlight of the same mean
    // (its variance its neighbours') at (32, 24).
    Background b = constantAt16Spp(31);  // the noise depends on the radiance alone, not the normals
    CleanScene& s = b.s;
    NoisyRender& r = b.r;
    for (std::uint32_t x : {16u, 32u}) {
        s.normal.at(x, 24, 0) = 1.0f;
        s.normal.at(x, 24, 2) = 0.0f;
    }
    const float background = b.luminance, extra = 200.0f;
    addFirefly(r, 16, 24, extra * s.radiance.at(16, 24, 1), false);
    addFirefly(r, 32, 24, extra * s.radiance.at(32, 24, 1), true);
    const Image out = denoiser(dev).run(inputOf(s, r));
    DenoiseOptions off = options();
    off.fireflyBound = 0.0f;
    const Image kept = Denoiser(dev, off).run(inputOf(s, r));
    const float fly = luminance(out, 16, 24), flyOff = luminance(kept, 16, 24), sure = luminance(out, 32, 24);
    std::printf("  background %.3f: firefly %.3f raw, %.3f denoised, %.3f without the bound; sure highlight %.3f raw, %.3f denoised\n",
                background, luminance(r.color, 16, 24), fly, flyOff, luminance(r.color, 32, 24), sure);
    // The firefly's raw mean is 13.5x the background. Its neighbours' values plus 2 of their
    // standard deviations (16-spp noise of 25 % per pixel) bound it at about 1.5-2x; the largest
    // of 8 such bounds passes 2.5x only if a neighbour's noise is 4 sigma high: probability
    // < 8 x 3.2e-5 = 2.6e-4 for an unlucky seed. Without the bound it stays (> 10x).
    EXPECT_LT(fly, 2.5f * background);
    EXPECT_GT(flyOff, 10.0f * background);
    // The sure highlight is detail: kept within 1 % of its raw value.
    EXPECT_NEAR(sure, luminance(r.color, 32, 24), 0.01f * luminance(r.color, 32, 24));
}

TEST_P(GpuDenoise, ASmallBrightRegionDoesNotLeakIntoItsDarkNeighbours) {
    VKP_REQUIRE_DEVICE(dev);
    // env-sky's sun seen through its glass sphere at 16 spp, made synthetic: a 48x48 constant
    // scene (seed 37) with a 3x3 block around (24, 24) at 1000x the background (variance of the
    // mean (value / 8)^2), and next to it, single samples of the sun:
    // pixels where one of 16 samples saw it (addFirefly: mean + 1000/16 x the background,
    // variance of the mean (1000/16 x the background)^2).
    // Every pixel shares normal, depth and albedo, so only the luminance edge-stop can keep the
    // sun's light out of the dark pixels between them. With the 3x3 mean of the variances alone
    // (SVGF eq. 5) the single samples' variance widened that stop for their dark neighbours,
    // which took the sun's light in: env-sky's halo, 10 pixels with 76 % of its denoised error.
    Background b = constantAt16Spp(37);
    const CleanScene& s = b.s;
    NoisyRender& r = b.r;
    for (std::uint32_t y = 23; y <= 25; ++y)
        for (std::uint32_t x = 23; x <= 25; ++x)
            for (int c = 0; c < 3; ++c) {
                const float value = 1000.0f * s.radiance.at(x, y, c);
                r.color.at(x, y, c) = value;
                r.variance.at(x, y, c) = (value / 8.0f) * (value / 8.0f);
            }
    const std::uint32_t samples[][2] = {{22, 22}, {24, 22}, {26, 23}, {22, 25}, {25, 26}, {26, 26}};
    for (const auto& p : samples) addFirefly(r, p[0], p[1], 1000.0f * s.radiance.at(p[0], p[1], 1), false);
    const Image out = denoiser(dev).run(inputOf(s, r));
    // The unchanged pixels within 3 of the block's centre.
    const auto [dark, darkRaw] = brightest(out, r.color, 21, 27, [&](std::uint32_t x, std::uint32_t y) {
        bool changed = x >= 23 && x <= 25 && y >= 23 && y <= 25;
        for (const auto& p : samples) changed |= p[0] == x && p[1] == y;
        return changed;
    });
    std::printf("  background %.3f: the dark pixels around the sun at most %.3f raw, %.3f denoised\n", b.luminance, darkRaw, dark);
    // Those pixels carry 16-spp noise of 25 % (the largest of 34 raw is 1.45x with this seed);
    // the filter lowers it (1.12x by default, 1.02x by the a-trous filter alone), so 1.5x is
    // passed only if it takes the sun's light in (the mean of the variances alone gave 2.09x).
    EXPECT_LT(dark, 1.5f * b.luminance);
}

TEST_P(GpuDenoise, ANoisyBrightRegionDoesNotLeakIntoItsDarkNeighbours) {
    VKP_REQUIRE_DEVICE(dev);
    // The sun seen through env-sky's glass sphere as the samples see it: a 5x5 block around
    // (24, 24) of a 48x48 constant scene at 16 spp (seed 41) whose pixels each saw the sun (1000x
    // the background) in k of their 16 samples, k drawn from Binomial(16, 1/4) (an mt19937 bit
    // pair per sample), their variance of the mean the samples' own. Such pixels are as noisy as
    // they are bright, so the patches of a dark pixel and of its bright neighbours are alike within
    // those neighbours' variance: non-local means' patch weight alone let env-sky's dark pixels
    // beside the sun take its light in. Only the brighter-tap term (nlmBrighterSigma) keeps it out.
    Background b = constantAt16Spp(41);
    const CleanScene& s = b.s;
    NoisyRender& r = b.r;
    std::mt19937 rng(41);
    for (std::uint32_t y = 22; y <= 26; ++y)
        for (std::uint32_t x = 22; x <= 26; ++x) {
            std::uint32_t k = 0;
            for (int sample = 0; sample < 16; ++sample) k += (rng() >> 30) == 0u ? 1u : 0u;
            const double f = k / 16.0;
            for (int c = 0; c < 3; ++c) {
                const double sun = 1000.0 * s.radiance.at(x, y, c);
                r.color.at(x, y, c) += float(sun * f);
                r.variance.at(x, y, c) += float(sun * sun * f * (1.0 - f) / 15.0);  // sample variance / 16
            }
        }
    const Image out = denoiser(dev).run(inputOf(s, r));
    // The ring of pixels 1-3 outside the block.
    const auto [dark, darkRaw] = brightest(out, r.color, 19, 29, [](std::uint32_t x, std::uint32_t y) {
        return x >= 22 && x <= 26 && y >= 22 && y <= 26;
    });
    std::printf("  background %.3f: the dark pixels around the noisy sun at most %.3f raw, %.3f denoised\n", b.luminance, darkRaw,
                dark);
    // 1.5x the background is passed only if the sun's light comes in: without the brighter-tap
    // term non-local means gave 6.1x. Over 12 seeds (41 + 1000 k, k = 0..11) the ring's maximum
    // was 1.46-1.81x raw, 1.00-1.22x denoised by default (mean 1.08x, standard deviation 0.06x)
    // and 1.00-1.05x by the a-trous filter alone: the bound is more than 4 standard deviations
    // away (false failure < 1e-4).
    EXPECT_LT(dark, 1.5f * b.luminance);
}

TEST_P(GpuDenoise, ConvergesToTheRawImage) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t w = 128, h = 128;
    const CleanScene s = piecewiseScene(w, h);
    double previous = 0.0;
    for (std::uint32_t spp : {4u, 64u, 4096u}) {
        const NoisyRender r = renderNoisy(s, spp, 100 + spp);
        const Image out = denoiser(dev).run(inputOf(s, r));
        // Relative change: mean |denoised - raw| / mean |raw|; and per value in units of the
        // noise's standard deviation (the sky, noise free, apart).
        double diff = 0.0, mag = 0.0, inSigma = 0.0;
        std::size_t noisy = 0, beyond = 0;
        for (std::size_t i = 0; i < out.rgb.size(); ++i) {
            const double d = std::abs(double(out.rgb[i]) - r.color.rgb[i]);
            diff += d;
            mag += std::abs(r.color.rgb[i]);
            if (s.noiseFree[i / 3]) continue;
            const double sigma = kNoisePerSample * s.radiance.rgb[i] / std::sqrt(double(spp));
            inSigma += d / sigma;
            beyond += d > 4.0 * sigma ? 1 : 0;
            ++noisy;
        }
        const double rel = diff / mag;
        std::printf("  %5u spp: mean |denoised - raw| / mean |raw| = %.4g, mean |denoised - raw| = %.3f sigma, "
                    "%.3g%% beyond 4 sigma\n",
                    spp, rel, inSigma / double(noisy), 100.0 * double(beyond) / double(noisy));
        // Each 16x more samples: the noise the filter removes shrinks 4x; ask for 2x.
        if (previous > 0.0) EXPECT_LT(rel, previous / 2.0) << spp << " spp";
        previous = rel;
        if (spp == 4096u) {
            // The output is the input within the noise: removing the noise alone gives a mean of
            // 0.80 sigma (the mean |Gaussian|) and 6e-3 % beyond 4 sigma; the filter leaves part
            // of it (measured over 8 seeds: 0.71-0.72 sigma, at most 0.0024 %, both filters;
            // docs/accuracy.md). Over 3 x 109 x 128 noisy
            // values the mean's own standard deviation is ~0.002 sigma: the 1.0 threshold is
            // >100 of them away, the 0.5 % one ~13 binomial deviations (false failure < 1e-12).
            EXPECT_LT(inSigma / double(noisy), 1.0);
            EXPECT_LT(double(beyond) / double(noisy), 0.005);
        }
    }
}

/// Texture statistics of the checker floor (docs/design.md "Denoiser"): the variance of the
/// luminance over the floor, and the mean |luminance step| across the checker's vertical edges.
struct FloorStats {
    double variance = 0.0, edgeContrast = 0.0;
};
FloorStats floorStats(const Image& img) {
    const PiecewiseLayout L = piecewiseLayout(img.width, img.height);
    FloorStats st;
    double sum = 0.0, sumSq = 0.0, edges = 0.0;
    std::size_t n = 0, ne = 0;
    for (std::uint32_t y = L.floorBegin; y < img.height; ++y)
        for (std::uint32_t x = 0; x < img.width; ++x) {
            const double l = luminance(img, x, y);
            sum += l;
            sumSq += l * l;
            ++n;
            if (x + 1 < img.width && (x + 1) % kCheckerSize == 0) {
                edges += std::abs(double(luminance(img, x + 1, y)) - l);
                ++ne;
            }
        }
    st.variance = sumSq / double(n) - (sum / double(n)) * (sum / double(n));
    st.edgeContrast = edges / double(ne);
    return st;
}

TEST_P(GpuDenoise, PiecewiseSmoothSceneTenfoldAndTextureKept) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t w = 160, h = 160;
    const CleanScene s = piecewiseScene(w, h);
    const FloorStats clean = floorStats(s.radiance);
    for (std::uint32_t spp : {16u, 64u}) {
        const NoisyRender r = renderNoisy(s, spp, 7 + spp);
        const Image out = denoiser(dev).run(inputOf(s, r));
        const double raw = relMse(r.color, s.radiance), den = relMse(out, s.radiance);
        const FloorStats st = floorStats(out);
        std::printf("  %u spp: relMSE raw %.4g, denoised %.4g (%.1fx lower); floor variance %.4f (clean %.4f, %+.2f%%), "
                    "checker edge contrast %.4f (clean %.4f, %+.2f%%)\n",
                    spp, raw, den, raw / den, st.variance, clean.variance, 100.0 * (st.variance / clean.variance - 1.0),
                    st.edgeContrast, clean.edgeContrast, 100.0 * (st.edgeContrast / clean.edgeContrast - 1.0));
        // The ratio, over 8 seeds (renderNoisy's seed + 1000 k, k = 0..7): a-trous 45-50x at 16
        // spp, 41-48x at 64 spp; non-local means first 30-31x and 30-34x (relative standard
        // deviation ~4%); a failure needs it 3x off (false failure < 1e-12).
        EXPECT_GE(raw / den, 10.0) << spp << " spp";
        // Over the same 8 seeds the floor's variance came out 2.9% to 0.1% below the clean one
        // (mean -1.4%, standard deviation 0.8%; both filters alike), the edge contrast -1.3% to
        // -0.1%: the 5% bounds are more than 4 standard deviations away (false failure < 1e-5).
        EXPECT_NEAR(st.variance / clean.variance, 1.0, 0.05) << spp << " spp";
        EXPECT_NEAR(st.edgeContrast / clean.edgeContrast, 1.0, 0.05) << spp << " spp";
    }
}

TEST_P(GpuDenoise, BandsGiveTheSameBits) {
    VKP_REQUIRE_DEVICE(dev);
    const CleanScene s = piecewiseScene(72, 203);
    const NoisyRender r = renderNoisy(s, 16, 5);
    for (std::uint32_t iterations : {5u, 3u}) {
        DenoiseOptions one = options();
        one.iterations = iterations;
        const std::uint32_t halo = filterRadius(one);
        Denoiser single(dev, one);
        const Image whole = single.run(inputOf(s, r));
        EXPECT_EQ(single.lastBandCount(), 1u);
        DenoiseOptions banded = one;
        banded.maxBandRows = 2 * halo + 23;  // 23 output rows per band
        Denoiser bands(dev, banded);
        const Image parts = bands.run(inputOf(s, r));
        EXPECT_EQ(bands.lastBandCount(), (203u + 22u) / 23u) << iterations << " iterations";
        ASSERT_EQ(parts.rgb.size(), whole.rgb.size());
        EXPECT_EQ(std::memcmp(parts.rgb.data(), whole.rgb.data(), whole.rgb.size() * sizeof(float)), 0)
            << iterations << " iterations: the banded result differs from one pass";
        // A second run of the same Denoiser (buffers reused) gives the same bits too.
        const Image again = bands.run(inputOf(s, r));
        EXPECT_EQ(std::memcmp(again.rgb.data(), whole.rgb.data(), whole.rgb.size() * sizeof(float)), 0);
    }
}

INSTANTIATE_TEST_SUITE_P(Filters, GpuDenoise, ::testing::Values(DenoiseFilter::NonLocalMeans, DenoiseFilter::ATrous),
                         filterName);

TEST(GpuDenoiseOptions, PlanBandsCoversEveryRowOnce) {
    const std::vector<DenoiseBand> one = planDenoiseBands(100, 100, 62);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].y1, 100u);
    const std::vector<DenoiseBand> b = planDenoiseBands(203, 147, 62);
    ASSERT_EQ(b.size(), 9u);
    std::uint32_t next = 0;
    for (const DenoiseBand& band : b) {
        EXPECT_EQ(band.y0, next);
        EXPECT_EQ(band.loadY0, band.y0 >= 62 ? band.y0 - 62 : 0u);
        EXPECT_EQ(band.loadY1, std::min(203u, band.y1 + 62));
        EXPECT_LE(band.loadY1 - band.loadY0, 147u);
        next = band.y1;
    }
    EXPECT_EQ(next, 203u);
    EXPECT_THROW(planDenoiseBands(300, 124, 62), std::invalid_argument);
    EXPECT_EQ(filterRadius(5), 63u);  // 2 + 4 + 8 + 16 + 32, and the firefly bound's 3x3 neighbours
    DenoiseOptions o;
    o.filter = DenoiseFilter::NonLocalMeans;
    o.nlmRadius = 4;
    o.iterations = 3;
    EXPECT_EQ(filterRadius(o), 18u);  // 4, the patch's 1 and the firefly bound's 1, then 4 + 8
    o.iterations = 0;
    EXPECT_EQ(levels(o), 2u);
    o.filter = DenoiseFilter::ATrous;
    EXPECT_EQ(levels(o), 4u);
    EXPECT_EQ(filterRadius(o), filterRadius(4u));
}

TEST(GpuDenoiseOptions, BadInputsThrow) {
    VKP_REQUIRE_DEVICE(dev);
    const CleanScene s = piecewiseScene(32, 24);
    const NoisyRender r = renderNoisy(s, 16, 3);
    Denoiser d(dev);
    DenoiseInput in = inputOf(s, r);
    const auto without = [&](auto member) {
        DenoiseInput bad = in;
        bad.*member = nullptr;
        return bad;
    };
    EXPECT_THROW(d.run(without(&DenoiseInput::color)), std::invalid_argument);
    EXPECT_THROW(d.run(without(&DenoiseInput::variance)), std::invalid_argument);
    EXPECT_THROW(d.run(without(&DenoiseInput::albedo)), std::invalid_argument);
    EXPECT_THROW(d.run(without(&DenoiseInput::normal)), std::invalid_argument);
    EXPECT_THROW(d.run(without(&DenoiseInput::depth)), std::invalid_argument);
    const Image small(32, 23);
    DenoiseInput bad = in;
    bad.albedo = &small;
    EXPECT_THROW(d.run(bad), std::invalid_argument);
    bad = in;
    bad.variance = &small;
    EXPECT_THROW(d.run(bad), std::invalid_argument);
    const std::vector<float> shortDepth(32 * 23, 1.0f);
    bad = in;
    bad.depth = &shortDepth;
    EXPECT_THROW(d.run(bad), std::invalid_argument);
    Image broken = r.color;
    broken.rgb.pop_back();
    bad = in;
    bad.color = &broken;
    EXPECT_THROW(d.run(bad), std::invalid_argument);
    DenoiseOptions o;
    o.iterations = 11;
    EXPECT_THROW(Denoiser(dev, o), std::invalid_argument);
    o = DenoiseOptions{};
    o.sigmaLuminance = 0.0f;
    EXPECT_THROW(Denoiser(dev, o), std::invalid_argument);
    for (std::uint32_t radius : {0u, 16u}) {
        o = DenoiseOptions{};
        o.nlmRadius = radius;
        EXPECT_THROW(Denoiser(dev, o), std::invalid_argument) << "nlmRadius " << radius;
    }
    o = DenoiseOptions{};
    o.nlmPatchK = 0.0f;
    EXPECT_THROW(Denoiser(dev, o), std::invalid_argument);
    o = DenoiseOptions{};
    o.nlmBrighterSigma = std::nanf("");
    EXPECT_THROW(Denoiser(dev, o), std::invalid_argument);
    o = DenoiseOptions{};
    o.filter = static_cast<DenoiseFilter>(7);
    EXPECT_THROW(Denoiser(dev, o), std::invalid_argument);
    // A band that cannot hold its two halos: the device (here a forced band size) is too small.
    o = DenoiseOptions{};
    o.maxBandRows = 2 * filterRadius(o);
    Denoiser tiny(dev, o);
    const CleanScene tall = piecewiseScene(16, 200);
    const NoisyRender tallRender = renderNoisy(tall, 4, 1);
    EXPECT_THROW(tiny.run(inputOf(tall, tallRender)), DeviceError);
    // An empty image is no error: an empty result.
    const Image none;
    const std::vector<float> noDepth;
    EXPECT_TRUE(d.run(DenoiseInput{&none, &none, &none, &none, &noDepth}).empty());
    // Still usable after the refusals.
    EXPECT_EQ(d.run(in).rgb.size(), r.color.rgb.size());
}

}  // namespace
}  // namespace vkp::test
