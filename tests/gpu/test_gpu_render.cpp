// The integrator on a device: analytic answers, determinism, agreement of the samplers, and no
// non-finite samples on any shipped scene. Validation layer on: any message fails (GpuEnv).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <tuple>

#include "core/errors.h"
#include "gpu_env.h"
#include "bvh_test_scenes.h"
#include "image_checks.h"
#include "render/gpu_arrays.h"
#include "render/workgroup.h"
#include "scene/gltf.h"
#include "render_helpers.h"
#include "sums_agreement.h"
#include "test_paths.h"
#include "vk/compute_pipeline.h"

namespace vkp::test {
namespace {

std::filesystem::path writeScene(const std::string& name, const std::string& json) {
    auto p = scratchDir("gpu_render") / name;
    std::ofstream(p) << json;
    return p;
}

// A lambertian sphere (albedo a) under a uniform background of radiance 1, seen by a camera that
// it fills in the middle. Light reflected off a convex object never returns to it, so every
// sample of a pixel that sees the sphere is exactly a, whatever the sampler: the estimator has no
// variance and the test tolerance is float rounding.
TEST(GpuRender, WhiteFurnaceConvexSphereEqualsAlbedo) {
    VKP_REQUIRE_DEVICE(dev);
    const auto file = writeScene("furnace.json", R"({
      "camera": {"lookfrom": [0, 0, 4], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 24, "height": 24},
      "render": {"spp": 8, "max_depth": 50, "background": [1, 1, 1]},
      "materials": {"m": {"type": "lambertian", "albedo": [0.2, 0.5, 0.8]}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
    for (Sampler s : kAllSamplers) {
        TestRender r = makeRender(dev, file, 24, 24, s);
        r.renderer->addSamples(8);
        const Image img = r.renderer->image();
        // Pixels within the sphere's inner disc (its radius on screen is ~8.6 px): exactly albedo.
        for (std::uint32_t y = 8; y < 16; ++y)
            for (std::uint32_t x = 8; x < 16; ++x) {
                EXPECT_NEAR(img.at(x, y, 0), 0.2f, 1e-5f) << samplerName(s) << " at " << x << "," << y;
                EXPECT_NEAR(img.at(x, y, 1), 0.5f, 1e-5f);
                EXPECT_NEAR(img.at(x, y, 2), 0.8f, 1e-5f);
            }
        // Corners see only the background.
        EXPECT_FLOAT_EQ(img.at(0, 0, 1), 1.0f);
        EXPECT_FLOAT_EQ(img.at(23, 23, 1), 1.0f);
        EXPECT_EQ(r.renderer->counters().nonfinite, 0u);
    }
}

// Pixel sums are compensated (shared/compensated_sum.h): a pixel that sees a constant 0.1 (not a
// float) keeps its mean to ~1e-10 relative after 2^16 samples, where a float32 running sum drifts
// by ~1e-4 (computed below for the same values, to show the tolerance would catch it).
// Deterministic: every sample is exactly float(0.1), no randomness reaches the sums.
TEST(GpuRender, ConstantPixelMeanDoesNotDriftAtHighSpp) {
    VKP_REQUIRE_DEVICE(dev);
    const auto file = writeScene("constant.json", R"({
      "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vup": [0, 1, 0], "vfov": 40, "width": 8, "height": 8},
      "render": {"spp": 1, "max_depth": 4, "background": [0.1, 0.3, 0.7]},
      "materials": {"m": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "sphere", "center": [0, 0, 10], "radius": 1, "material": "m"}]})");
    constexpr std::uint32_t kSpp = 1u << 16;
    TestRender r = makeRender(dev, file, 8, 8, Sampler::Bsdf, 4096);
    r.renderer->addSamples(kSpp);
    const PixelSums sums = r.renderer->readSums();
    const float bg[3] = {0.1f, 0.3f, 0.7f};
    constexpr double kTol = 1e-8;  // relative; the double-float pair errs by <= ~n eps^2 = 2.3e-10
    for (int c = 0; c < 3; ++c) {
        float naive = 0.0f;
        for (std::uint32_t i = 0; i < kSpp; ++i) naive += bg[c];
        const double naiveErr = std::abs(double(naive) / kSpp / double(bg[c]) - 1.0);
        EXPECT_GT(naiveErr, 100 * kTol) << "a float32 sum would not drift: the test has no teeth";
        for (std::size_t i = 0; i < 64; ++i) {
            ASSERT_EQ(sums.sum[4 * i + 3], double(kSpp));
            EXPECT_NEAR(sums.sum[4 * i + c] / kSpp / double(bg[c]), 1.0, kTol) << "pixel " << i << " channel " << c;
            const double sq = double(bg[c]) * double(bg[c]);
            EXPECT_NEAR(sums.sumSq[4 * i + c] / kSpp / sq, 1.0, 1e-6) << "pixel " << i << " channel " << c;
        }
        std::printf("channel %d: float32 running sum would be off by %.2e relative\n", c, naiveErr);
    }
}

// The same seed, spp and device give the same bits however samples are split into dispatches
// and submissions (RNG keyed by pixel, sample index, seed; sums added in sample order).
TEST(GpuRender, BitIdenticalAcrossDispatchSplits) {
    VKP_REQUIRE_DEVICE(dev);
    const auto file = scenesDir() / "cornell-book3.json";
    TestRender a = makeRender(dev, file, 20, 20, Sampler::Mixture, 1);
    a.renderer->addSamples(6);
    TestRender b = makeRender(dev, file, 20, 20, Sampler::Mixture, 2);
    b.renderer->addSamples(2);
    b.renderer->addSamples(4);
    TestRender c = makeRender(dev, file, 20, 20, Sampler::Mixture, 3);
    c.renderer->addSamples(1);
    c.renderer->addSamples(5);
    const PixelSums sa = a.renderer->readSums(), sb = b.renderer->readSums(), sc = c.renderer->readSums();
    EXPECT_TRUE(litAndNotConstant(sa.mean(), "cornell-book3, 6 spp in one call"));  // identical renders of nothing prove nothing
    ASSERT_EQ(sa.sum.size(), sb.sum.size());
    EXPECT_EQ(0, std::memcmp(sa.sum.data(), sb.sum.data(), sa.sum.size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(sa.sum.data(), sc.sum.data(), sa.sum.size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(sa.sumSq.data(), sc.sumSq.data(), sa.sumSq.size() * sizeof(double)));
}

// The rounding probe (device_rounding.h) on this device. A CPU device (lavapipe, CI's) must round
// as the host, or the bit-for-bit comparisons of these tests would turn rounding-tolerant on it
// unnoticed. The probe's operands are such that the roundings a GPU may use would show: a division
// as a multiplication by the reciprocal and a fused a * b + c each give other bits for many of them.
TEST(GpuRender, CpuDevicesRoundLikeTheHost) {
    VKP_REQUIRE_DEVICE(dev);
    const RoundingProbe& p = probeRounding(dev);
    std::printf("%s: %s\n", dev.info().name.c_str(), p.describe().c_str());
    ASSERT_EQ(p.items, 4096u);
    int viaReciprocal = 0, fused = 0;
    for (const glm::vec4& v : roundingProbeInputs()) {
        const volatile float reciprocal = 1.0f / v.y, product = v.x * v.y;
        const float quotient = v.x / v.y, unfused = product + v.z;
        viaReciprocal += v.x * reciprocal != quotient;
        fused += std::fma(v.x, v.y, v.z) != unfused;
    }
    std::printf("the probe's operands: a * (1 / b) != a / b for %d, fma(a, b, c) != a * b + c for %d of 4096\n",
                viaReciprocal, fused);
    EXPECT_GT(viaReciprocal, 400);
    EXPECT_GT(fused, 400);
    if (dev.info().kind == DeviceKind::Cpu) EXPECT_TRUE(p.exact()) << p.describe();
}

// The rounding-tolerant comparison of two renders (sums_agreement.h, used on a device that rounds
// otherwise than the host), measured here: the camera moved by 1e-3 (4e-6 of the box; every ray's
// arithmetic rounds differently, the random numbers are the same) changes the bits but stays within
// rounding; another seed (other samples of the same image) is refused many times over.
TEST(GpuRender, RoundingTolerantComparisonSeparatesRoundingFromOtherSamples) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");
    scene.camera.width = 48;
    scene.camera.height = 32;
    auto render = [&](const Scene& s) {
        RenderOptions o;
        o.samplesPerDispatch = 4;
        TestRender r = makeRender(dev, s, o);
        r.renderer->addSamples(8);
        return r.renderer->readSums();
    };
    Scene moved = scene, reseeded = scene;
    moved.camera.lookfrom.x += 1e-3f;
    reseeded.render.seed = scene.render.seed + 7;
    const PixelSums a = render(scene);
    ASSERT_TRUE(litAndNotConstant(a.mean(), "cornell-book3 48x32"));
    const SumsAgreement m = compareSums(a, render(moved)), r = compareSums(a, render(reseeded));
    std::printf("camera moved by 1e-3: %zu of %zu pixels beyond %.0e, total %.2e; another seed: %zu pixels beyond, total %.2e\n",
                m.beyond, m.pixels, kPixelRelative, m.totalRelative, r.beyond, r.totalRelative);
    EXPECT_FALSE(m.identical) << "the move must reach the sums' bits, or this measures nothing";
    EXPECT_TRUE(m.withinRounding());
    EXPECT_FALSE(r.withinRounding());
    EXPECT_GT(r.beyond, 20 * r.allowedBeyond());
}

// Automatic samples per dispatch: on lavapipe (a CPU device: no watchdog) only the loop budget
// limits them, so a small image reaches 32 (Renderer::maxAutoSamplesPerDispatch; a GPU's most is 8); a time target of a microsecond (what a GPU's would be to
// a dispatch far slower than it) holds them at 1, measured from device timestamps, and the sums do
// not change.
TEST(GpuRender, DispatchTimeTargetHoldsTheSamplesPerDispatchDown) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");
    scene.camera.width = 16;
    scene.camera.height = 16;
    PixelSums sums[2];
    std::uint32_t spd[2];
    for (int k = 0; k < 2; ++k) {
        RenderOptions o;
        o.targetDispatchSeconds = k == 0 ? -1.0 : 1e-6;
        TestRender r = makeRender(dev, scene, o);
        for (int batch = 0; batch < 6; ++batch) r.renderer->addSamples(8);
        spd[k] = r.renderer->samplesPerDispatch();
        EXPECT_GT(r.renderer->longestDispatchSeconds(), 0.0);  // timestamps (lavapipe has them) or wall time
        EXPECT_LT(r.renderer->longestDispatchSeconds(), 5.0);
        sums[k] = r.renderer->readSums();
    }
    EXPECT_EQ(spd[0], dev.info().kind == DeviceKind::Cpu ? 32u : 8u)
        << "no time target that a 16x16 dispatch misses: the loop budget alone, up to the device kind's most";
    EXPECT_EQ(spd[1], 1u) << "a target no dispatch can meet";
    ASSERT_TRUE(litAndNotConstant(sums[0].mean(), "cornell-book3 16x16"));
    EXPECT_EQ(0, std::memcmp(sums[0].sum.data(), sums[1].sum.data(), sums[0].sum.size() * sizeof(double)));
}

// Several pixels per invocation (RenderOptions::pixelsPerInvocation: the PIXEL_SLOTS pipeline,
// shaders/pathtrace.comp) change which invocation traces a pixel's samples, never the samples or
// their order: the sums, the feature sums and adaptive sampling's choices are those of one pixel
// per invocation, whatever the slots, the samples per dispatch and the workgroup size. 23 x 17
// pixels: neither the tiles nor the active pixels divide by the slots.
TEST(GpuRender, SeveralPixelsPerInvocationGiveTheSameSamples) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");  // glass: paths of very different lengths
    scene.camera.width = 23;
    scene.camera.height = 17;
    const bool exactAovs = dev.info().kind == DeviceKind::Cpu;  // rounds like the host (CpuDevicesRoundLikeTheHost)
    for (double adaptive : {0.0, 0.5}) {
        auto render = [&](std::uint32_t slots, std::uint32_t spd, std::uint32_t wx, std::uint32_t wy) {
            RenderOptions o;
            o.pixelsPerInvocation = slots;
            o.samplesPerDispatch = spd;
            o.workgroupX = wx;
            o.workgroupY = wy;
            o.aov = true;
            o.adaptiveThreshold = adaptive;
            o.adaptiveMinSpp = 4;
            TestRender r = makeRender(dev, scene, o);
            for (std::uint32_t n : {1u, 5u, 18u}) r.renderer->addSamples(n);  // 24 in submissions of several sizes
            EXPECT_EQ(r.renderer->maxPixelsPerInvocation(), slots);
            return std::tuple{r.renderer->readSums(), r.renderer->readAovSums(), r.renderer->activePixels()};
        };
        const auto [sums, aovs, active] = render(1, 4, 0, 0);
        ASSERT_TRUE(litAndNotConstant(sums.mean(), "cornell-book3 23x17"));
        if (adaptive > 0) EXPECT_LT(active, 23u * 17u) << "adaptive sampling must stop some pixels";
        for (const auto& [slots, spd, wx, wy] : {std::tuple{2u, 4u, 0u, 0u}, std::tuple{3u, 1u, 0u, 0u},
                                                std::tuple{7u, 2u, 4u, 4u}, std::tuple{64u, 1u, 0u, 0u}}) {
            const std::string what = std::to_string(slots) + " pixels per invocation, " + std::to_string(spd) +
                                     " samples per dispatch" + (wx ? ", 4x4" : "") + (adaptive > 0 ? ", adaptive" : "");
            const auto [s, a, act] = render(slots, spd, wx, wy);
            EXPECT_TRUE(sameSamples(dev, sums, s, what));  // the PIXEL_SLOTS pipeline is another compiled kernel
            EXPECT_EQ(act, active) << what;
            ASSERT_EQ(a.size(), aovs.size());
            if (exactAovs) EXPECT_EQ(0, std::memcmp(a.data(), aovs.data(), a.size() * sizeof(float))) << what;
        }
    }
}

// The automatic choice (RenderOptions::pixelsPerInvocation 0): a small image keeps one pixel per
// invocation, even in a submission of one sample; on a CPU device an image where one dispatch of
// the samples per dispatch would outlast Renderer::kSlotSeconds takes several in its one-sample
// submissions, as a session's large renders have them. 2048x1024 pixels of the Cornell box take
// 0.9 s per sample on lavapipe with 2 threads, so the rule holds on CPUs up to ~14x this
// machine's (docs/performance.md "Dispatch size"). A GPU keeps one pixel per invocation.
TEST(GpuRender, LargeImagesTakeSeveralPixelsPerInvocationOnACpuDevice) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-classic.json");
    scene.camera.width = 32;
    scene.camera.height = 32;
    {
        TestRender r = makeRender(dev, scene, RenderOptions{});
        for (std::uint32_t n : {1u, 8u, 8u, 8u, 1u, 1u}) r.renderer->addSamples(n);
        EXPECT_EQ(r.renderer->samplesPerDispatch(), r.renderer->maxAutoSamplesPerDispatch());
        EXPECT_EQ(r.renderer->maxPixelsPerInvocation(), 1u) << "a 32x32 image's dispatches are short";
    }
    scene.camera.width = 2048;
    scene.camera.height = 1024;
    TestRender r = makeRender(dev, scene, RenderOptions{});
    for (int k = 0; k < 5; ++k) r.renderer->addSamples(1);
    if (dev.info().kind == DeviceKind::Cpu) {
        EXPECT_GT(r.renderer->maxPixelsPerInvocation(), 1u);
        EXPECT_EQ(r.renderer->pixelsPerInvocation(1), std::min(r.renderer->samplesPerDispatch(), Renderer::kSlotSamples));
    } else {
        EXPECT_EQ(r.renderer->maxPixelsPerInvocation(), 1u);
    }
    EXPECT_EQ(r.renderer->counters().loopGuard, 0u);
    ASSERT_TRUE(litAndNotConstant(r.renderer->image(), "cornell-classic 2048x1024"));
}

// The workgroup size and the tile order only change which invocation computes a pixel, never its
// samples: the sums are bit-identical, with and without adaptive sampling (whose packed list of
// active pixels is laid out by workgroup size too). 21 x 13 pixels: no size divides it.
TEST(GpuRender, BitIdenticalAcrossWorkgroupSizesAndTileOrders) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");
    scene.camera.width = 21;
    scene.camera.height = 13;
    for (double adaptive : {0.0, 0.5}) {
        PixelSums first;
        for (const auto& [wx, wy, linear] : {std::tuple{0u, 0u, false}, std::tuple{8u, 8u, true}, std::tuple{16u, 4u, false},
                                             std::tuple{3u, 5u, true}, std::tuple{32u, 32u, false}, std::tuple{1u, 1u, false}}) {
            RenderOptions o;
            o.sampler = Sampler::Mis;
            o.samplesPerDispatch = 4;
            o.workgroupX = wx;
            o.workgroupY = wy;
            o.linearTiles = linear;
            o.adaptiveThreshold = adaptive;
            o.adaptiveMinSpp = 4;
            TestRender r = makeRender(dev, scene, o);
            if (wx == 0) {  // auto: the device's (render/workgroup.h), which the kernel then runs with
                const std::uint32_t lanes = dev.info().subgroupSize;
                EXPECT_TRUE(lanes != 0 && (lanes & (lanes - 1)) == 0) << "Vulkan 1.1 reports a power of two: " << lanes;
                const glm::uvec2 expected = autoWorkgroup(deviceLimits(dev.info()));
                EXPECT_EQ(r.renderer->features().workgroupX, expected.x);
                EXPECT_EQ(r.renderer->features().workgroupY, expected.y);
                EXPECT_EQ(r.renderer->features().specConstants().at(VKP_SPEC_WORKGROUP_X), expected.x);
            }
            r.renderer->addSamples(24);
            const PixelSums s = r.renderer->readSums();
            const std::string what = (wx ? std::to_string(wx) + "x" + std::to_string(wy) : std::string("auto")) +
                                     (linear ? " linear" : " scrambled") +
                                     (adaptive > 0 ? " adaptive" : "");
            if (first.sum.empty()) {
                first = s;
                EXPECT_TRUE(litAndNotConstant(first.mean(), what));
                if (adaptive > 0) EXPECT_LT(r.renderer->activePixels(), 21u * 13u) << "adaptive sampling must stop some pixels";
                continue;
            }
            ASSERT_EQ(first.sum.size(), s.sum.size());
            EXPECT_TRUE(sameSamples(dev, first, s, what));  // another workgroup size is another compiled kernel
        }
    }
    // Beyond the device's limits: one clear error, no crash.
    RenderOptions big;
    big.workgroupX = 64;
    big.workgroupY = 64;
    EXPECT_THROW(makeRender(dev, scene, big), DeviceError);
}

// An image whose accumulation buffers exceed one storage binding is rendered in bands of rows
// (render/gpu_arrays.h planBands), each with buffers of its own: the sums are bit-identical to the
// one-band render, with and without adaptive sampling and for workgroups whose height does not
// divide 8. The bands are forced here by pretending the device's maxStorageBufferRange is 8 rows
// of the image; the next test meets the real limit.
TEST(GpuRender, BitIdenticalAcrossBands) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");
    scene.camera.width = 40;
    scene.camera.height = 37;
    DeviceLimits small = deviceLimits(dev.info());
    small.maxStorageBufferRange = 8 * 40 * 32;
    for (double adaptive : {0.0, 0.5})
        for (const auto& [wx, wy] : {std::pair{8u, 8u}, std::pair{3u, 5u}}) {
            RenderOptions o;
            o.samplesPerDispatch = 4;
            o.workgroupX = wx;
            o.workgroupY = wy;
            o.adaptiveThreshold = adaptive;
            o.adaptiveMinSpp = 8;
            const std::string what = std::to_string(wx) + "x" + std::to_string(wy) + (adaptive > 0 ? " adaptive" : "");
            // Bands of 8 rows (8x8) or 40 rows (3x5: lcm(8, 5)), the latter more than fits the
            // pretended binding: then the render is refused.
            if (wy == 5) {
                EXPECT_THROW(makeRender(dev, scene, o, &small), DeviceError) << what;
                continue;
            }
            TestRender one = makeRender(dev, scene, o);
            TestRender banded = makeRender(dev, scene, o, &small);
            ASSERT_EQ(one.renderer->bandCount(), 1u);
            EXPECT_EQ(banded.renderer->bandCount(), 5u) << what;
            one.renderer->addSamples(24);
            banded.renderer->addSamples(24);
            const PixelSums a = one.renderer->readSums(), b = banded.renderer->readSums();
            EXPECT_TRUE(litAndNotConstant(a.mean(), "cornell-book3 40x37 " + what));
            EXPECT_EQ(0, std::memcmp(a.sum.data(), b.sum.data(), a.sum.size() * sizeof(double))) << what;
            EXPECT_EQ(0, std::memcmp(a.sumSq.data(), b.sumSq.data(), a.sumSq.size() * sizeof(double))) << what;
            EXPECT_EQ(one.renderer->activePixels(), banded.renderer->activePixels()) << what;
            if (adaptive > 0) EXPECT_LT(one.renderer->activePixels(), 40u * 37u) << "adaptive sampling must stop some pixels";
            // Bands with several pixels per invocation (the slots stay within a band).
            RenderOptions os = o;
            os.pixelsPerInvocation = 3;
            TestRender slotted = makeRender(dev, scene, os, &small);
            slotted.renderer->addSamples(24);
            EXPECT_TRUE(sameSamples(dev, a, slotted.renderer->readSums(), what + ", banded, 3 pixels per invocation"));
            EXPECT_EQ(one.renderer->activePixels(), slotted.renderer->activePixels()) << what;
        }
    // With room for 40 rows the 3x5 workgroup splits too.
    small.maxStorageBufferRange = 40 * 40 * 32;
    RenderOptions o;
    o.samplesPerDispatch = 4;
    o.workgroupX = 3;
    o.workgroupY = 5;
    Scene tall = scene;
    tall.camera.height = 90;
    TestRender one = makeRender(dev, tall, o), banded = makeRender(dev, tall, o, &small);
    EXPECT_EQ(banded.renderer->bandCount(), 3u);
    one.renderer->addSamples(8);
    banded.renderer->addSamples(8);
    const PixelSums a = one.renderer->readSums(), b = banded.renderer->readSums();
    EXPECT_EQ(0, std::memcmp(a.sum.data(), b.sum.data(), a.sum.size() * sizeof(double)));
}

// The real limit: lavapipe's maxStorageBufferRange holds 2048 x 2048 pixels; 2056 x 2048 needs two
// bands. One sample at max depth 2 on the validation layer (a binding beyond the range would be a
// validation message, which fails the render): no message, and the last band's rows are lit like
// the rows just above it (a band whose buffers were not written would be black). A GPU's range
// (often 4 GiB: 134 M pixels, more than a test should allocate) holds this image in one band; there
// the bands are forced at lavapipe's range, which still renders and checks them but does not meet
// the device's own limit (said in the output). Skipping instead would fail under CI=true, as in
// tools/gpu-check.sh.
TEST(GpuRender, ImagesBeyondOneBindingRenderInBands) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "env-sky.json");  // sky everywhere: every row is lit
    scene.camera.width = 2056;
    scene.camera.height = 2048;
    scene.render.maxDepth = 2;
    RenderOptions o;
    o.samplesPerDispatch = 1;
    DeviceLimits limits = deviceLimits(dev.info());
    const std::uint64_t lavapipeRange = std::uint64_t(2048) * 2048 * 32;
    const bool realLimit = std::uint64_t(2056) * 2048 * 32 > limits.maxStorageBufferRange;
    if (!realLimit) {
        std::printf("  this device's maxStorageBufferRange (%llu bytes) holds the image in one band: bands forced at %llu\n",
                    static_cast<unsigned long long>(limits.maxStorageBufferRange),
                    static_cast<unsigned long long>(lavapipeRange));
        limits.maxStorageBufferRange = lavapipeRange;
    }
    TestRender r = makeRender(dev, scene, o, realLimit ? nullptr : &limits);
    ASSERT_GE(r.renderer->bandCount(), 2u);
    r.renderer->addSamples(1);
    EXPECT_EQ(r.renderer->counters().loopGuard, 0u);
    const Image img = r.renderer->image();
    auto rowsMean = [&](std::uint32_t y0, std::uint32_t y1) {
        double sum = 0;
        for (std::uint32_t y = y0; y < y1; ++y)
            for (std::uint32_t x = 0; x < img.width; ++x) sum += img.at(x, y, 1);
        return sum / (double(y1 - y0) * img.width);
    };
    // The last band holds the last rows of the image; the first band ends just above them. Over
    // ~16,000 pixels each at 1 spp, the two means of a smooth sky and ground agree to a few percent.
    const Band last{2048 - 8, 8};
    ASSERT_EQ(planBands(r.arrays, limits).back().firstRow, last.firstRow);
    const double above = rowsMean(last.firstRow - 8, last.firstRow), inLast = rowsMean(last.firstRow, 2048);
    std::printf("  green mean of the 8 rows above the last band %.4f, of the last band %.4f\n", above, inLast);
    EXPECT_GT(above, 0.01);
    EXPECT_GT(inLast, 0.5 * above) << "the last band's rows";
}

// `--light-sampling auto` is a per-point choice between the other two: with its switch at 0 sr
// every point qualifies and the image is bit for bit `solid-angle`'s; with the switch beyond any
// size in the box it is `area`'s. Between them (the default) it differs from both, since near the
// ceiling light it samples in solid angle and elsewhere in area. (cornell-classic: its light is a
// rectangle; the glass and metal of book3 are not needed here.)
TEST(GpuRender, AutoLightSamplingIsSolidAngleOrAreaPerPoint) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-classic.json");
    scene.camera.width = 24;
    scene.camera.height = 24;
    auto render = [&](LightSampling ls, float minSize) {
        RenderOptions o;
        o.sampler = Sampler::Mis;
        o.samplesPerDispatch = 4;
        o.lightSampling = ls;
        o.solidAngleMinSize = minSize;
        TestRender r = makeRender(dev, scene, o);
        r.renderer->addSamples(16);
        return r.renderer->readSums();
    };
    // Differences are asked of the bits (on a device that rounds otherwise than the host that is
    // weaker, device_rounding.h); sameness of the samples, of the bits or up to rounding.
    auto differ = [](const PixelSums& a, const PixelSums& b) { return !compareSums(a, b).identical; };
    const PixelSums solid = render(LightSampling::SolidAngle, 0.0f), area = render(LightSampling::Area, 0.0f);
    EXPECT_TRUE(litAndNotConstant(solid.mean(), "cornell-classic, solid-angle"));
    EXPECT_TRUE(litAndNotConstant(area.mean(), "cornell-classic, area"));
    EXPECT_TRUE(differ(solid, area));
    EXPECT_TRUE(sameSamples(dev, render(LightSampling::Auto, 0.0f), solid, "auto with its switch at 0 sr"));
    EXPECT_TRUE(sameSamples(dev, render(LightSampling::Auto, 1e9f), area, "auto with its switch beyond any size"));
    const PixelSums mid = render(LightSampling::Auto, kSolidAngleMinSize);
    EXPECT_TRUE(differ(mid, solid));
    EXPECT_TRUE(differ(mid, area));
}

/// Mean and variance-of-mean of square blocks of pixels, per channel.
struct Blocks {
    std::vector<double> mean, var;
};
Blocks blockStats(const PixelSums& s, std::uint32_t block) {
    const Image m = s.mean(), v = s.varianceOfMean();
    Blocks b;
    for (std::uint32_t by = 0; by + block <= s.height; by += block)
        for (std::uint32_t bx = 0; bx + block <= s.width; bx += block)
            for (int c = 0; c < 3; ++c) {
                double sm = 0, sv = 0;
                for (std::uint32_t y = by; y < by + block; ++y)
                    for (std::uint32_t x = bx; x < bx + block; ++x) {
                        sm += m.at(x, y, c);
                        sv += v.at(x, y, c);
                    }
                const double n = double(block) * block;
                b.mean.push_back(sm / n);
                b.var.push_back(sv / (n * n));
            }
    return b;
}

// Every sampler estimates the same integral: block means agree within their noise.
// 16 blocks x 3 channels x 6 pairs = 288 z-tests; the threshold 4.15 is the Sidak-corrected
// two-sided bound for a suite-wide false-failure probability of 0.01 (per test 3.5e-5), assuming
// the block means (16k samples each) are close to normal.
TEST(GpuRender, SamplersAgreeOnCornellBook3) {
    VKP_REQUIRE_DEVICE(dev);
    const auto file = scenesDir() / "cornell-book3.json";
    const std::uint32_t size = 32, spp = 256;
    std::vector<Blocks> results;
    for (Sampler s : kAllSamplers) {
        TestRender r = makeRender(dev, file, size, size, s);
        r.renderer->addSamples(spp);
        EXPECT_EQ(r.renderer->counters().nonfinite, 0u) << samplerName(s);
        EXPECT_EQ(r.renderer->counters().loopGuard, 0u) << samplerName(s);
        const PixelSums sums = r.renderer->readSums();
        EXPECT_TRUE(litAndNotConstant(sums.mean(), std::string("cornell-book3, ") + samplerName(s)));
        results.push_back(blockStats(sums, 8));
    }
    const std::size_t n = results.size();
    double maxZ = 0;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = 0; k < results[i].mean.size(); ++k) {
                const double z = (results[i].mean[k] - results[j].mean[k]) / std::sqrt(results[i].var[k] + results[j].var[k]);
                maxZ = std::max(maxZ, std::abs(z));
                EXPECT_LT(std::abs(z), 4.15) << samplerName(kAllSamplers[i]) << " vs " << samplerName(kAllSamplers[j]) << " block " << k / 3 << " channel " << k % 3
                                            << ": " << results[i].mean[k] << " vs " << results[j].mean[k];
            }
    std::printf("max |z| over %zu block comparisons: %.2f\n", results[0].mean.size() * n * (n - 1) / 2, maxZ);
}

// Every shipped scene, every sampler: no NaN/Inf sample and no path cut by the loop guard.
TEST(GpuRender, NoNonFiniteSamplesOnShippedScenes) {
    VKP_REQUIRE_DEVICE(dev);
    for (const char* name : {"cornell-book3.json", "cornell-classic.json", "cornell-lights.json", "cornell-biglight.json", "spheres-book1.json", "env-sky.json",
                             "lamps.json", "next-week/checkered-spheres.json", "next-week/earth.json", "next-week/perlin-spheres.json",
                             "next-week/quads.json", "next-week/simple-light.json", "next-week/cornell-box.json",
                             "next-week/cornell-smoke.json", "next-week/bouncing-spheres.json", "next-week/final-scene.json"}) {
        for (Sampler s : kAllSamplers) {
            TestRender r = makeRender(dev, scenesDir() / name, 32, 24, s);
            r.renderer->addSamples(8);
            const RenderCounters c = r.renderer->counters();
            EXPECT_EQ(c.nonfinite, 0u) << name << " " << samplerName(s);
            EXPECT_EQ(c.loopGuard, 0u) << name << " " << samplerName(s);
            EXPECT_GT(c.rays, 32u * 24u * 8u) << name;
        }
    }
}

}  // namespace
}  // namespace vkp::test

namespace vkp::test {
namespace {

// The variant compiled for the scene (specialization constants false for unused kinds) computes
// the same samples as the pipeline with every feature compiled in.
TEST(GpuRender, SceneVariantMatchesFullVariant) {
    VKP_REQUIRE_DEVICE(dev);
    for (const char* name : {"cornell-book3.json", "spheres-book1.json", "lamps.json", "next-week/simple-light.json",
                             "next-week/cornell-smoke.json", "next-week/bouncing-spheres.json"}) {
        Scene scene = loadSceneJson(scenesDir() / name);
        scene.camera.width = 24;
        scene.camera.height = 16;
        RenderOptions o;
        TestRender variant = makeRender(dev, scene, o);
        o.fullVariant = true;
        TestRender full = makeRender(dev, scene, o);
        EXPECT_NE(variant.renderer->features().name(), full.renderer->features().name());
        variant.renderer->addSamples(4);
        full.renderer->addSamples(4);
        const PixelSums a = variant.renderer->readSums(), b = full.renderer->readSums();
        EXPECT_TRUE(litAndNotConstant(a.mean(), std::string(name) + ", scene variant"));
        EXPECT_TRUE(sameSamples(dev, a, b, name));
    }
}

// Specialization constants baked in on the host (vk/spirv_specialize.h: constants folded, dead
// code removed before the driver sees the kernel) render bit for bit what the driver's own
// specialization renders. Each scene's own variant, specialized on the host, against the full
// variant specialized by the driver (one driver compile for all scenes: their options agree; the
// full variant renders as the scene's own, SceneVariantMatchesFullVariant). The scenes cover every
// shape, material, light kind, texture kind, alpha, layers, vertex colours, instancing, motion,
// media, defocus, the environment and the feature images. Fails if baking a value, folding or
// removing code changed what the kernel computes.
TEST(GpuRender, HostSpecializationRendersTheSameBits) {
    VKP_REQUIRE_DEVICE(dev);
    struct Case {
        const char* file;
        bool aov;
    };
    for (const Case c : {Case{"cornell-book3.json", false}, Case{"spheres-book1.json", false}, Case{"env-sky.json", false},
                         Case{"lamps.json", false}, Case{"next-week/cornell-smoke.json", false},
                         Case{"next-week/bouncing-spheres.json", false}, Case{"next-week/final-scene.json", false},
                         Case{"gltf/textures.gltf", false}, Case{"gltf/layer-textures.gltf", false}, Case{"gltf/alpha.gltf", false},
                         Case{"gltf/lights.gltf", false}, Case{"gltf/vertex-colors.gltf", false},
                         Case{"gltf/transmission-textures.gltf", false}, Case{"gltf/instances.gltf", false},
                         Case{"cornell-classic.json", true}}) {
        const std::filesystem::path file = scenesDir() / c.file;
        GltfOptions instancing;
        instancing.instancing = true;
        Scene scene = file.extension() == ".json" ? loadSceneJson(file) : loadSceneGltf(file, instancing);
        if (file.extension() != ".json") scene.render.background = glm::vec3(0.5f);  // most of these files bring no light
        scene.camera.width = 24;
        scene.camera.height = 16;
        RenderOptions o;
        o.aov = c.aov;
        TestRender host = makeRender(dev, scene, o);
        o.fullVariant = true;
        o.specializeOnHost = false;
        TestRender driver = makeRender(dev, scene, o);
        host.renderer->addSamples(4);
        driver.renderer->addSamples(4);
        const PixelSums a = host.renderer->readSums(), b = driver.renderer->readSums();
        EXPECT_TRUE(litAndNotConstant(a.mean(), std::string(c.file) + ", host specialization"));
        EXPECT_TRUE(sameSamples(dev, a, b, c.file));
    }
}

}  // namespace
}  // namespace vkp::test

namespace vkp::test {
namespace {

// Renderers of one variant on one device share its compiled pipeline (VulkanDevice::
// compiledPipelines; lavapipe spends seconds per compile), another variant gets its own, and the
// shared pipeline renders bit for bit what a pipeline compiled afresh (on a second device, which
// has its own) renders. Fails if sharing were keyed too loosely (a variant reusing another's code)
// or if a reused pipeline behaved differently from a fresh one.
TEST(GpuRender, RenderersOfOneVariantShareTheCompiledPipeline) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");
    scene.camera.width = 24;
    scene.camera.height = 16;
    RenderOptions o;
    o.samplesPerDispatch = 2;
    const std::uint64_t before = dev.compiledPipelines().compiled;
    TestRender first = makeRender(dev, scene, o);
    EXPECT_EQ(dev.compiledPipelines().compiled, before + 1);
    first.renderer->addSamples(4);
    const PixelSums a = first.renderer->readSums();
    first = TestRender{};  // the cache keeps the pipeline when its renderer is gone
    TestRender second = makeRender(dev, scene, o);
    EXPECT_EQ(dev.compiledPipelines().compiled, before + 1) << "same variant: reused";
    second.renderer->addSamples(4);
    const PixelSums b = second.renderer->readSums();
    EXPECT_TRUE(litAndNotConstant(a.mean(), "cornell-book3"));
    EXPECT_EQ(0, std::memcmp(a.sum.data(), b.sum.data(), a.sum.size() * sizeof(double)));
    RenderOptions light = o;
    light.sampler = Sampler::Light;
    TestRender other = makeRender(dev, scene, light);
    EXPECT_EQ(dev.compiledPipelines().compiled, before + 2) << "another sampler: another variant";

    VulkanDevice fresh(*GpuEnv::get().instance(), "");
    TestRender own = makeRender(fresh, scene, o);
    EXPECT_EQ(fresh.compiledPipelines().compiled, 1u);
    own.renderer->addSamples(4);
    const PixelSums c = own.renderer->readSums();
    EXPECT_EQ(0, std::memcmp(a.sum.data(), c.sum.data(), a.sum.size() * sizeof(double))) << "shared vs compiled afresh";
    EXPECT_EQ(0, std::memcmp(a.sumSq.data(), c.sumSq.data(), a.sumSq.size() * sizeof(double)));
}

/// A render over a BVH with spatial splits is the same estimator on the same random numbers: the
/// same closest hit on every ray, so the same image, except where a ray meets two primitives at
/// the same distance (a shared mesh edge), which the two trees may order differently.
TEST(GpuRender, SpatialSplitsRenderTheSameImage) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-classic.json");
    scene.camera.width = 64;
    scene.camera.height = 64;
    const std::uint32_t material = scene.shapes.front().material;
    const glm::vec3 c(278.0f, 200.0f, 278.0f);
    for (Shape s : sphereMesh(48, 48, 120.0f)) {  // a mesh, with two large slanted triangles through it
        for (glm::vec3* p : {&s.p0, &s.p1, &s.p2}) *p += c;
        s.material = material;
        scene.shapes.push_back(s);
    }
    scene.shapes.push_back(triangle(c + glm::vec3(-200, -150, -180), c + glm::vec3(190, 140, 200), c + glm::vec3(-160, 170, 20), material));
    scene.shapes.push_back(triangle(c + glm::vec3(200, -160, -190), c + glm::vec3(-190, 100, 210), c + glm::vec3(210, 170, -10), material));
    RenderOptions o;
    o.samplesPerDispatch = 4;
    BvhBuildOptions spatial;
    spatial.spatialSplits = 0.3f;  // as --spatial-splits
    TestRender plain = makeRender(dev, scene, o);
    TestRender split = makeRender(dev, scene, o, nullptr, spatial);
    ASSERT_GT(split.bvh.prims.size(), plain.bvh.prims.size()) << "no primitive was split";
    plain.renderer->addSamples(32);
    split.renderer->addSamples(32);
    const PixelSums a = plain.renderer->readSums(), b = split.renderer->readSums();
    ASSERT_EQ(a.sum.size(), b.sum.size());
    std::size_t differ = 0, pixels = a.sum.size() / 4;
    double sumA = 0.0, sumDiff = 0.0;
    for (std::size_t i = 0; i < pixels; ++i) {
        bool d = false;
        for (int c = 0; c < 3; ++c) {
            d = d || a.sum[4 * i + c] != b.sum[4 * i + c];
            sumA += a.sum[4 * i + c];
            sumDiff += std::abs(double(a.sum[4 * i + c]) - double(b.sum[4 * i + c]));
        }
        differ += d;
    }
    std::printf("spatial splits: %zu references for %zu primitives; %zu of %zu pixels differ, relative L1 %.2e\n",
                split.bvh.prims.size(), plain.bvh.prims.size(), differ, pixels, sumDiff / sumA);
    EXPECT_GT(sumA, 0.0) << "a black image agrees with anything";
    EXPECT_LT(double(differ), 0.02 * double(pixels));
    EXPECT_LT(sumDiff / sumA, 1e-3);
}

}  // namespace
}  // namespace vkp::test
