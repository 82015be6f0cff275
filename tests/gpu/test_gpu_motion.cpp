// Motion blur on the device ("Ray Tracing: The Next Week", sec. 2; docs/design.md "Motion blur"),
// labels gpu and stats. The image of a moving scene is the mean over the shutter interval of the
// still images, so each test compares a motion-blurred render with still renders at K evenly
// spaced times (k + 0.5) / K, K = 32:
//  1. a sphere moving from `center` to `center1` (the book's moving sphere) over a floor, lit by
//     the background: shadows, inter-reflection and the sphere's own shading at one time per path
//     (sequence random);
//  2. a quad with "motion": {"translate": ...} and a checker texture, under a uniform sky (a plane
//     then reflects exactly its albedo): the texture moves with the quad. Its still renders move
//     the camera the other way instead of the quad (the same image: nothing else is in the scene),
//     because a still quad's checker would stay in place. Under both sequences (sobol, random);
//  3. moving emitters, a sphere light (center1) and a quad light (motion), over a floor: next-event
//     estimation samples them where they are at the path's time, so `light`, `mixture` and `mis`
//     agree with `bsdf`, which only finds them by hitting them (sequence random).
// The mean of K still renders is the midpoint rule of the time integral: at K = 32 its error is
// about 1/10 of a pixel's standard error here (edges cross a pixel in ~0.1 of the interval, so a
// pixel's value is piecewise linear in time with kinks, and the rule's error is ~ slope change x
// h^2 / 8 = 10 x (1/32)^2 / 8 ~ 1e-3 against standard errors of ~1e-2).
//
// Statistics (fixed seeds): z = difference / sqrt(sum of the variances of the means), the
// variances estimated from the per-pixel sums (the still mean's is the sum of the K renders'
// over K^2). 1-2: every pixel and channel, |z| <= 5 (two-sided normal tail 5.7e-7; 1152 and
// 2 x 1152 tests: false-failure probability <= 2e-3 in all), and the mean of z^2 over the V values
// that vary at most 1.5 (its expectation is 1; pixels are independent, and a pixel's three channels
// add at most 3 z^2, of variance <= 9 x 2, so the mean's standard deviation is at most
// sqrt(18 x 384) / V <= 0.12 for the V >= 700 measured here, and 1.5 is over 4 of them: a false
// failure below 2e-5 by the central limit theorem over the pixels). Under sobol the variances estimated as if the
// samples were independent overstate the true ones (stratification), so its z are smaller (mean
// z^2 0.06 measured): safe against false failures, less sharp, hence random in 1 and both in 2.
// 3: block means (4 x 4 pixels), |z| <= 4.5 per block, channel and sampler pair against bsdf
// (16 x 3 x 3 = 144 tests, 1e-3 in all).
//
// Each test fails when what it checks is broken (measured): times in [0, 0.5) instead of [0, 1)
// fail 1 (|z| up to 142); JSON textures read where the point is instead of where it was at time
// 0 fail 2 (|z| up to 42); next-event estimation sampling the lights where they are at time 0
// fails 3 (54 of 144 block means).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gpu_env.h"
#include "render_helpers.h"
#include "scene/scene.h"

namespace vkp::test {
namespace {

constexpr int kTimes = 32;  // still renders per motion-blurred one

/// "%.17g" of a double, for JSON text.
std::string num(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}
std::string vec(glm::dvec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

/// Per pixel and channel: the mean and the variance of the mean.
struct MeanImage {
    std::uint32_t width = 0, height = 0;
    std::vector<double> mean, var;
};

MeanImage meanImage(const PixelSums& s) {
    const Image m = s.mean(), v = s.varianceOfMean();
    MeanImage out{s.width, s.height, {}, {}};
    for (std::uint32_t y = 0; y < s.height; ++y)
        for (std::uint32_t x = 0; x < s.width; ++x)
            for (int c = 0; c < 3; ++c) {
                out.mean.push_back(m.at(x, y, c));
                out.var.push_back(v.at(x, y, c));
            }
    return out;
}

/// Adds `part` / k to `acc` (the mean of k images, the variance of that mean).
void addMean(MeanImage& acc, const MeanImage& part, int k) {
    if (acc.mean.empty()) acc = MeanImage{part.width, part.height, std::vector<double>(part.mean.size(), 0.0),
                                          std::vector<double>(part.var.size(), 0.0)};
    for (std::size_t i = 0; i < part.mean.size(); ++i) {
        acc.mean[i] += part.mean[i] / k;
        acc.var[i] += part.var[i] / (double(k) * k);
    }
}

/// Every pixel and channel of the blurred image against the mean of the still ones (file comment).
void expectSameImage(const MeanImage& blurred, const MeanImage& still, const std::string& what) {
    ASSERT_EQ(blurred.mean.size(), still.mean.size());
    double maxZ = 0, sumZ2 = 0;
    int bad = 0, varying = 0;
    for (std::size_t i = 0; i < blurred.mean.size(); ++i) {
        const double d = blurred.mean[i] - still.mean[i], v = blurred.var[i] + still.var[i];
        if (!(v > 0.0)) {  // both constant (e.g. only the background): the same constant
            EXPECT_NEAR(blurred.mean[i], still.mean[i], 1e-6 * (1.0 + std::abs(still.mean[i]))) << what << " value " << i;
            continue;
        }
        const double z = d / std::sqrt(v);
        maxZ = std::max(maxZ, std::abs(z));
        sumZ2 += z * z;
        ++varying;
        if (std::abs(z) > 5.0 && bad++ < 8)
            ADD_FAILURE() << what << ": pixel " << i / 3 % blurred.width << "," << i / 3 / blurred.width << " channel " << i % 3
                          << ": blurred " << blurred.mean[i] << " vs still mean " << still.mean[i] << " (z " << z << ")";
    }
    const double meanZ2 = sumZ2 / std::max(varying, 1);
    std::printf("  %s: %d values vary, max |z| %.2f, mean z^2 %.3f\n", what.c_str(), varying, maxZ, meanZ2);
    EXPECT_LE(meanZ2, 1.5) << what;
    EXPECT_GT(varying, int(blurred.mean.size()) / 4) << what << ": the scene should cover most pixels";
}

/// A render's mean image. Each still render gets a seed of its own (`seed`): with one seed they
/// would all take the same random numbers, and their mean would not have the variance computed
/// for independent renders.
MeanImage render(VulkanDevice& dev, Scene scene, Sampler sampler, Sequence sequence, std::uint32_t spp,
                 const std::string& what, std::uint32_t seed = 0) {
    scene.render.seed = seed;
    RenderOptions o;
    o.sampler = sampler;
    o.sequence = sequence;
    o.samplesPerDispatch = 8;
    return meanImage(renderSums(dev, scene, o, spp, what));
}

// ---- 1. The book's moving sphere -----------------------------------------------------------------

std::string sphereScene(const std::string& sphere) {
    return R"({
      "camera": {"lookfrom": [0, 1.2, 6], "lookat": [0, 0.6, 0], "vfov": 30, "width": 24, "height": 16},
      "render": {"max_depth": 8, "background": [0.8, 0.85, 0.9]},
      "materials": {"floor": {"type": "lambertian", "albedo": [0.6, 0.6, 0.6]},
                    "ball": {"type": "lambertian", "albedo": [0.8, 0.3, 0.2]}},
      "objects": [{"type": "quad", "Q": [-4, 0, 4], "u": [8, 0, 0], "v": [0, 0, -8], "material": "floor"},
                  )" + sphere + "]}";
}

TEST(GpuMotion, AMovingSphereIsTheMeanOfStillOnesOverTheInterval) {
    VKP_REQUIRE_DEVICE(dev);
    const glm::dvec3 c0(-1.0, 0.5, 0.0), c1(1.0, 1.1, -0.5);
    const Scene blurredScene = parseSceneJson(
        sphereScene(R"({"type": "sphere", "center": )" + vec(c0) + R"(, "center1": )" + vec(c1) + R"(, "radius": 0.5, "material": "ball"})"),
        "moving-sphere.json");
    const std::uint32_t spp = 2048;
    const MeanImage blurred = render(dev, blurredScene, Sampler::Mis, Sequence::Random, spp, "moving sphere");
    MeanImage still;
    for (int k = 0; k < kTimes; ++k) {
        const glm::dvec3 c = c0 + (k + 0.5) / kTimes * (c1 - c0);
        const Scene s = parseSceneJson(sphereScene(R"({"type": "sphere", "center": )" + vec(c) + R"(, "radius": 0.5, "material": "ball"})"),
                                       "still-sphere.json");
        addMean(still, render(dev, s, Sampler::Mis, Sequence::Random, spp / kTimes, "still sphere", 1000 + k), kTimes);
    }
    expectSameImage(blurred, still, "moving sphere (random, mis)");
}

// ---- 2. A quad with motion.translate and a texture that moves with it ----------------------------

std::string quadScene(glm::dvec3 cameraShift, const std::string& motion) {
    return R"({
      "camera": {"lookfrom": )" + vec(glm::dvec3(0, 0, 5) - cameraShift) + R"(, "lookat": )" + vec(-cameraShift) +
           R"(, "vfov": 30, "width": 24, "height": 16},
      "render": {"max_depth": 4, "background": [1, 1, 1]},
      "materials": {"check": {"type": "lambertian",
                    "albedo": {"type": "checker", "scale": 0.25, "even": [0.9, 0.2, 0.1], "odd": [0.1, 0.3, 0.8]}}},
      "objects": [{"type": "quad", "Q": [-1.5, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "check")" +
           motion + "}]}";
}

TEST(GpuMotion, AMovingQuadCarriesItsTextureAndIsTheMeanOfStillOnes) {
    VKP_REQUIRE_DEVICE(dev);
    const glm::dvec3 move(1.0, 0.25, 0.0);
    const Scene blurredScene = parseSceneJson(quadScene(glm::dvec3(0.0), R"(, "motion": {"translate": )" + vec(move) + "}"), "moving-quad.json");
    const std::uint32_t spp = 1024;
    for (Sequence sequence : {Sequence::Sobol, Sequence::Random}) {
        const MeanImage blurred = render(dev, blurredScene, Sampler::Mis, sequence, spp, "moving quad");
        MeanImage still;
        for (int k = 0; k < kTimes; ++k) {
            const Scene s = parseSceneJson(quadScene((k + 0.5) / kTimes * move, ""), "still-quad.json");
            addMean(still, render(dev, s, Sampler::Mis, sequence, spp / kTimes, "still quad", 1000 + k), kTimes);
        }
        expectSameImage(blurred, still, std::string("moving textured quad (") + sequenceName(sequence) + ", mis)");
    }
}

// ---- 3. Moving emitters under every sampler ------------------------------------------------------

TEST(GpuMotion, EverySamplerAgreesOnMovingLights) {
    VKP_REQUIRE_DEVICE(dev);
    const Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 2.5, 7], "lookat": [0, 0.6, 0], "vfov": 35, "width": 16, "height": 16},
      "render": {"max_depth": 6},
      "materials": {"floor": {"type": "lambertian", "albedo": [0.7, 0.7, 0.7]},
                    "ball": {"type": "lambertian", "albedo": [0.3, 0.6, 0.4]},
                    "lamp": {"type": "diffuse_light", "emit": [5, 5, 5]},
                    "bulb": {"type": "diffuse_light", "emit": [8, 5, 3]}},
      "objects": [{"type": "quad", "Q": [-4, 0, 4], "u": [8, 0, 0], "v": [0, 0, -8], "material": "floor"},
                  {"type": "sphere", "center": [0.5, 0.5, 0], "radius": 0.5, "material": "ball"},
                  {"type": "quad", "Q": [-1.5, 2.2, -0.5], "u": [1, 0, 0], "v": [0, 0, 1], "material": "lamp",
                   "motion": {"translate": [2, 0, 0.5]}},
                  {"type": "sphere", "center": [-1.5, 0.8, 0.8], "center1": [-0.4, 1.4, 0.2], "radius": 0.3, "material": "bulb"}]})",
                                       "moving-lights.json");
    ASSERT_EQ(scene.lights.size(), 2u);
    double mean[4][16][3], var[4][16][3];
    int k = 0;
    for (Sampler sampler : kAllSamplers) {
        const MeanImage m = render(dev, scene, sampler, Sequence::Random, sampler == Sampler::Bsdf ? 8192 : 2048, "moving lights");
        for (int b = 0; b < 16; ++b)
            for (int c = 0; c < 3; ++c) {
                double sm = 0, sv = 0;
                for (int y = 0; y < 4; ++y)
                    for (int x = 0; x < 4; ++x) {
                        const std::size_t i = 3 * std::size_t((4 * (b / 4) + y) * 16 + 4 * (b % 4) + x) + std::size_t(c);
                        sm += m.mean[i];
                        sv += m.var[i];
                    }
                mean[k][b][c] = sm / 16;
                var[k][b][c] = sv / 256;
            }
        ++k;
    }
    double maxZ = 0;
    for (int j = 1; j < 4; ++j)
        for (int b = 0; b < 16; ++b)
            for (int c = 0; c < 3; ++c) {
                const double v = var[j][b][c] + var[0][b][c];
                if (!(v > 0.0)) {  // no light reaches the block (black background): both exactly 0
                    EXPECT_EQ(mean[j][b][c], mean[0][b][c]) << samplerName(kAllSamplers[j]) << " block " << b;
                    continue;
                }
                const double z = (mean[j][b][c] - mean[0][b][c]) / std::sqrt(v);
                maxZ = std::max(maxZ, std::abs(z));
                EXPECT_LE(std::abs(z), 4.5) << samplerName(kAllSamplers[j]) << " block " << b << " channel " << c << ": "
                                            << mean[j][b][c] << " vs bsdf " << mean[0][b][c];
            }
    std::printf("  moving lights: max |z| against bsdf over 144 block means %.2f\n", maxZ);
    EXPECT_GT(mean[0][5][0], 0.05) << "the floor is lit";
}

}  // namespace
}  // namespace vkp::test
