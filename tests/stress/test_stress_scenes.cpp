// The stress scenes (scenes/stress/, listed with their properties in scenes/stress/README.md),
// rendered with every sampler on the device (label stress). Every render must have no non-finite
// sample and no path cut by the loop guard (renderSums); each scene adds its own property:
//  - an exact value (flat or convex surfaces under a uniform background, closed furnaces, glass),
//  - a closed-form irradiance (lights of radius 1e-3 and 1e3),
//  - the same image as another render (cornell-classic scaled / moved; samplers against BSDF
//    sampling, which never samples a light),
//  - an energy bound: no pixel above Le_max / (1 - a_max).
// Tolerances are in standard errors from the per-pixel variances (tests/gpu/test_gpu_analytic_common.h):
// this executable declares 4000 z-tests at family-wise false-failure probability 0.01 (critical
// |z| ~ 4.7, Sidak). Means are averaged over >= 16 pixels x 256 samples of bounded values, except
// the BSDF sampler on the 1e-3 light (a sample is 0 or ~1e6): that case is only held to its upper
// bound, and a test of a difference uses both renders' variances.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gpu_env.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"
#include "file_frame.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(4000, 0.01));

Scene stressScene(const std::string& name, std::uint32_t seed) {
    Scene s = loadSceneJson(scenesDir() / "stress" / name);
    s.render.seed = seed;
    return s;
}

/// Image and 6 x 6-pixel blocks of a 24 x 24 image.
std::vector<std::pair<std::string, std::vector<Pixel>>> regions(std::uint32_t size) { return imageAndBlocks(size, 6); }

/// Every region of `b` agrees with `a` within noise (the difference has expectation 0). Both must
/// be lit and not constant first (two renders of nothing agree).
void expectSameImage(const PixelStats& a, const std::string& nameA, const PixelStats& b, const std::string& nameB) {
    EXPECT_TRUE(litAndNotConstant(a.mean, nameA));
    EXPECT_TRUE(litAndNotConstant(b.mean, nameB));
    const std::string what = nameA + " - " + nameB;
    for (const auto& [name, px] : regions(a.width))
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(withinNoise(difference(a, b, px, c), 0.0, what + ", " + name + ", " + kChannel[c], name == "image"));
}

/// One-sided: the mean of every pixel region is not above `bound` by more than noise.
void expectBelow(const PixelStats& s, double bound, const std::string& what) {
    for (const auto& [name, px] : regions(s.width))
        for (int c = 0; c < 3; ++c) {
            const Estimate e = average(s, px, c);
            const double z = zBudget().take();
            EXPECT_LE(e.mean, bound + z * std::sqrt(e.var) + 1e-6 * bound) << what << ", " << name << ", " << kChannel[c];
        }
}

// ---- Scale and translation invariance ---------------------------------------------------------
// cornell-classic scaled by 1e-4, 1e-6 and 1e5 (camera included) and moved 1e4, 1e5 and 1e7 from the origin
// gives the same image as at scale 1 within noise (radiance does not depend on scale), for every
// sampler: difference of region means, both renders' variances.
TEST(StressScenes, CornellIsScaleAndTranslationInvariant) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t size = 24, spp = 512;
    for (Sampler s : samplersUnderTest()) {
        Scene ref = loadSceneJson(scenesDir() / "cornell-classic.json");
        ref.camera.width = ref.camera.height = size;
        ref.render.seed = 300 + std::uint32_t(s);
        const PixelStats base(renderSums(dev, ref, s, spp, "cornell-classic"));
        std::uint32_t seed = 400;
        for (const char* name : {"cornell-scale-1e-4.json", "cornell-scale-1e-6.json", "cornell-scale-1e5.json", "cornell-translate-1e4.json",
                                 "cornell-translate-1e5.json", "cornell-translate-1e7.json"}) {
            Scene v = stressScene(name, seed++ + 10 * std::uint32_t(s));
            v.camera.width = v.camera.height = size;
            const PixelStats st(renderSums(dev, v, s, spp, name));
            expectSameImage(st, std::string(samplerName(s)) + " " + name, base, "cornell-classic");
        }
    }
}

// ---- Exact values -------------------------------------------------------------------------------

/// Direction (double) from the camera origin through point (i, j) of the pixel grid.
glm::dvec3 through(const gpu::GpuFrame& f, double i, double j) {
    return glm::normalize(glm::dvec3(f.pixel00) + i * glm::dvec3(f.pixelDu) + j * glm::dvec3(f.pixelDv) - glm::dvec3(f.origin));
}

/// Pixels whose four corner rays and centre ray all satisfy `on` (inside), or all satisfy `off`.
void classify(const Scene& scene, const std::function<bool(glm::dvec3, glm::dvec3)>& on,
              const std::function<bool(glm::dvec3, glm::dvec3)>& off, std::vector<Pixel>& inside, std::vector<Pixel>& outside) {
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    const glm::dvec3 o(f.origin);
    for (std::uint32_t y = 0; y < scene.camera.height; ++y)
        for (std::uint32_t x = 0; x < scene.camera.width; ++x) {
            bool allOn = true, allOff = true;
            for (auto [sx, sy] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}, {0.0, 0.0}}) {
                const glm::dvec3 d = through(f, x + sx, y + sy);
                allOn = allOn && on(o, d);
                allOff = allOff && off(o, d);
            }
            if (allOn) inside.push_back({x, y});
            if (allOff) outside.push_back({x, y});
        }
}

/// True if the ray meets z = 0 at t > 0 inside [-r, r]^2.
bool hitsSquare(glm::dvec3 o, glm::dvec3 d, double r) {
    const double t = -o.z / d.z;
    const glm::dvec3 p = o + t * d;
    return t > 0 && std::abs(p.x) <= r && std::abs(p.y) <= r;
}

bool hitsSphere(glm::dvec3 o, glm::dvec3 d, double r) {
    const double b = -glm::dot(o, d);
    return b > 0 && glm::length(o + b * d) < r;
}

/// A lambertian surface of albedo a, flat or convex, under a uniform background of 1 and nothing
/// else: light it reflects never returns to it, so its pixels are exactly a (zero variance for
/// the samplers that do not draw a light direction on it; the others must average to a), and
/// pixels that see only the background are exactly 1. Each quarter of the surface's pixels, and
/// all of them, is z-tested; for bsdf and light every pixel must equal a up to float summation.
void expectExactSurface(VulkanDevice& dev, const std::string& file, const std::function<bool(glm::dvec3, glm::dvec3)>& on,
                        const std::function<bool(glm::dvec3, glm::dvec3)>& off) {
    const glm::dvec3 albedo(0.2, 0.5, 0.8);
    for (Sampler s : samplersUnderTest()) {
        const Scene scene = stressScene(file, 500 + std::uint32_t(s));
        std::vector<Pixel> inside, outside;
        classify(scene, on, off, inside, outside);
        ASSERT_GT(inside.size(), 60u) << file;
        const std::uint32_t spp = scene.render.spp;
        const PixelStats st(renderSums(dev, scene, s, spp, file));
        const std::string name = std::string(samplerName(s)) + " " + file;
        int bad = 0;
        for (const Pixel& p : outside)
            for (int c = 0; c < 3; ++c) bad += st.mean.at(p.x, p.y, c) != 1.0f;
        EXPECT_EQ(bad, 0) << name << ": background pixels not exactly 1";
        for (int c = 0; c < 3; ++c) {
            if (s == Sampler::Bsdf || s == Sampler::Light) {
                int off = 0;
                for (const Pixel& p : inside)
                    off += std::abs(st.mean.at(p.x, p.y, c) - albedo[c]) > spp * std::ldexp(1.0, -24) * albedo[c] + 1e-7;
                EXPECT_EQ(off, 0) << name << ": pixels on the surface not exactly the albedo, channel " << kChannel[c];
            }
            EXPECT_TRUE(withinNoise(average(st, inside, c), albedo[c], name + ", surface, " + kChannel[c], true));
            const std::uint32_t mx = scene.camera.width / 2, my = scene.camera.height / 2;
            for (int q = 0; q < 4; ++q) {
                std::vector<Pixel> part;
                for (const Pixel& p : inside)
                    if (int(p.x >= mx) + 2 * int(p.y >= my) == q) part.push_back(p);
                if (part.size() >= 16)
                    EXPECT_TRUE(withinNoise(average(st, part, c), albedo[c], name + ", quarter " + std::to_string(q) + ", " + kChannel[c]));
            }
        }
    }
}

TEST(StressScenes, GrazingRaysAlongALargeQuad) {
    VKP_REQUIRE_DEVICE(dev);
    // Camera 0.001 above the plane y = 0, looking along -z: rows below the horizon see the plane
    // (its far edge, 5000 away, is 2e-7 rad below the horizon: the row under the horizon is skipped).
    auto onPlane = [](glm::dvec3 o, glm::dvec3 d) { return d.y < 0 && o.y / -d.y < 4000.0; };
    auto sky = [](glm::dvec3, glm::dvec3 d) { return d.y > 0; };
    expectExactSurface(dev, "grazing-plane.json", onPlane, sky);
}

TEST(StressScenes, CoincidentQuads) {
    VKP_REQUIRE_DEVICE(dev);
    expectExactSurface(dev, "coincident-quads.json", [](glm::dvec3 o, glm::dvec3 d) { return hitsSquare(o, d, 1.0); },
                       [](glm::dvec3 o, glm::dvec3 d) { return !hitsSquare(o, d, 1.15); });
}

TEST(StressScenes, NeedleThinAndZeroAreaTriangles) {
    VKP_REQUIRE_DEVICE(dev);
    expectExactSurface(dev, "thin-triangles.json", [](glm::dvec3 o, glm::dvec3 d) { return hitsSquare(o, d, 1.0); },
                       [](glm::dvec3 o, glm::dvec3 d) { return !hitsSquare(o, d, 1.15); });
}

// A 400 x 400 plane through the origin, tilted, filling the view: as a quad, and as two triangles
// of which one is sampled (light sampling from points in its own plane must pick nothing there).
TEST(StressScenes, LargeTiltedPlanes) {
    VKP_REQUIRE_DEVICE(dev);
    auto all = [](glm::dvec3, glm::dvec3) { return true; };
    auto none = [](glm::dvec3, glm::dvec3) { return false; };
    expectExactSurface(dev, "tilted-quad.json", all, none);
    expectExactSurface(dev, "tilted-triangles.json", all, none);
}

TEST(StressScenes, DistantCamera) {
    VKP_REQUIRE_DEVICE(dev);
    expectExactSurface(dev, "distant-camera.json", [](glm::dvec3 o, glm::dvec3 d) { return hitsSphere(o, d, 1.0); },
                       [](glm::dvec3 o, glm::dvec3 d) { return !hitsSphere(o, d, 1.1); });
}

/// Every pixel of `file` has expected value `expected` (per channel): image and blocks z-tested.
/// rareJump: see withinNoise (the glass scene: almost every sample is exactly 1).
void expectUniform(VulkanDevice& dev, const std::string& file, const glm::dvec3& expected, double rareJump = 0.0) {
    for (Sampler s : samplersUnderTest()) {
        const Scene scene = stressScene(file, 600 + std::uint32_t(s));
        const PixelStats st(renderSums(dev, scene, s, scene.render.spp, file));
        for (const auto& [name, px] : regions(scene.camera.width))
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(withinNoise(average(st, px, c), expected[c],
                                        std::string(samplerName(s)) + " " + file + ", " + name + ", " + kChannel[c], name == "image",
                                        rareJump, double(px.size()) * scene.render.spp));
    }
}

glm::dvec3 closedFurnaceValue(const std::string& file) {
    const Scene s = stressScene(file, 0);
    const glm::dvec3 a(0.3, 0.5, 0.7), le(1.0, 0.5, 0.25);
    glm::dvec3 v;
    for (int c = 0; c < 3; ++c) v[c] = le[c] * (1.0 - std::pow(a[c], s.render.maxDepth)) / (1.0 - a[c]);
    return v;
}

TEST(StressScenes, TouchingAndNestedSpheres) {
    VKP_REQUIRE_DEVICE(dev);
    expectUniform(dev, "spheres-touching-nested.json", closedFurnaceValue("spheres-touching-nested.json"));
}

TEST(StressScenes, LightsOverlappingGeometryClosed) {
    VKP_REQUIRE_DEVICE(dev);
    expectUniform(dev, "lights-overlapping-closed.json", closedFurnaceValue("lights-overlapping-closed.json"));
}

// Almost every sample is exactly 1 (out through the glass, or reflected a few times): only paths
// that reach Russian roulette (3 vertices, probability ~0.002) vary, 0 when it ends them (~1e-4
// of the samples, so a block of 9216 samples often has none, and its sample variance then misses
// them): the variance of one such event, (1.2 / N)^2, is added (withinNoise's rareJump).
TEST(StressScenes, CameraInsideGlassSphere) {
    VKP_REQUIRE_DEVICE(dev);
    expectUniform(dev, "glass-camera.json", glm::dvec3(1.0), 1.2);
}

TEST(StressScenes, CameraInThePlaneOfAQuad) {
    VKP_REQUIRE_DEVICE(dev);
    for (Sampler s : samplersUnderTest()) {
        const Scene scene = stressScene("grazing-in-plane.json", 700 + std::uint32_t(s));
        expectBelow(PixelStats(renderSums(dev, scene, s, scene.render.spp, "grazing-in-plane.json")), 1.0,
                    std::string(samplerName(s)) + " grazing-in-plane.json");
    }
}

// ---- Lights of radius 1e-3 (radiance 1e6) and 1e3 ------------------------------------------------

void expectPlaneUnderSphereLight(VulkanDevice& dev, const std::string& file, glm::dvec3 centre, double radius, double radiance) {
    const glm::dvec3 rho(0.2, 0.5, 0.8);
    for (Sampler s : samplersUnderTest()) {
        const Scene scene = stressScene(file, 800 + std::uint32_t(s));
        gpu::GpuFrame f{};
        packFileFrameCamera(scene, f);
        const std::uint32_t size = scene.camera.width;
        std::vector<double> expected(size * size);
        for (std::uint32_t j = 0; j < size; ++j)
            for (std::uint32_t i = 0; i < size; ++i)
                expected[j * size + i] = radiance / kPi * footprintMean(f, i, j, [&](glm::dvec3 x) {
                                             return sphereIrradiance(x, glm::dvec3(0, 0, 1), centre, radius);
                                         });
        const PixelStats st(renderSums(dev, scene, s, scene.render.spp, file));
        const std::string name = std::string(samplerName(s)) + " " + file;
        for (const auto& [region, px] : regions(size))
            for (int c = 0; c < 3; ++c) {
                double want = 0;
                for (const Pixel& p : px) want += rho[c] * expected[p.y * size + p.x] / double(px.size());
                const Estimate e = average(st, px, c);
                if (s == Sampler::Bsdf && radius < 0.01) {
                    // BSDF sampling hits this light with probability ~1e-6 per sample: only the bound.
                    const double z = zBudget().take();
                    EXPECT_LE(e.mean, want + z * std::sqrt(e.var) + 1e-6) << name << ", " << region;
                } else {
                    EXPECT_TRUE(withinNoise(e, want, name + ", " + region + ", " + kChannel[c], region == "image"));
                }
            }
    }
}

TEST(StressScenes, TinyIntenseSphereLight) {
    VKP_REQUIRE_DEVICE(dev);
    expectPlaneUnderSphereLight(dev, "light-tiny-intense.json", glm::dvec3(3, 0.5, 1), 1e-3, 1e6);
}

TEST(StressScenes, HugeSphereLight) {
    VKP_REQUIRE_DEVICE(dev);
    expectPlaneUnderSphereLight(dev, "light-huge.json", glm::dvec3(0, 0, 1002), 1000.0, 1.0);
}

// ---- Agreement with BSDF sampling, and the energy bound -------------------------------------------

void expectAgreeWithBsdf(VulkanDevice& dev, const std::string& file, double bound) {
    const Scene scene = stressScene(file, 900);
    const std::uint32_t spp = 1024;
    const PixelStats bsdf(renderSums(dev, scene, Sampler::Bsdf, spp, file));
    expectBelow(bsdf, bound, std::string("bsdf ") + file);
    for (Sampler s : samplersUnderTest()) {
        if (s == Sampler::Bsdf) continue;
        Scene other = scene;
        other.render.seed = 901 + std::uint32_t(s);
        const PixelStats st(renderSums(dev, other, s, spp, file));
        expectSameImage(st, std::string(samplerName(s)) + " " + file, bsdf, std::string("bsdf ") + file);
        expectBelow(st, bound, std::string(samplerName(s)) + " " + file);
    }
}

TEST(StressScenes, LightsOverlappingGeometryOpen) {
    VKP_REQUIRE_DEVICE(dev);
    expectAgreeWithBsdf(dev, "lights-overlapping-open.json", 4.0 / (1.0 - 0.7));
}

TEST(StressScenes, ShadingPointsOnSampledSpheres) {
    VKP_REQUIRE_DEVICE(dev);
    expectAgreeWithBsdf(dev, "on-sampled-sphere.json", 3.0 / (1.0 - 0.8));
}

}  // namespace
}  // namespace vkp::test
