// Convergence of every sampler on cornell-classic at 24 x 24 pixels (label gpu).
//
// Tests 1 and 2 use independent random numbers (--sequence random): the spp^(-1/2) law and the
// variance a render's own per-pixel sample variances predict hold for independent samples only.
// The Sobol' sequence (shaders/shared/sobol.h) is tested by 3, 4 and 5 (file end).
//
// Every sampler renders 4096 samples per pixel (its own seed), read back every 16 samples: 256
// disjoint 16-spp chunks and 4 disjoint 1024-spp blocks per pixel. Tests 1, 2 and 3 all read these
// renders, so they are one gtest case (GpuConvergence.RmseSlopeAndUncorrelatedSeeds), which makes
// them once; 4 and 5 are cases of their own.
//
// 1. RMSE against a reference falls as spp^(-1/2): the log-log slope between 16 and 1024 spp lies
//    in [-0.55, -0.45] for every sampler.
//    - Reference for sampler k: the OTHER samplers' 4096-spp renders, combined with one global
//      weight per sampler (1 / its median per-pixel variance: global, so the weights do not depend
//      on a pixel's noise; the median, so the pixels on the light's edge, equally noisy for every
//      sampler, do not decide it). Leaving k out makes the test see a bias of k against the others:
//      a biased sampler's error stops falling at its bias.
//    - MSE(n) = mean over pixels of sum over channels of w ((image_n - ref)^2 - v_ref). The
//      reference's noise v_ref (from its per-pixel variances) is subtracted, since
//      E[(image_n - ref)^2] = sigma^2 / n + v_ref + bias^2. MSE(16) averages the chunks, MSE(1024)
//      the blocks. slope = ln(MSE(1024) / MSE(16)) / (2 ln 64).
//    - Weights w = 1 / (v + floor), v the sampler's own variance of a 1024-spp block (floor: 10% of
//      its median), so that every pixel counts about equally: unweighted, the few pixels on the
//      light's edge (samples of 15 or ~0.5) would make MSE(1024) a chi-square with a handful of
//      degrees of freedom. Cross-fitted, so that weights never depend on the errors they weigh:
//      blocks 0-1 and their chunks are weighted with the variances of blocks 2-3, and vice versa.
//    - Soundness: the slope's standard deviation is estimated from the spread of the per-pixel
//      terms (delta method, pixels as independent units) and must be below 0.0125, so that the
//      interval's half-width 0.05 is >= 4 standard deviations: false-failure probability < 6e-5
//      per sampler under the normal approximation. Teeth: the slope of a render biased by
//      truncation (max_depth 2: direct light only) against the full reference, and that of the
//      images plus a bias of one 1024-spp standard error, must fall outside the interval.
// 2. Independent renders with different seeds are uncorrelated: block 0 of seed s against a
//    1024-spp render with seed s + 1. Their difference d has the variance that their per-pixel
//    variances predict: R = sum w d^2 / sum w (v1 + v2) (over pixels and channels; w from blocks
//    2-3, independent of both) has expectation 1, both sums being unbiased for the same quantity;
//    a correlation rho between the renders gives R = 1 - rho. Two-sided z-test of R - 1 with its
//    delta-method standard deviation at family-wise level 0.01 (Sidak over the samplers); that
//    standard deviation must be below 0.1 (a correlation of 0.3 is then >= 3 sd away).
//    Teeth: block 0 against the 2048-spp mean that contains it (rho^2 = 1/2) gives R = 1/3 and
//    must be rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "gpu_env.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

constexpr std::uint32_t kSize = 24;       // image width and height (pixels are the independent units)
constexpr std::uint32_t kFullSpp = 4096;  // samples per sampler (test blocks and references)
constexpr std::uint32_t kChunk = 16, kBlock = 1024;

/// Means (3 per pixel) and variances of the means of the samples added between two read-backs.
struct Span {
    std::vector<double> mean, var;
};

Span spanBetween(const PixelSums& a, const PixelSums& b) {
    Span s;
    for (std::size_t i = 0; i < b.sum.size() / 4; ++i) {
        const double n = double(b.sum[4 * i + 3]) - double(a.sum[4 * i + 3]);
        for (int c = 0; c < 3; ++c) {
            const double m = (double(b.sum[4 * i + c]) - double(a.sum[4 * i + c])) / n;
            const double sq = (double(b.sumSq[4 * i + c]) - double(a.sumSq[4 * i + c])) / n;
            s.mean.push_back(m);
            s.var.push_back(std::max(0.0, sq - m * m) / (n - 1.0));
        }
    }
    return s;
}

/// One sampler's render: its 16-spp chunks, its 1024-spp blocks, and the whole render.
struct SamplerRun {
    Sampler sampler{};
    std::uint32_t seed = 0;
    std::vector<std::vector<double>> chunks;  // [chunk][3 * pixel + c]: means
    std::vector<Span> blocks;
    Span first2048, full;
    double medianVar = 0;  // median over pixels and channels of full.var
};

Scene cornell(std::uint32_t seed, std::uint32_t maxDepth = 50) {
    Scene s = loadSceneJson(scenesDir() / "cornell-classic.json");
    s.camera.width = kSize;
    s.camera.height = kSize;
    s.render.seed = seed;
    s.render.maxDepth = maxDepth;
    return s;
}

SamplerRun runScene(VulkanDevice& dev, const Scene& scene, Sampler sampler, std::uint32_t spp, Sequence sequence) {
    SamplerRun run;
    run.sampler = sampler;
    run.seed = scene.render.seed;
    RenderOptions o;
    o.sampler = sampler;
    o.sequence = sequence;
    o.samplesPerDispatch = 4;
    TestRender r = makeRender(dev, scene, o);
    const PixelSums start = r.renderer->readSums();
    PixelSums prev = start, blockStart = start;
    for (std::uint32_t done = 0; done < spp; done += kChunk) {
        r.renderer->addSamples(kChunk);
        PixelSums cur = r.renderer->readSums();
        run.chunks.push_back(spanBetween(prev, cur).mean);
        if ((done + kChunk) % kBlock == 0) {
            run.blocks.push_back(spanBetween(blockStart, cur));
            blockStart = cur;
        }
        if (done + kChunk == 2 * kBlock) run.first2048 = spanBetween(start, cur);
        prev = std::move(cur);
    }
    run.full = spanBetween(start, prev);
    std::vector<double> sorted = run.full.var;
    std::sort(sorted.begin(), sorted.end());
    run.medianVar = sorted[sorted.size() / 2];
    const RenderCounters c = r.renderer->counters();
    EXPECT_EQ(c.nonfinite, 0u) << samplerName(sampler);
    EXPECT_EQ(c.loopGuard, 0u) << samplerName(sampler);
    return run;
}

SamplerRun runSampler(VulkanDevice& dev, Sampler sampler, std::uint32_t seed, std::uint32_t spp,
                      std::uint32_t maxDepth = 50, Sequence sequence = Sequence::Random) {
    return runScene(dev, cornell(seed, maxDepth), sampler, spp, sequence);
}

struct Reference {
    std::vector<double> mean, var;
};

/// The runs except `skip` combined with global weights 1 / medianVar (file comment).
Reference referenceWithout(const std::vector<SamplerRun>& runs, std::size_t skip) {
    double wsum = 0;
    for (std::size_t j = 0; j < runs.size(); ++j)
        if (j != skip) wsum += 1.0 / runs[j].medianVar;
    Reference ref;
    ref.mean.assign(runs[0].full.mean.size(), 0.0);
    ref.var.assign(ref.mean.size(), 0.0);
    for (std::size_t j = 0; j < runs.size(); ++j) {
        if (j == skip) continue;
        const double w = (1.0 / runs[j].medianVar) / wsum;
        for (std::size_t i = 0; i < ref.mean.size(); ++i) {
            ref.mean[i] += w * runs[j].full.mean[i];
            ref.var[i] += w * w * runs[j].full.var[i];
        }
    }
    return ref;
}

/// Error weights 1 / (v + floor) from the variances of the 1024-spp blocks `blocks` of a run
/// (v: their mean; floor: 10% of v's median), normalised to mean 1.
std::vector<double> weightsFrom(const SamplerRun& run, std::initializer_list<std::size_t> blocks) {
    std::vector<double> v(run.full.var.size(), 0.0);
    for (std::size_t b : blocks)
        for (std::size_t i = 0; i < v.size(); ++i) v[i] += run.blocks[b].var[i] / double(blocks.size());
    std::vector<double> sorted;  // the positive variances (every one in a full render; max_depth 1 leaves
    for (double x : v)           // pixels that see no light's edge at exactly 0)
        if (x > 0) sorted.push_back(x);
    std::sort(sorted.begin(), sorted.end());
    const double floor = sorted.empty() ? 1.0 : 0.1 * sorted[sorted.size() / 2];
    std::vector<double> w;
    double wmean = 0;
    for (double x : v) {
        w.push_back(1.0 / (x + floor));
        wmean += w.back() / double(v.size());
    }
    for (double& x : w) x /= wmean;
    return w;
}

/// Mean of x and the variance of that mean, treating the values as independent.
void meanAndVar(const std::vector<double>& x, double& mean, double& varOfMean) {
    mean = 0;
    for (double v : x) mean += v / double(x.size());
    double ss = 0;
    for (double v : x) ss += (v - mean) * (v - mean);
    varOfMean = ss / double(x.size() - 1) / double(x.size());
}

struct Slope {
    double mse16 = 0, mse1024 = 0, slope = 0, sd = 0;
    double var1024 = 0;  // variance of mse1024 (pixels as independent units)
};

/// Adds to out[pixel] the mean over `images` of sum over channels of w ((image + bias - ref)^2 - v_ref).
void addWeightedSquaredErrors(const std::vector<const std::vector<double>*>& images, const Reference& ref,
                              const std::vector<double>& w, double bias, std::vector<double>& out) {
    for (const std::vector<double>* img : images)
        for (std::size_t i = 0; i < ref.mean.size(); ++i) {
            const double e = (*img)[i] + bias - ref.mean[i];
            out[i / 3] += w[i] * (e * e - ref.var[i]) / double(images.size());
        }
}

/// The slope of log RMSE between 16 and 1024 spp (file comment), with its estimated standard
/// deviation. Cross-fitted weights: blocks 0-1 (and their chunks) are weighted by the variances of
/// blocks 2-3 and the other way round. `bias` is added to every image value (teeth).
Slope slopeOf(const SamplerRun& run, const Reference& ref, double bias = 0.0) {
    const std::size_t pixels = ref.mean.size() / 3;
    const std::size_t perBlock = kBlock / kChunk;
    std::vector<double> a(pixels, 0.0), b(pixels, 0.0);
    for (int half = 0; half < 2; ++half) {
        const std::vector<double> w = half == 0 ? weightsFrom(run, {2, 3}) : weightsFrom(run, {0, 1});
        std::vector<const std::vector<double>*> chunks, blocks;
        for (std::size_t k = 2 * half * perBlock; k < 2 * (half + 1) * perBlock; ++k) chunks.push_back(&run.chunks[k]);
        for (std::size_t k = 2 * half; k < 2 * half + 2; ++k) blocks.push_back(&run.blocks[k].mean);
        addWeightedSquaredErrors(blocks, ref, w, bias, a);
        addWeightedSquaredErrors(chunks, ref, w, bias, b);
    }
    double va, vb;
    Slope s;
    meanAndVar(a, s.mse1024, va);
    meanAndVar(b, s.mse16, vb);
    s.var1024 = va;
    const double lnRatio = std::log(double(kBlock) / kChunk);
    s.slope = std::log(s.mse1024 / s.mse16) / (2.0 * lnRatio);
    s.sd = std::sqrt(va / (s.mse1024 * s.mse1024) + vb / (s.mse16 * s.mse16)) / (2.0 * lnRatio);
    return s;
}

bool inInterval(double slope) { return slope >= -0.55 && slope <= -0.45; }

/// Test 1 on `rs`, every sampler's 4096-spp render (see GpuConvergence.RmseSlopeAndUncorrelatedSeeds below).
void expectRmseFallsAsInverseSquareRootOfSpp(VulkanDevice& dev, const std::vector<SamplerRun>& rs) {
    ASSERT_GE(rs.size(), 2u);
    for (std::size_t k = 0; k < rs.size(); ++k) {
        const char* name = samplerName(rs[k].sampler);
        const Reference ref = referenceWithout(rs, k);
        const Slope s = slopeOf(rs[k], ref);
        std::printf("%-8s weighted RMSE(16) %.4f RMSE(1024) %.5f slope %.4f (sd %.4f)\n", name, std::sqrt(s.mse16),
                    std::sqrt(s.mse1024), s.slope, s.sd);
        EXPECT_TRUE(inInterval(s.slope)) << name << ": slope " << s.slope;
        EXPECT_LT(s.sd, 0.0125) << name << ": the slope is too noisy for the test to mean anything";
        // Teeth: a bias of one 1024-spp standard error on every value flattens the slope.
        double se = 0;
        for (double v : rs[k].blocks[0].var) se += v / double(rs[k].blocks[0].var.size());
        const Slope biased = slopeOf(rs[k], ref, std::sqrt(se));
        std::printf("         with a bias of one standard error (%.5f): slope %.4f\n", std::sqrt(se), biased.slope);
        EXPECT_FALSE(inInterval(biased.slope)) << name;
    }
    // Teeth with a real render: max_depth 2 (direct light only) against the reference of all.
    const SamplerRun truncated = runSampler(dev, rs[0].sampler, 4242, kFullSpp, 2);
    const Slope t = slopeOf(truncated, referenceWithout(rs, rs.size()));
    std::printf("%s at max_depth 2 against the full reference: slope %.4f\n", samplerName(rs[0].sampler), t.slope);
    EXPECT_FALSE(inInterval(t.slope));
}

/// R = sum w d^2 / sum w (v1 + v2) over the pairs, pixels and channels, d = m1 - m2, and its
/// standard deviation (delta method for a ratio of means over independent pixels).
void varianceRatio(const std::vector<std::pair<const Span*, const Span*>>& pairs, const std::vector<double>& w,
                   double& r, double& sd) {
    const std::size_t pixels = w.size() / 3;
    std::vector<double> x(pixels, 0.0), y(pixels, 0.0);
    for (const auto& [a, b] : pairs)
        for (std::size_t i = 0; i < w.size(); ++i) {
            const double d = a->mean[i] - b->mean[i];
            x[i / 3] += w[i] * d * d;
            y[i / 3] += w[i] * (a->var[i] + b->var[i]);
        }
    double mx, my, vx, vy;
    meanAndVar(x, mx, vx);
    meanAndVar(y, my, vy);
    r = mx / my;
    std::vector<double> lin(pixels);
    for (std::size_t p = 0; p < pixels; ++p) lin[p] = (x[p] - r * y[p]) / my;
    double ml, vl;
    meanAndVar(lin, ml, vl);
    sd = std::sqrt(vl);
}

/// Test 2 on `rs` (as test 1).
void expectRendersWithDifferentSeedsUncorrelated(VulkanDevice& dev, const std::vector<SamplerRun>& rs) {
    const double z = normalTwoSidedZ(1.0 - std::pow(1.0 - 0.01, 1.0 / double(rs.size())));
    for (std::size_t k = 0; k < rs.size(); ++k) {
        const char* name = samplerName(rs[k].sampler);
        const SamplerRun other = runSampler(dev, rs[k].sampler, rs[k].seed + 1, kBlock);
        double ratio, sd;
        const std::vector<double> w = weightsFrom(rs[k], {2, 3});  // independent of blocks 0, 1 and of `other`
        varianceRatio({{&rs[k].blocks[0], &other.blocks[0]}}, w, ratio, sd);
        std::printf("%-8s seeds %u, %u: R = %.3f (sd %.3f, %+.2f sd)\n", name, rs[k].seed, other.seed, ratio, sd,
                    (ratio - 1.0) / sd);
        EXPECT_LE(std::abs(ratio - 1.0), z * sd) << name << ": R " << ratio;
        EXPECT_LT(sd, 0.1) << name;
        double nested, sdNested;
        varianceRatio({{&rs[k].blocks[0], &rs[k].first2048}}, w, nested, sdNested);
        std::printf("         block 0 against the 2048 samples that contain it (expected 1/3): R = %.3f\n", nested);
        EXPECT_GT(std::abs(nested - 1.0), z * sdNested) << name << ": the test cannot see a correlation";
    }
}

// ---- 3, 4: the Sobol' sequence ------------------------------------------------------------------
//
// 3. Renders with different seeds are uncorrelated (--sequence sobol). A QMC render's per-pixel
//    sample variance overestimates the variance of its mean (the samples are stratified), so the
//    variance is estimated from independent replicates instead: R = sum w (A - B)^2 / sum w (C - D)^2,
//    A, B the 1024-spp renders with seeds s, s + 1 under test, C, D two with seeds s + 1000,
//    s + 2000. With all four independent both sums estimate 2 sum w sigma^2 and E[R] ~ 1; a
//    correlation rho between A and B gives 1 - rho. z-test as in 2 (family-wise 0.01 over the
//    samplers; delta-method sd < 0.15 required). Teeth: block 0 of seed s against the 2048 samples
//    that contain it must be rejected.
// 4. The Sobol' sequence converges at least as fast as spp^(-1/2), with a much lower error, on
//    direct light (max_depth 2, `light`: the pixel 2D x the light point 2D, each a (0,2) pair).
//    Reference: 4 independent 4096-spp Sobol' renders, their noise v_ref estimated from their
//    spread (unbiased; the per-pixel sample variances would overestimate it). Slope as in 1.
//    Asserted: slope <= -0.5 + 4 sd (false failure < 3.2e-5 if the true slope is <= -0.5, normal
//    approximation); MSE(1024) of the Sobol' render below the random sequence's by more than 4
//    standard deviations of the difference (measured: 8.3x lower, 19 sd); the random sequence's
//    slope inside [-0.55, -0.45] (control). Measured slopes: Sobol' -0.535 (sd 0.017), random
//    -0.497. (Camera rays only on cornell-classic, the light's edges: measured -0.76 against
//    random's -0.54, but its few edge pixels at 24 x 24 leave a standard deviation of 0.09; test 5
//    asserts the pixel-edge rate on a scene made of edges.)

/// R = sum w (a - b)^2 / sum w (c - d)^2 over pixels and channels, and its delta-method sd.
void replicateRatio(const Span& a, const Span& b, const Span& c, const Span& d, const std::vector<double>& w,
                    double& r, double& sd) {
    const std::size_t pixels = w.size() / 3;
    std::vector<double> x(pixels, 0.0), y(pixels, 0.0);
    for (std::size_t i = 0; i < w.size(); ++i) {
        x[i / 3] += w[i] * (a.mean[i] - b.mean[i]) * (a.mean[i] - b.mean[i]);
        y[i / 3] += w[i] * (c.mean[i] - d.mean[i]) * (c.mean[i] - d.mean[i]);
    }
    double mx, my, vx, vy;
    meanAndVar(x, mx, vx);
    meanAndVar(y, my, vy);
    r = mx / my;
    std::vector<double> lin(pixels);
    for (std::size_t p = 0; p < pixels; ++p) lin[p] = (x[p] - r * y[p]) / my;
    double ml, vl;
    meanAndVar(lin, ml, vl);
    sd = std::sqrt(vl);
}

/// Test 3; `rs` (as test 1) gives the weights.
void expectSobolRendersWithDifferentSeedsUncorrelated(VulkanDevice& dev, const std::vector<SamplerRun>& rs) {
    const double z = normalTwoSidedZ(1.0 - std::pow(1.0 - 0.01, 1.0 / double(rs.size())));
    for (std::size_t k = 0; k < rs.size(); ++k) {
        const Sampler smp = rs[k].sampler;
        const char* name = samplerName(smp);
        const std::uint32_t s = 5000 + 7 * std::uint32_t(smp);
        const SamplerRun a = runSampler(dev, smp, s, 2 * kBlock, 50, Sequence::Sobol);
        const SamplerRun b = runSampler(dev, smp, s + 1, kBlock, 50, Sequence::Sobol);
        const SamplerRun c = runSampler(dev, smp, s + 1000, kBlock, 50, Sequence::Sobol);
        const SamplerRun d = runSampler(dev, smp, s + 2000, kBlock, 50, Sequence::Sobol);
        const std::vector<double> w = weightsFrom(rs[k], {2, 3});  // from another render: independent
        double ratio, sd;
        replicateRatio(a.blocks[0], b.blocks[0], c.blocks[0], d.blocks[0], w, ratio, sd);
        std::printf("%-8s sobol seeds %u, %u: R = %.3f (sd %.3f, %+.2f sd)\n", name, s, s + 1, ratio, sd, (ratio - 1.0) / sd);
        EXPECT_LE(std::abs(ratio - 1.0), z * sd) << name << ": R " << ratio;
        EXPECT_LT(sd, 0.15) << name;
        double nested, sdNested;
        replicateRatio(a.blocks[0], a.first2048, c.blocks[0], d.blocks[0], w, nested, sdNested);
        std::printf("         block 0 against the 2048 samples that contain it: R = %.3f\n", nested);
        EXPECT_GT(std::abs(nested - 1.0), z * sdNested) << name << ": the test cannot see a correlation";
    }
}

// Tests 1, 2 and 3 read the same renders, 4096 spp of every sampler with its own seed: one test,
// so that they are made once (CTest runs every test in a process of its own).
TEST(GpuConvergence, RmseSlopeAndUncorrelatedSeeds) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<SamplerRun> rs;
    for (Sampler s : samplersUnderTest()) rs.push_back(runSampler(dev, s, 1000 + 7 * std::uint32_t(s), kFullSpp));
    {
        SCOPED_TRACE("test 1: RMSE falls as spp^(-1/2)");
        expectRmseFallsAsInverseSquareRootOfSpp(dev, rs);
    }
    {
        SCOPED_TRACE("test 2: renders with different seeds are uncorrelated");
        expectRendersWithDifferentSeedsUncorrelated(dev, rs);
    }
    {
        SCOPED_TRACE("test 3: Sobol' renders with different seeds are uncorrelated");
        expectSobolRendersWithDifferentSeedsUncorrelated(dev, rs);
    }
}

/// A reference from independent renders: their mean, and the variance of that mean from their spread.
Reference replicateReference(const std::vector<SamplerRun>& reps) {
    Reference ref;
    const std::size_t n = reps[0].full.mean.size();
    const double k = double(reps.size());
    ref.mean.assign(n, 0.0);
    ref.var.assign(n, 0.0);
    for (const SamplerRun& r : reps)
        for (std::size_t i = 0; i < n; ++i) ref.mean[i] += r.full.mean[i] / k;
    for (const SamplerRun& r : reps)
        for (std::size_t i = 0; i < n; ++i) ref.var[i] += (r.full.mean[i] - ref.mean[i]) * (r.full.mean[i] - ref.mean[i]) / ((k - 1.0) * k);
    return ref;
}

TEST(GpuConvergenceSobol, AtLeastInverseSquareRootAndLowerErrorOnDirectLight) {
    VKP_REQUIRE_DEVICE(dev);
    struct Case {
        const char* name;
        Sampler sampler;
        std::uint32_t maxDepth;
    };
    for (const Case& c : {Case{"direct light (max_depth 2, light)", Sampler::Light, 2}}) {
        std::vector<SamplerRun> reps;
        for (std::uint32_t r = 0; r < 4; ++r) reps.push_back(runSampler(dev, c.sampler, 7000 + r, kFullSpp, c.maxDepth, Sequence::Sobol));
        const Reference ref = replicateReference(reps);
        const SamplerRun sobol = runSampler(dev, c.sampler, 6000, kFullSpp, c.maxDepth, Sequence::Sobol);
        const SamplerRun random = runSampler(dev, c.sampler, 6000, kFullSpp, c.maxDepth, Sequence::Random);
        const Slope qs = slopeOf(sobol, ref), rs = slopeOf(random, ref);
        std::printf("%s: sobol RMSE(16) %.4f RMSE(1024) %.5f slope %.4f (sd %.4f); random RMSE(16) %.4f RMSE(1024) %.5f slope %.4f (sd %.4f)\n",
                    c.name, std::sqrt(qs.mse16), std::sqrt(qs.mse1024), qs.slope, qs.sd, std::sqrt(rs.mse16),
                    std::sqrt(rs.mse1024), rs.slope, rs.sd);
        const double zMse = (rs.mse1024 - qs.mse1024) / std::sqrt(rs.var1024 + qs.var1024);
        std::printf("    MSE(1024) random / sobol = %.2f (difference %.1f sd)\n", rs.mse1024 / qs.mse1024, zMse);
        EXPECT_LE(qs.slope, -0.5 + 4.0 * qs.sd) << c.name;
        EXPECT_GT(zMse, 4.0) << c.name;
        EXPECT_TRUE(inInterval(rs.slope)) << c.name << ": random sequence slope " << rs.slope;
    }
}

/// 24 x 24 pixels looking at a 10 x 10 grid of small emitting squares (1.3 pixels wide, 0.9 apart,
/// turned against the pixel grid), camera rays only: nearly every pixel straddles an edge.
Scene edgeGrid(std::uint32_t seed) {
    std::string objects;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            const double x = -2.4 + 0.5 * i, y = -2.4 + 0.5 * j;
            objects += std::string(objects.empty() ? "" : ",") + R"({"type": "quad", "Q": [)" + std::to_string(x) + ", " +
                       std::to_string(y) + R"(, 0], "u": [0.3, 0, 0], "v": [0, 0.3, 0], "material": "light"})";
        }
    const std::string json = R"({"camera": {"lookfrom": [0, 0, 10], "lookat": [0, 0, 0], "vup": [0.3, 1, 0], "vfov": 30,
        "width": 24, "height": 24}, "render": {"spp": 16, "max_depth": 1, "seed": )" + std::to_string(seed) + R"(},
        "materials": {"light": {"type": "diffuse_light", "emit": [1, 1, 1]}}, "objects": [)" + objects + "]}";
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "vkpath_test_edge_grid.json";
    {
        std::ofstream(file) << json;
    }
    Scene scene = loadSceneJson(file);
    std::filesystem::remove(file);
    return scene;
}

// 5. Pixel edges: camera rays only on edgeGrid (the pixel integral of a 2D discontinuity, where
//    Owen-scrambled (0,2)-nets give RMSE ~ spp^(-3/4)). Reference: 4 independent 4096-spp Sobol'
//    renders, noise from their spread (as in 4). Asserted: Sobol' slope + 4 sd <= -0.6 and sd <
//    0.0125 (false failure < 3.2e-5 under the normal approximation when the true slope is <= -0.6);
//    control and teeth: the random sequence's slope lies in [-0.55, -0.45] and fails the bound.
TEST(GpuConvergenceSobol, FasterThanInverseSquareRootOnPixelEdges) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<SamplerRun> reps;
    for (std::uint32_t r = 0; r < 4; ++r) reps.push_back(runScene(dev, edgeGrid(8000 + r), Sampler::Bsdf, kFullSpp, Sequence::Sobol));
    const Reference ref = replicateReference(reps);
    const SamplerRun sobol = runScene(dev, edgeGrid(9000), Sampler::Bsdf, kFullSpp, Sequence::Sobol);
    const SamplerRun random = runScene(dev, edgeGrid(9000), Sampler::Bsdf, kFullSpp, Sequence::Random);
    const Slope qs = slopeOf(sobol, ref), rs = slopeOf(random, ref);
    std::printf("pixel edges: sobol RMSE(16) %.4f RMSE(1024) %.5f slope %.4f (sd %.4f); random RMSE(16) %.4f RMSE(1024) %.5f slope %.4f (sd %.4f)\n",
                std::sqrt(qs.mse16), std::sqrt(qs.mse1024), qs.slope, qs.sd, std::sqrt(rs.mse16), std::sqrt(rs.mse1024), rs.slope, rs.sd);
    EXPECT_LE(qs.slope + 4.0 * qs.sd, -0.6);
    EXPECT_LT(qs.sd, 0.0125);
    EXPECT_TRUE(inInterval(rs.slope)) << "random sequence slope " << rs.slope;
    EXPECT_GT(rs.slope + 4.0 * rs.sd, -0.6) << "the bound does not separate the sequences";
}

}  // namespace
}  // namespace vkp::test
