// Feature images (`--aov`, shaders/shared/aov.h, render/aov.h) on the device, against closed
// forms, label gpu:
//  1. Textured quads under a uniform sky: a pixel whose footprint lies in one checker cell or one
//     nearest texel has exactly that albedo, and every other pixel one between the values its
//     footprint sees; a noise quad's albedo is the mean of the noise over the footprint. Their
//     normal is +z exactly, their depth the plane's distance 8.1, their position on the plane;
//     the sky's pixels have albedo 1 (the background, clamped), normal 0, no depth, and the
//     background as their emission (the quads' is 0).
//  2. A sphere: each pixel's normal and position are the means over its footprint of the unit
//     normal and the hit point (a 16 x 16 grid of exact ray-sphere hits on the host).
//  3. A mirror tints and passes on: through a fuzz-0 metal the albedo is its colour times the wall's
//     behind it and the normal the wall's; a fuzzy metal is the first non-specular vertex itself.
//  4. The image does not change: with and without --aov, every sampler, Cornell smoke (media: the
//     albedo of a scattering point) and a textured glTF scene give the same sums, bit for bit.
//  5. The AOV sums survive what the image's sums survive: a checkpoint (state, restore, the
//     accumulation file) continues them bit for bit, and bands of rows change no bit.
//
// Statistics: the noise quad's pixels are compared with |difference| <= 0.5 x the footprint's
// standard deviation / sqrt(spp) + 1e-5. Independent samples would miss that bound often; the
// Owen-scrambled Sobol' points of a fixed seed (deterministic) land within 0.03 of it, 16 times
// inside. A texture read at the pixel's centre instead of at each sample's point misses it.
#include "solid_texture_host.h"  // first: the host build of shared/solid_texture.h

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/errors.h"
#include "core/image_io.h"
#include "gpu_env.h"
#include "render/accum_file.h"
#include "render/aov.h"
#include "render/render_key.h"
#include "render/render_state.h"
#include "render_helpers.h"
#include "sums_agreement.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

/// Renders `scene` with the feature images on, `spp` samples; returns the renderer (read what you need).
TestRender renderWithAovs(VulkanDevice& dev, const Scene& scene, std::uint32_t spp, Sampler sampler = Sampler::Mis) {
    RenderOptions o;
    o.sampler = sampler;
    o.samplesPerDispatch = 4;
    o.aov = true;
    TestRender r = makeRender(dev, scene, o);
    r.renderer->addSamples(spp);
    EXPECT_EQ(r.renderer->counters().loopGuard, 0u);
    return r;
}

FeatureImages featuresOf(TestRender& r) {
    return featureImages(r.renderer->readAovSums(), r.arrays.width, r.arrays.height, r.arrays.aovFrame);
}

// ---- 1. Textured quads --------------------------------------------------------------------------

TEST(GpuAov, TexturedQuadsShowTheirTextureNormalAndDepth) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_aov_quads");
    Image big(3, 2);  // texels larger than a pixel
    for (std::size_t i = 0; i < big.rgb.size(); ++i) big.rgb[i] = float((i * 5) % 7) / 6.0f;
    writeImage(big, dir / "big.png");
    // Three quads in the plane z = -4.1 of the file, seen from z = 4 (the kernel's frame is the
    // file's minus (0, 0, 4): the positions must come back in the file's coordinates).
    const Scene scene = loadSceneText(dir, R"({
      "camera": {"lookfrom": [0, 0, 4], "lookat": [0, 0, -4], "vfov": 40, "width": 72, "height": 20},
      "render": {"background": [1.5, 1.5, 1.5], "max_depth": 8},
      "materials": {
        "check": {"type": "lambertian", "albedo": {"type": "checker", "scale": 1, "even": [0.2, 0.3, 0.1], "odd": [0.9, 0.8, 0.7]}},
        "image": {"type": "lambertian", "albedo": {"type": "image", "file": "big.png", "filter": "nearest"}},
        "noise": {"type": "lambertian", "albedo": {"type": "noise", "scale": 2}}},
      "objects": [{"type": "quad", "Q": [-8.4, -2.7, -4.1], "u": [5.4, 0, 0], "v": [0, 5.4, 0], "material": "check"},
                  {"type": "quad", "Q": [-2.7, -2.7, -4.1], "u": [5.4, 0, 0], "v": [0, 5.4, 0], "material": "image"},
                  {"type": "quad", "Q": [3.0, -2.7, -4.1], "u": [5.4, 0, 0], "v": [0, 5.4, 0], "material": "noise"}]})");
    const std::uint32_t spp = 256;
    TestRender r = renderWithAovs(dev, scene, spp);
    const FeatureImages f = featuresOf(r);
    const gpu::GpuFrame frame = r.arrays.frame;
    const TexturePack pack = packTextures(scene, false);
    gSolidPack = &pack;
    const glm::vec3 origin(scene.origin);
    const double z = -4.1 - 4.0;  // the plane in the kernel's coordinates
    int exact = 0, between = 0, averaged = 0, sky = 0;
    double worstNoise = 0.0;
    for (std::uint32_t py = 0; py < 20; ++py)
        for (std::uint32_t px = 0; px < 72; ++px) {
            const std::size_t i = std::size_t(py) * 72 + px, at = 3 * i;
            // The quad under the pixel's footprint (a 9 x 9 grid, edges included), if one covers it all.
            int quad = -1;
            bool inside = true, outside = true;
            glm::vec3 lo(1e9f), hi(-1e9f);
            glm::dvec3 sum(0.0), sumSq(0.0);
            for (int j = 0; j <= 8; ++j)
                for (int k = 0; k <= 8; ++k) {
                    const glm::dvec3 w = rayPlanePoint(frame, px - 0.5 + k / 8.0, py - 0.5 + j / 8.0, z);
                    const int q = int(std::floor((w.x + 8.4) / 5.7));
                    const double a = (w.x - (-8.4 + 5.7 * q)) / 5.4, b = (w.y + 2.7) / 5.4;
                    const bool on = q >= 0 && q <= 2 && a >= 0 && a <= 1 && b >= 0 && b <= 1;
                    if (!on || (quad >= 0 && q != quad)) inside = false;
                    if (on) outside = false;
                    if (!on) continue;
                    quad = q;
                    const glm::vec3 v = gpu::evalSolidTexture(std::uint32_t(scene.materials[std::size_t(q)].albedoTexture),
                                                              glm::vec3(w) + origin, glm::vec2(float(a), float(b)));
                    lo = glm::min(lo, v);
                    hi = glm::max(hi, v);
                    sum += glm::dvec3(v);
                    sumSq += glm::dvec3(v) * glm::dvec3(v);
                }
            if (outside) {  // the sky: the background clamped to 1, no surface
                for (int c = 0; c < 3; ++c) {
                    EXPECT_EQ(f.albedo.rgb[at + c], 1.0f) << px << "," << py;
                    EXPECT_EQ(f.normal.rgb[at + c], 0.0f) << px << "," << py;
                    EXPECT_EQ(f.emission.rgb[at + c], 1.5f) << px << "," << py;  // the sky seen directly
                }
                EXPECT_TRUE(std::isinf(f.depth[i])) << px << "," << py;
                EXPECT_EQ(f.hitFraction[i], 0.0f);
                ++sky;
                continue;
            }
            if (!inside) continue;
            // On one quad: normal +z, depth 8.1 along the view axis, the position on the plane.
            EXPECT_EQ(f.normal.rgb[at], 0.0f);
            EXPECT_EQ(f.normal.rgb[at + 1], 0.0f);
            EXPECT_NEAR(f.normal.rgb[at + 2], 1.0f, 1e-6);
            EXPECT_NEAR(f.depth[i], 8.1f, 2e-5) << px << "," << py;
            EXPECT_NEAR(f.position.rgb[at + 2], -4.1f, 2e-5) << px << "," << py;
            const glm::dvec3 centre = rayPlanePoint(frame, px, py, z) + glm::dvec3(origin);
            EXPECT_NEAR(f.position.rgb[at], centre.x, 0.04) << px << "," << py;  // a pixel is ~0.12 wide: the mean is near its centre
            EXPECT_NEAR(f.position.rgb[at + 1], centre.y, 0.04) << px << "," << py;
            EXPECT_EQ(f.hitFraction[i], 1.0f);
            for (int c = 0; c < 3; ++c) EXPECT_EQ(f.emission.rgb[at + c], 0.0f);  // the quads do not emit
            if (quad < 2) {
                if (lo == hi) {  // one cell or texel: exactly its value
                    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f.albedo.rgb[at + c], lo[c], 1e-6 * (1.0 + lo[c])) << px << "," << py;
                    ++exact;
                } else {  // an edge: a mean of the values the footprint sees
                    for (int c = 0; c < 3; ++c) {
                        EXPECT_GE(f.albedo.rgb[at + c], lo[c] - 1e-6) << px << "," << py;
                        EXPECT_LE(f.albedo.rgb[at + c], hi[c] + 1e-6) << px << "," << py;
                    }
                    ++between;
                }
            } else {  // noise: the mean over the footprint (32 x 32 midpoints; the 9 x 9 grid's spread)
                const glm::dvec3 m9 = sum / 81.0, sd = glm::sqrt(glm::max(sumSq / 81.0 - m9 * m9, glm::dvec3(0.0)));
                glm::dvec3 mean(0.0);
                const std::uint32_t node = std::uint32_t(scene.materials[2].albedoTexture);
                for (int j = 0; j < 32; ++j)
                    for (int k = 0; k < 32; ++k) {
                        const glm::dvec3 w = rayPlanePoint(frame, px - 0.5 + (k + 0.5) / 32.0, py - 0.5 + (j + 0.5) / 32.0, z);
                        const double a = (w.x - 3.0) / 5.4, b = (w.y + 2.7) / 5.4;
                        mean += glm::dvec3(gpu::evalSolidTexture(node, glm::vec3(w) + origin, glm::vec2(float(a), float(b)))) / 1024.0;
                    }
                for (int c = 0; c < 3; ++c) {
                    const double d = std::abs(f.albedo.rgb[at + c] - mean[c]);
                    worstNoise = std::max(worstNoise, d / (sd[c] / std::sqrt(double(spp)) + 1e-7));
                    EXPECT_LE(d, 0.5 * sd[c] / std::sqrt(double(spp)) + 1e-5) << px << "," << py;
                }
                ++averaged;
            }
        }
    std::printf("  %d pixels on one cell or texel, %d on edges, %d noise pixels (worst %.2f sd of the mean), %d sky pixels\n",
                exact, between, averaged, worstNoise, sky);
    EXPECT_GT(exact, 200);
    EXPECT_GT(between, 20);
    EXPECT_GT(averaged, 150);
    EXPECT_GT(sky, 100);
}

// ---- 2. A sphere's normals and positions --------------------------------------------------------

TEST(GpuAov, SphereNormalsAndPositionsAreTheFootprintMeans) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_aov_sphere");
    const Scene scene = loadSceneText(dir, R"({
      "camera": {"lookfrom": [1, 2, 3], "lookat": [1, 2, -5], "vfov": 30, "width": 32, "height": 32},
      "render": {"background": [0.5, 0.5, 0.5], "max_depth": 4},
      "materials": {"m": {"type": "lambertian", "albedo": [0.6, 0.5, 0.4]}},
      "objects": [{"type": "sphere", "center": [1.3, 1.8, -5], "radius": 1.6, "material": "m"}]})");
    TestRender r = renderWithAovs(dev, scene, 256);
    const FeatureImages f = featuresOf(r);
    const gpu::GpuFrame frame = r.arrays.frame;
    const glm::dvec3 o(frame.origin), c = glm::dvec3(1.3, 1.8, -5) - scene.origin;  // kernel coordinates
    int tested = 0;
    double worstN = 0.0, worstP = 0.0;
    for (std::uint32_t py = 0; py < 32; ++py)
        for (std::uint32_t px = 0; px < 32; ++px) {
            // The hit through image point (x, y) of the pixel grid, if any.
            auto hit = [&](double x, double y, glm::dvec3& p) {
                const glm::dvec3 t = glm::dvec3(frame.pixel00) + x * glm::dvec3(frame.pixelDu) + y * glm::dvec3(frame.pixelDv);
                const glm::dvec3 d = glm::normalize(t - o), oc = o - c;
                const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - 1.6 * 1.6);
                if (disc <= 0.0) return false;
                p = o + (-b - std::sqrt(disc)) * d;
                return true;
            };
            // The sphere's outline is convex: a footprint whose corners it covers lies inside it.
            glm::dvec3 q;
            bool all = true;
            for (int k = 0; k < 4; ++k) all = all && hit(px - 0.5 + (k & 1), py - 0.5 + (k >> 1), q);
            if (!all) continue;  // the silhouette's pixels
            glm::dvec3 nSum(0.0), pSum(0.0), nLo(2.0), nHi(-2.0);
            const int g = 16;
            for (int j = 0; j < g; ++j)
                for (int k = 0; k < g; ++k) {
                    hit(px - 0.5 + (k + 0.5) / g, py - 0.5 + (j + 0.5) / g, q);
                    const glm::dvec3 nn = (q - c) / 1.6;
                    nSum += nn;
                    pSum += q;
                    nLo = glm::min(nLo, nn);
                    nHi = glm::max(nHi, nn);
                }
            const std::size_t at = 3 * (std::size_t(py) * 32 + px);
            const glm::dvec3 n = nSum / double(g * g), p = pSum / double(g * g) + scene.origin;
            for (int k = 0; k < 3; ++k) {
                worstN = std::max(worstN, std::abs(f.normal.rgb[at + k] - n[k]));
                worstP = std::max(worstP, std::abs(f.position.rgb[at + k] - p[k]));
                // The sample mean of 256 stratified points against the grid's: well within a
                // twentieth of how much the normal turns over the footprint.
                const double spread = nHi[k] - nLo[k];
                EXPECT_NEAR(f.normal.rgb[at + k], n[k], 0.05 * spread + 2e-4) << px << "," << py;
                EXPECT_NEAR(f.position.rgb[at + k], p[k], 1.6 * (0.05 * spread + 2e-4)) << px << "," << py;
            }
            EXPECT_NEAR(f.depth[std::size_t(py) * 32 + px], glm::dot(p - glm::dvec3(1, 2, 3), glm::dvec3(0, 0, -1)), 1e-2);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(f.albedo.rgb[at + k], 0.6f - 0.1f * k, 1e-6);
            ++tested;
        }
    std::printf("  %d pixels inside the silhouette: worst normal difference %.2g, position %.2g\n", tested, worstN, worstP);
    EXPECT_GT(tested, 150);
}

// ---- 3. Mirrors and fuzzy metal -----------------------------------------------------------------

TEST(GpuAov, AMirrorTintsTheAlbedoBehindItAndAFuzzyMetalIsItself) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_aov_mirror");
    // A mirror at 45 degrees in front of the camera sends its rays to +x, onto a wall facing -x.
    for (const char* fuzz : {"0", "0.3"}) {
        const Scene scene = loadSceneText(dir, std::string(R"({
          "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 10, "width": 16, "height": 16},
          "render": {"background": [0.2, 0.2, 0.2], "max_depth": 6},
          "materials": {"mirror": {"type": "metal", "albedo": [0.5, 0.6, 0.7], "fuzz": )") + fuzz + R"(},
                        "wall": {"type": "lambertian", "albedo": [0.8, 0.4, 0.2]}},
          "objects": [{"type": "quad", "Q": [-1, -1, -2], "u": [2, 0, -2], "v": [0, 2, 0], "material": "mirror"},
                      {"type": "quad", "Q": [6, -20, -20], "u": [0, 40, 0], "v": [0, 0, 40], "material": "wall"}]})");
        TestRender r = renderWithAovs(dev, scene, 16);
        const FeatureImages f = featuresOf(r);
        const bool mirror = std::string(fuzz) == "0";
        const glm::vec3 want = mirror ? glm::vec3(0.5f * 0.8f, 0.6f * 0.4f, 0.7f * 0.2f) : glm::vec3(0.5f, 0.6f, 0.7f);
        const glm::vec3 wantN = mirror ? glm::vec3(-1, 0, 0) : glm::vec3(glm::normalize(glm::dvec3(1, 0, 1)));
        for (std::size_t i = 0; i < f.albedo.pixelCount(); ++i)
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(f.albedo.rgb[3 * i + c], want[c], 1e-6) << "fuzz " << fuzz << " pixel " << i;
                EXPECT_NEAR(f.normal.rgb[3 * i + c], wantN[c], 1e-5) << "fuzz " << fuzz << " pixel " << i;
            }
        // The position and depth are the mirror's (the first hit), not the wall's.
        for (std::size_t i = 0; i < f.depth.size(); ++i) EXPECT_LT(f.depth[i], 5.0f);
    }
}

// ---- 3b. The indirect moments -------------------------------------------------------------------

TEST(GpuAov, TheIndirectMomentsLeaveTheEmissionOut) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_aov_indirect");
    // Everything grey under a white light, so every sample's radiance has R = G = B and its
    // luminance is any channel: where no sample saw emission, the indirect moments are the
    // image's own. The light (which reflects nothing) fills the top of the image.
    const Scene scene = loadSceneText(dir, R"({
      "camera": {"lookfrom": [0, 1, 3], "lookat": [0, 1, 0], "vfov": 60, "width": 24, "height": 24},
      "render": {"background": [0, 0, 0], "max_depth": 6},
      "materials": {"grey": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
                    "light": {"type": "diffuse_light", "emit": [4, 4, 4]}},
      "objects": [{"type": "quad", "Q": [-10, 0, -10], "u": [20, 0, 0], "v": [0, 0, 20], "material": "grey"},
                  {"type": "quad", "Q": [-0.9, 2.4, -1], "u": [1.8, 0, 0], "v": [0, 0, 2], "material": "light"},
                  {"type": "quad", "Q": [-10, 0, -3], "u": [20, 0, 0], "v": [0, 10, 0], "material": "grey"}]})");
    const std::uint32_t spp = 64;
    TestRender r = renderWithAovs(dev, scene, spp);
    const std::vector<float> sums = r.renderer->readAovSums();
    const FeatureImages f = featuresOf(r);
    const PixelSums px = r.renderer->readSums();
    const Image mean = px.mean(), var = px.varianceOfMean();
    int plain = 0, inLight = 0, edge = 0;
    for (std::size_t i = 0; i < mean.pixelCount(); ++i) {
        const float* a = sums.data() + i * kAovFloatsPerPixel;
        ASSERT_EQ(a[3], float(spp));
        const float e = f.emission.rgb[3 * i];
        if (e == 0.0f) {  // no sample saw the light: the moments are the image's
            ++plain;
            EXPECT_NEAR(a[11], mean.rgb[3 * i], 1e-5 * mean.rgb[3 * i] + 1e-7) << "pixel " << i;
            // Running means of L and L^2 in float: each within ~sqrt(n) ulps; the variance is
            // their difference, so its error is bounded by the mean square's.
            EXPECT_NEAR(f.indirectVariance[i], var.rgb[3 * i], 1e-3 * var.rgb[3 * i] + 4e-6 * a[15] / spp) << "pixel " << i;
        } else if (e == 4.0f) {  // every sample saw the light and nothing else
            ++inLight;
            EXPECT_EQ(a[11], 0.0f) << "pixel " << i;
            EXPECT_EQ(a[15], 0.0f) << "pixel " << i;
        } else {  // the light's edge: its coverage noise is in the image's variance, not here
            ++edge;
            EXPECT_LT(f.indirectVariance[i], 0.5f * var.rgb[3 * i]) << "pixel " << i;
        }
    }
    EXPECT_GT(plain, 200);
    EXPECT_GT(inLight, 10);
    EXPECT_GT(edge, 5);
}

TEST(GpuAov, ALightSeenThroughGlassIsFilteredNotEmission) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_aov_glass");
    // A light fills the view; a glass pane (two parallel quads) covers its left half. Glass
    // reflects or refracts by chance (about 4 % reflect here, onto the black background), so what
    // is seen through it is noise to filter: its emission feature is 0 and the light is in the
    // indirect moments. The right half sees the light directly: emission 4, no indirect part.
    const Scene scene = loadSceneText(dir, R"({
      "camera": {"lookfrom": [0, 0, 3], "lookat": [0, 0, 0], "vfov": 40, "width": 24, "height": 16},
      "render": {"background": [0, 0, 0], "max_depth": 8},
      "materials": {"glass": {"type": "dielectric", "ior": 1.5},
                    "light": {"type": "diffuse_light", "emit": [4, 4, 4]}},
      "objects": [{"type": "quad", "Q": [-10, -10, -2], "u": [20, 0, 0], "v": [0, 20, 0], "material": "light"},
                  {"type": "quad", "Q": [-10, -10, 0], "u": [10, 0, 0], "v": [0, 20, 0], "material": "glass"},
                  {"type": "quad", "Q": [-10, -10, -0.1], "u": [10, 0, 0], "v": [0, 20, 0], "material": "glass"}]})");
    const std::uint32_t spp = 64;
    TestRender r = renderWithAovs(dev, scene, spp);
    const std::vector<float> sums = r.renderer->readAovSums();
    const FeatureImages f = featuresOf(r);
    const Image mean = r.renderer->readSums().mean();
    int throughGlass = 0, direct = 0;
    for (std::uint32_t y = 0; y < 16; ++y)
        for (std::uint32_t x = 0; x < 24; ++x) {
            if (x == 11 || x == 12) continue;  // the pane's edge
            const std::size_t i = std::size_t(y) * 24 + x;
            const float* a = sums.data() + i * kAovFloatsPerPixel;
            if (x < 11) {
                ++throughGlass;
                EXPECT_EQ(f.emission.rgb[3 * i], 0.0f) << x << "," << y;
                EXPECT_GT(mean.rgb[3 * i], 2.0f) << x << "," << y;  // the light, through the pane
                EXPECT_NEAR(a[11], mean.rgb[3 * i], 1e-5f * mean.rgb[3 * i]) << x << "," << y;  // all of it indirect
            } else {
                ++direct;
                EXPECT_EQ(f.emission.rgb[3 * i], 4.0f) << x << "," << y;
                EXPECT_EQ(a[11], 0.0f) << x << "," << y;
            }
        }
    EXPECT_EQ(throughGlass, 11 * 16);
    EXPECT_EQ(direct, 11 * 16);
}

// ---- 4. The image does not change ----------------------------------------------------------------

TEST(GpuAov, TheImageIsBitIdenticalWithAndWithoutFeatureImages) {
    VKP_REQUIRE_DEVICE(dev);
    // Media (a scattering point's albedo), the glTF BRDF with textures, and the books' materials;
    // one scene under every sampler (each takes its own branches of the integrator).
    struct Case {
        const char* file;
        std::uint32_t spp;
        bool everySampler;
    };
    for (const Case& k : {Case{"cornell-book3.json", 8, true}, Case{"next-week/cornell-smoke.json", 8, false},
                          Case{"gltf/textures.gltf", 4, false}}) {
        const std::filesystem::path file = scenesDir() / k.file;
        Scene scene = file.extension() == ".gltf" ? loadSceneGltf(file) : loadSceneJson(file);
        scene.camera.width = 24;
        scene.camera.height = 24;
        for (Sampler sampler : kAllSamplers) {
            if (!k.everySampler && sampler != Sampler::Mis) continue;
            RenderOptions o;
            o.sampler = sampler;
            o.samplesPerDispatch = 4;
            const PixelSums off = renderSums(dev, scene, o, k.spp, k.file);
            o.aov = true;
            TestRender r = makeRender(dev, scene, o);
            r.renderer->addSamples(k.spp);
            const PixelSums on = r.renderer->readSums();
            EXPECT_TRUE(sameSamples(dev, off, on, std::string(k.file) + " " + samplerName(sampler)));
            // Every sample is in the AOV sums, and the albedo is a reflectance.
            const std::vector<float> aov = r.renderer->readAovSums();
            for (std::size_t i = 0; i < off.sum.size() / 4; ++i) {
                EXPECT_EQ(aov[kAovFloatsPerPixel * i + 3], float(k.spp)) << k.file << " pixel " << i;
                for (int c = 0; c < 3; ++c) {
                    EXPECT_GE(aov[kAovFloatsPerPixel * i + c], 0.0f);
                    EXPECT_LE(aov[kAovFloatsPerPixel * i + c], float(k.spp) * 1.000001f);
                }
            }
        }
    }
}

// ---- 5. Checkpoints and bands --------------------------------------------------------------------

TEST(GpuAov, ACheckpointAndBandsKeepTheSumsBitForBit) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = loadSceneJson(scenesDir() / "cornell-book3.json");
    scene.camera.width = 40;
    scene.camera.height = 36;
    RenderOptions o;
    o.samplesPerDispatch = 2;
    o.aov = true;
    TestRender straight = makeRender(dev, scene, o);
    straight.renderer->addSamples(12);
    const std::vector<float> want = straight.renderer->readAovSums();

    // Interrupted after 5 samples, written to an accumulation file, read back and continued.
    TestRender first = makeRender(dev, scene, o);
    first.renderer->addSamples(5);
    const std::filesystem::path file = scratchDir("gpu_aov_checkpoint") / "state.exr";
    writeAccumFile(file, renderKey(first.arrays, o), first.renderer->state());
    const AccumFile back = readAccumFile(file);
    ASSERT_EQ(back.state.aov.size(), want.size());
    TestRender second = makeRender(dev, scene, o);
    second.renderer->restore(back.state, file.string());
    second.renderer->addSamples(7);
    const std::vector<float> resumed = second.renderer->readAovSums();
    EXPECT_EQ(std::memcmp(resumed.data(), want.data(), want.size() * sizeof(float)), 0);

    // A state without feature images does not continue a render with them, and the other way.
    RenderOptions plain = o;
    plain.aov = false;
    TestRender without = makeRender(dev, scene, plain);
    EXPECT_THROW(without.renderer->restore(back.state, "state"), InputError);

    // Bands of 8 rows.
    DeviceLimits limits = deviceLimits(dev.info());
    limits.maxStorageBufferRange = 8 * 40 * kAovBytesPerPixel;
    TestRender banded = makeRender(dev, scene, o, &limits);
    ASSERT_GT(banded.renderer->bandCount(), 1u);
    banded.renderer->addSamples(12);
    const std::vector<float> bands = banded.renderer->readAovSums();
    EXPECT_EQ(std::memcmp(bands.data(), want.data(), want.size() * sizeof(float)), 0);
}

}  // namespace
}  // namespace vkp::test
