// Shared pieces of the accuracy tests (tests/gpu/test_gpu_analytic*.cpp, test_gpu_convergence*.cpp,
// tests/stress): z-tests of pixel means against expected values with tolerances in standard
// errors (the Sidak-corrected critical value of a test executable: z_budget.h), closed-form
// irradiance, and the comparison of two renders. Renders are made with render_helpers.h.
//
// Statistics. A pixel's mean over n samples has variance sigma^2 / n, estimated by
// PixelSums::varianceOfMean (sample variance / n). A region (a block of pixels, or a list of
// pixels) is summarised by the average of its pixel means, whose variance is sum(var_i) / k^2 for
// k pixels with independent samples. A z-test compares |mean - expected| with
//     z_crit * sqrt(var) + (n - 1) 2^-24 |expected|,
// where the second term is the worst-case relative error of a sequential float sum of n terms
// (Higham, "Accuracy and Stability of Numerical Algorithms", sec. 4.2), kept as a generous bound
// for pixels whose samples are all equal (zero variance) although the device's sums are now
// double-float pairs (shaders/shared/compensated_sum.h) and err far less.
// z_crit comes from a suite budget (z_budget.h): a test executable declares that it performs at
// most B z-tests at family-wise level alpha; each is run at the Sidak level 1 - (1 - alpha)^(1/B)
// (Sidak 1967: for jointly normal statistics, correlated or not, the family-wise false-failure
// probability is then <= alpha). The executable checks at exit that its tests did not exceed B.
// The region means are averages of >= 4096 samples, so the normal approximation is adequate for
// the tails used here (z ~ 4.4-4.6) as long as the samples are not heavy-tailed; each test says
// why its samples are not.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "file_frame.h"
#include "gpu_env.h"
#include "image_checks.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "render_helpers.h"
#include "scene/scene.h"
#include "z_budget.h"

namespace vkp::test {

/// Mean of a region and the variance of that mean.
struct Estimate {
    double mean = 0.0;
    double var = 0.0;  ///< variance of `mean`
    double n = 0.0;    ///< samples per pixel (the smallest in the region)
};

/// Per-pixel means, variances of the means and sample counts of a render.
struct PixelStats {
    Image mean, var;
    std::vector<double> n;
    std::uint32_t width = 0, height = 0;
    explicit PixelStats(const PixelSums& s) : mean(s.mean()), var(s.varianceOfMean()), width(s.width), height(s.height) {
        for (std::size_t i = 0; i < s.sum.size() / 4; ++i) n.push_back(s.sum[4 * i + 3]);
    }
    double samples(std::uint32_t x, std::uint32_t y) const { return n[std::size_t(y) * width + x]; }
};

struct Pixel {
    std::uint32_t x, y;
};

/// Average over `pixels` of channel c (each pixel's mean weighted equally).
inline Estimate average(const PixelStats& s, const std::vector<Pixel>& pixels, int c) {
    Estimate e;
    e.n = 1e30;
    for (const Pixel& p : pixels) {
        e.mean += s.mean.at(p.x, p.y, c);
        e.var += s.var.at(p.x, p.y, c);
        e.n = std::min(e.n, s.samples(p.x, p.y));
    }
    const double k = double(pixels.size());
    e.mean /= k;
    e.var /= k * k;
    return e;
}

/// The pixels of [x0, x1) x [y0, y1).
inline std::vector<Pixel> rect(std::uint32_t x0, std::uint32_t y0, std::uint32_t x1, std::uint32_t y1) {
    std::vector<Pixel> out;
    for (std::uint32_t y = y0; y < y1; ++y)
        for (std::uint32_t x = x0; x < x1; ++x) out.push_back({x, y});
    return out;
}

/// z-test of an estimate against an expected value (file comment); counts against zBudget().
/// With print = true the result is also printed (for the summaries in docs/accuracy.md).
/// rareJump: for estimators whose samples rarely (probability << 1 / samples) jump by up to
/// rareJump from the common value (Russian roulette ending a path that almost always has the same
/// value), the sample variance misses those events when none happened; the variance of one such
/// event among the region's samples, (rareJump / N)^2, N = samples in the region, is then added.
inline ::testing::AssertionResult withinNoise(const Estimate& e, double expected, const std::string& what,
                                              bool print = false, double rareJump = 0.0, double regionSamples = 1.0) {
    const double z = zBudget().take();
    const double slack = std::max(0.0, e.n - 1.0) * std::ldexp(1.0, -24) * std::abs(expected);
    const double sd = std::sqrt(e.var + (rareJump / regionSamples) * (rareJump / regionSamples));
    const double err = e.mean - expected;
    const double zs = sd > 0 ? err / sd : (err == 0 ? 0.0 : INFINITY);
    if (std::abs(err) > slack) zBudget().maxAbsZ = std::max(zBudget().maxAbsZ, std::abs(zs));
    std::ostringstream msg;
    msg << what << ": mean " << e.mean << ", expected " << expected << ", error " << err << " = " << zs
        << " standard errors (sd " << sd << ", limit " << z << " sd + " << slack << ")";
    const bool fails = std::abs(err) > z * sd + slack;
    if (print || fails || (std::abs(err) > slack && std::abs(zs) > 0.8 * z))  // near misses are worth seeing too
        std::printf("  %s: %.6g (expected %.6g), error %+.2e = %+.2f se, relative se %.2e\n", what.c_str(), e.mean,
                    expected, err, zs, expected != 0 ? sd / std::abs(expected) : sd);
    if (!fails) return ::testing::AssertionSuccess() << msg.str();
    return ::testing::AssertionFailure() << msg.str();
}

// ---- Closed-form irradiance on a plane, averaged over pixel footprints -------------------------

constexpr double kPi = 3.14159265358979323846;

/// Irradiance (per unit radiance L = 1) at x with unit normal n from a uniformly emitting convex
/// polygon that lies entirely above x's tangent plane: Lambert's formula E = 1/2 |sum_i theta_i
/// (n . g_i)|, theta_i the angle edge i subtends at x, g_i the unit normal of the plane through x
/// and that edge (Arvo, "Applications of Irradiance Tensors", SIGGRAPH 1995, eq. 7).
inline double polygonIrradiance(const glm::dvec3& x, const glm::dvec3& n, const std::vector<glm::dvec3>& poly) {
    double sum = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec3 a = glm::normalize(poly[i] - x), b = glm::normalize(poly[(i + 1) % poly.size()] - x);
        const glm::dvec3 c = glm::cross(a, b);
        const double theta = std::atan2(glm::length(c), glm::dot(a, b));
        sum += theta * glm::dot(glm::normalize(c), n);
    }
    return 0.5 * std::abs(sum);
}

/// Irradiance (L = 1) at x with unit normal n from a sphere (c, R) entirely above x's horizon:
/// pi (R/d)^2 cos(theta), the sphere acting as a point of intensity pi R^2 at its centre.
inline double sphereIrradiance(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& c, double r) {
    const glm::dvec3 f = c - x;
    const double d = glm::length(f);
    return kPi * (r / d) * (r / d) * glm::dot(f / d, n);
}

/// Gauss-Legendre nodes and weights on [-0.5, 0.5] (8 points, exact for degree 15).
inline const std::array<double, 8> kGlX = {-0.4801449282487681, -0.3983332387068134, -0.2627662472838140, -0.0916717321004510,
                                    0.0916717321004510,  0.2627662472838140,  0.3983332387068134,  0.4801449282487681};
inline const std::array<double, 8> kGlW = {0.0506142681451881, 0.1111905172266872, 0.1568533229389436, 0.1813418916891810,
                                    0.1813418916891810, 0.1568533229389436, 0.1111905172266872, 0.0506142681451881};

/// The mean of E over pixel (i, j)'s footprint on the plane z = 0: the kernel aims each sample at
/// pixel00 + (i + jx) du + (j + jy) dv, jx, jy uniform in [-0.5, 0.5], from the camera origin;
/// that point is carried along its ray to z = 0 and E is integrated over (jx, jy) by 8x8
/// Gauss-Legendre quadrature (accurate for an E that is smooth on the scale of a pixel: lights
/// several pixel footprints away from the plane).
inline double footprintMean(const gpu::GpuFrame& f, std::uint32_t i, std::uint32_t j, const std::function<double(glm::dvec3)>& E) {
    const glm::dvec3 o(f.origin), p00(f.pixel00), du(f.pixelDu), dv(f.pixelDv);
    double sum = 0.0;
    for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
            const glm::dvec3 target = p00 + (i + kGlX[a]) * du + (j + kGlX[b]) * dv;
            const glm::dvec3 x = o + (target - o) * (o.z / (o.z - target.z));
            sum += kGlW[a] * kGlW[b] * E(x);
        }
    return sum;
}

const char* const kChannel[] = {"R", "G", "B"};

/// a - b of two independent estimates (its variance the sum of theirs), to z-test against 0.
inline Estimate difference(const Estimate& a, const Estimate& b) {
    Estimate d;
    d.mean = a.mean - b.mean;
    d.var = a.var + b.var;
    d.n = std::min(a.n, b.n);
    return d;
}

/// difference() of the averages of `pixels` (channel c) in two independent renders a and b.
inline Estimate difference(const PixelStats& a, const PixelStats& b, const std::vector<Pixel>& pixels, int c) {
    return difference(average(a, pixels, c), average(b, pixels, c));
}

/// The whole image and every block x block square of a size x size image, named for messages.
inline std::vector<std::pair<std::string, std::vector<Pixel>>> imageAndBlocks(std::uint32_t size, std::uint32_t block) {
    std::vector<std::pair<std::string, std::vector<Pixel>>> regions = {{"image", rect(0, 0, size, size)}};
    for (std::uint32_t by = 0; by < size; by += block)
        for (std::uint32_t bx = 0; bx < size; bx += block)
            regions.push_back({"block " + std::to_string(bx) + "," + std::to_string(by), rect(bx, by, bx + block, by + block)});
    return regions;
}

/// Two independent renders of the same image (size x size pixels), a named nameA and b nameB,
/// that must agree within noise: both must be lit and not constant (litAndNotConstant: two black
/// images agree), then the whole image (printed) and every block x block square, per channel,
/// z-test of a - b against 0 (3 x (1 + (size / block)^2) tests of zBudget()). Returns the whole
/// image's mean of a per channel, for checks that the scene is lit as brightly as it should be.
inline glm::dvec3 expectRendersAgree(const PixelStats& a, const std::string& nameA, const PixelStats& b,
                                     const std::string& nameB, std::uint32_t size, std::uint32_t block) {
    EXPECT_TRUE(litAndNotConstant(a.mean, nameA));
    EXPECT_TRUE(litAndNotConstant(b.mean, nameB));
    const std::string what = nameA + " - " + nameB;
    glm::dvec3 imageMean(0.0);
    for (const auto& [name, px] : imageAndBlocks(size, block))
        for (int c = 0; c < 3; ++c) {
            const Estimate ea = average(a, px, c), eb = average(b, px, c);
            if (name == "image") imageMean[c] = ea.mean;
            EXPECT_TRUE(withinNoise(difference(ea, eb), 0.0, what + ", " + name + ", " + kChannel[c], name == "image"));
        }
    return imageMean;
}

/// Every sampler the renderer knows (found by name, so that samplers added later are covered).
inline std::vector<Sampler> samplersUnderTest() {
    std::vector<Sampler> out;
    for (const char* name : {"bsdf", "light", "mixture", "mis", "mis-power", "guided"}) {
        Sampler s;
        if (parseSampler(name, s)) out.push_back(s);
    }
    return out;
}

/// z-tests of a 16 x 16 render of planeScene against expected radiance / albedo per pixel (row
/// major) times rho, per channel: the whole image (printed when printImage) and every block x block
/// square: 3 x (1 + (16 / block)^2) z-tests.
inline void expectPlanePixels(const PixelStats& st, glm::dvec3 rho, const std::vector<double>& expected, const std::string& name,
                              std::uint32_t block, bool printImage) {
    for (int c = 0; c < 3; ++c) {
        auto expect = [&](const std::vector<Pixel>& px) {
            double sum = 0;
            for (const Pixel& p : px) sum += rho[c] * expected[p.y * 16 + p.x];
            return sum / double(px.size());
        };
        const auto all = rect(0, 0, 16, 16);
        EXPECT_TRUE(withinNoise(average(st, all, c), expect(all), name + ", image, " + kChannel[c], printImage));
        for (std::uint32_t by = 0; by < 16; by += block)
            for (std::uint32_t bx = 0; bx < 16; bx += block) {
                const auto px = rect(bx, by, bx + block, by + block);
                EXPECT_TRUE(withinNoise(average(st, px, c), expect(px),
                                        name + ", block " + std::to_string(bx) + "," + std::to_string(by) + ", " + kChannel[c]));
            }
    }
}

/// Radiance of the "lamp" material of planeScene.
constexpr double kLampL = 10.0;

/// A large lambertian plane z = 0 of albedo (0.2, 0.5, 0.8) ("plane"), the objects `lights` (JSON,
/// comma-separated; the material "lamp" emits kLampL from its front) and a camera 100 units above
/// the origin seeing [-2, 2]^2 at 16 x 16; max_depth 2, black background: each pixel is the
/// direct light on the plane.
inline Scene planeScene(const std::string& lights, std::uint32_t seed) {
    Scene s = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 0, 100], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 2.2913, "width": 16, "height": 16},
      "render": {"max_depth": 2, "background": [0, 0, 0]},
      "materials": {"plane": {"type": "lambertian", "albedo": [0.2, 0.5, 0.8]},
                    "lamp": {"type": "diffuse_light", "emit": [10, 10, 10]},
                    "black": {"type": "lambertian", "albedo": [0, 0, 0]}},
      "objects": [{"type": "quad", "Q": [-50, -50, 0], "u": [100, 0, 0], "v": [0, 100, 0], "material": "plane"},
                  )" + lights + R"(]})",
                             "plane-direct.json");
    s.render.seed = seed;
    return s;
}

/// Renders planeScene(lights) with every sampler (samplersUnderTest; 1024 spp, bsdf 4096) and
/// z-tests the image and its 16 blocks of 4 x 4 pixels, per channel, against (rho / pi) times
/// the irradiance E(x) (W/m^2, in file coordinates) averaged over each pixel's footprint
/// (footprintMean): 3 x 17 z-tests per sampler. E must be smooth on the scale of a pixel.
inline void checkPlane(VulkanDevice& dev, const std::string& lightJson, const std::string& lightName,
                       const std::function<double(glm::dvec3)>& irradiance) {
    const glm::dvec3 rho(0.2, 0.5, 0.8);
    Scene scene = planeScene(lightJson, 1);
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    std::vector<double> expected(16 * 16);
    double eMin = 1e30, eMax = 0;
    for (std::uint32_t j = 0; j < 16; ++j)
        for (std::uint32_t i = 0; i < 16; ++i) {
            expected[j * 16 + i] = footprintMean(f, i, j, irradiance) / kPi;
            eMin = std::min(eMin, expected[j * 16 + i]);
            eMax = std::max(eMax, expected[j * 16 + i]);
        }
    std::printf("%s: expected pixel radiance / albedo in [%.4f, %.4f]\n", lightName.c_str(), eMin, eMax);
    ASSERT_GT(eMin, 0.0);
    for (Sampler s : samplersUnderTest()) {
        scene.render.seed = 20 + std::uint32_t(s);
        const std::uint32_t spp = s == Sampler::Bsdf ? 4096 : 1024;
        const PixelStats st(renderSums(dev, scene, s, spp, lightName));
        expectPlanePixels(st, rho, expected, std::string(samplerName(s)) + " " + lightName, 4, true);
    }
}

}  // namespace vkp::test
