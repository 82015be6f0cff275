// Adaptive sampling on the device (`--adaptive`, host/render/adaptive.h): the packed dispatch
// touches only the active pixels, the image agrees with uniform sampling within noise, and the
// result does not depend on how samples are split into calls. Validation layer on (GpuEnv).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "gpu_env.h"
#include "image_checks.h"
#include "render/adaptive.h"
#include "render_helpers.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

/// cornell-book3 at size x size pixels with mis and adaptive sampling (samples per dispatch: auto).
TestRender makeAdaptive(VulkanDevice& dev, std::uint32_t size, double threshold, std::uint32_t minSpp) {
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");
    scene.camera.width = size;
    scene.camera.height = size;
    RenderOptions o;
    o.sampler = Sampler::Mis;
    o.adaptiveThreshold = threshold;
    o.adaptiveMinSpp = minSpp;
    return makeRender(dev, std::move(scene), o);
}

// Stopped pixels keep their sums bit for bit while the others go on, and every active pixel gets
// exactly the image samples of the sample indices it was given (the list covers each once).
TEST(GpuAdaptive, OnlyActivePixelsReceiveSamples) {
    VKP_REQUIRE_DEVICE(dev);
    TestRender r = makeAdaptive(dev, 40, 0.08, 32);
    r.renderer->addSamples(64);
    const std::uint32_t pixels = 40 * 40;
    const std::vector<std::uint8_t> mask = r.renderer->activeMask();
    const std::uint32_t active = r.renderer->activePixels();
    std::printf("after 64 spp: %u of %u pixels active\n", active, pixels);
    ASSERT_GT(active, 0u);
    ASSERT_LT(active, pixels) << "no pixel stopped: the test would not exercise the packing";
    const PixelSums before = r.renderer->readSums();
    r.renderer->addSamples(16);  // no decision in between: 64 + 16 is the next decision point
    const PixelSums after = r.renderer->readSums();
    ASSERT_EQ(r.renderer->counters().nonfinite, 0u);
    for (std::uint32_t i = 0; i < pixels; ++i) {
        if (!mask[i]) {
            EXPECT_EQ(0, std::memcmp(&before.sum[4 * i], &after.sum[4 * i], 4 * sizeof(double))) << "stopped pixel " << i;
        } else {
            EXPECT_EQ(after.sum[4 * i + 3] - before.sum[4 * i + 3], double(imageSamplesBefore(80) - imageSamplesBefore(64)))
                << "active pixel " << i;
        }
    }
}

// The adaptive decisions happen at fixed sample counts: splitting the same samples into other
// calls gives the same bits.
TEST(GpuAdaptive, IndependentOfHowSamplesAreSplit) {
    VKP_REQUIRE_DEVICE(dev);
    TestRender a = makeAdaptive(dev, 24, 0.08, 32);
    a.renderer->addSamples(100);
    TestRender b = makeAdaptive(dev, 24, 0.08, 32);
    for (std::uint32_t n : {7u, 30u, 1u, 50u, 12u}) b.renderer->addSamples(n);
    EXPECT_EQ(a.renderer->activeMask(), b.renderer->activeMask());
    const PixelSums sa = a.renderer->readSums(), sb = b.renderer->readSums();
    EXPECT_TRUE(litAndNotConstant(sa.mean(), "adaptive cornell-book3, 100 spp in one call"));
    EXPECT_EQ(0, std::memcmp(sa.sum.data(), sb.sum.data(), sa.sum.size() * sizeof(double)));
}

// Unbiased: an adaptive render (many pixels stop early) and a uniform one of the same scene agree
// block by block within their noise. 16 blocks x 3 channels = 48 two-sided z-tests at the Sidak
// level for a family-wise false-failure probability of 0.01 (per test 2.1e-4, |z| < 3.71); block
// means average >= 64 pixels of >= 48 image samples each, close to normal.
TEST(GpuAdaptive, AgreesWithUniformSamplingWithinNoise) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t size = 32;
    TestRender ad = makeAdaptive(dev, size, 0.04, 64);
    ad.renderer->addSamples(1024);
    TestRender un = makeRender(dev, scenesDir() / "cornell-book3.json", size, size, Sampler::Mis);
    un.renderer->addSamples(512);
    const double meanSpp = double(ad.renderer->samplesTaken()) / (size * size);
    std::printf("adaptive: %.1f spp on average, %u pixels active at 1024 spp\n", meanSpp, ad.renderer->activePixels());
    EXPECT_LT(meanSpp, 1024.0 * 0.9) << "too few pixels stopped for this test to mean anything";
    const PixelSums sa = ad.renderer->readSums(), su = un.renderer->readSums();
    EXPECT_TRUE(litAndNotConstant(sa.mean(), "cornell-book3, adaptive"));
    EXPECT_TRUE(litAndNotConstant(su.mean(), "cornell-book3, uniform"));
    const Image ma = sa.mean(), va = sa.varianceOfMean(), mu = su.mean(), vu = su.varianceOfMean();
    double maxZ = 0;
    for (std::uint32_t by = 0; by < size; by += 8)
        for (std::uint32_t bx = 0; bx < size; bx += 8)
            for (int c = 0; c < 3; ++c) {
                double d = 0, v = 0;
                for (std::uint32_t y = by; y < by + 8; ++y)
                    for (std::uint32_t x = bx; x < bx + 8; ++x) {
                        d += ma.at(x, y, c) - mu.at(x, y, c);
                        v += va.at(x, y, c) + vu.at(x, y, c);
                    }
                const double z = d / std::sqrt(v);
                maxZ = std::max(maxZ, std::abs(z));
                EXPECT_LT(std::abs(z), 3.71) << "block " << bx << "," << by << " channel " << c;
            }
    std::printf("max |z| over 48 block comparisons: %.2f\n", maxZ);
}

}  // namespace
}  // namespace vkp::test
