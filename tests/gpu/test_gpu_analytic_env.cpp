// Environment lighting (label gpu), scenes with closed-form answers, maps written at test time and
// loaded through the JSON "environment" key (so the file readers, strength and rotate_y are in the
// loop):
//  - convex furnace: a lambertian sphere (albedo a) under a map of constant radiance 1: every pixel
//    that sees only the sphere has expected value a, every pixel that sees only the map is 1;
//  - band: a large tilted lambertian plane (albedo a, normal n) under a map that is bright only in
//    a band of rows (with colour varying along it): every pixel is (a / pi) E, E = sum over texels
//    of L_texel * integral over the texel of max(0, n . w) dw (nearest lookup: radiance is constant
//    per texel), integrated on the host from the map as loaded, 64 x 64 midpoints per texel;
//  - sun: the same plane under a dim sky with one very bright texel (the sun); the error of each
//    sampler at equal spp is measured and printed (docs/accuracy.md "Environment lighting: tests and numbers").
// z-tests share the budget of this executable (test_gpu_analytic_direct.cpp: 1000 tests, family-wise
// false-failure probability 0.01). Region means average >= 64 pixels x 256 samples of bounded
// values; in the band scene the bright band covers ~25% of the hemisphere, so even bsdf samples
// are far from heavy-tailed. In the sun scene bsdf finds the sun with probability ~1e-3 per
// sample: its mean is heavy-tailed, so bsdf is not z-tested there.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/image_io.h"
#include "gpu_env.h"
#include "render/gpu_scene.h"
#include "shared/environment_map.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"
#include "file_frame.h"

namespace vkp::test {
namespace {

/// Writes img to the scratch folder under name and returns the path.
std::filesystem::path writeMap(const Image& img, const std::string& name) {
    const std::filesystem::path p = scratchDir("gpu_analytic_env") / name;
    writeImage(img, p);
    return p;
}

// ---- Convex furnace under a constant map ---------------------------------------------------------
TEST(GpuAnalyticEnv, ConvexFurnaceUnderConstantMap) {
    VKP_REQUIRE_DEVICE(dev);
    Image map(16, 8);
    for (float& v : map.rgb) v = 0.5f;
    const std::filesystem::path file = writeMap(map, "constant.hdr");  // 0.5 is exact in RGBE
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 0, 4], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 24, "height": 24},
      "render": {"max_depth": 50, "seed": 21},
      "environment": {"file": ")" + file.filename().string() + R"(", "strength": 2, "rotate_y": 30},
      "materials": {"m": {"type": "lambertian", "albedo": [0.2, 0.5, 0.8]}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})",
                                 file.parent_path() / "furnace.json");
    ASSERT_TRUE(scene.environment.hasMap());
    const glm::dvec3 albedo(0.2, 0.5, 0.8);
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    // Pixels whose whole square sees the sphere (corners inside the silhouette disc), and pixels
    // 2 px away from it. The disc has radius tan(asin(1/4)) * 4 = 1.033 on the plane z = 0.
    std::vector<Pixel> inside, outside;
    const double r = std::tan(std::asin(0.25)) * 4.0, px = glm::length(glm::dvec3(f.pixelDu));  // at z = 0
    for (std::uint32_t y = 0; y < 24; ++y)
        for (std::uint32_t x = 0; x < 24; ++x) {
            const glm::dvec3 t = glm::dvec3(f.pixel00) + double(x) * glm::dvec3(f.pixelDu) + double(y) * glm::dvec3(f.pixelDv);
            const glm::dvec3 o(f.origin);
            const glm::dvec3 onPlane = o + (t - o) * (o.z / (o.z - t.z));
            const double d = glm::length(glm::dvec2(onPlane.x, onPlane.y));
            if (d + 0.75 * px < r) inside.push_back({x, y});
            if (d - 2.0 * px > r) outside.push_back({x, y});
        }
    ASSERT_GT(inside.size(), 150u);
    ASSERT_GT(outside.size(), 150u);
    for (Sampler s : samplersUnderTest()) {
        const PixelStats st(renderSums(dev, scene, s, 256, "env furnace"));
        const std::string name = samplerName(s);
        for (const Pixel& p : outside)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(st.mean.at(p.x, p.y, c), 1.0f) << name << " map at " << p.x << "," << p.y;
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(withinNoise(average(st, inside, c), albedo[c], name + " env furnace, sphere pixels, " + kChannel[c], true));
    }
}

// ---- A tilted plane under a map: closed-form irradiance ------------------------------------------
const glm::dvec3 kPlaneN = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));

/// The plane through the origin with normal kPlaneN (a 20 x 20 quad; the camera sees +-0.8 of it), seen from 3 n, and the map.
Scene planeScene(const std::filesystem::path& map, float rotateY, std::uint32_t seed) {
    const glm::dvec3 a = glm::normalize(glm::cross(kPlaneN, glm::dvec3(0, 0, 1)));
    const glm::dvec3 b = glm::cross(kPlaneN, a);  // a x b = n: the front face looks along n
    const glm::dvec3 q = -10.0 * (a + b), u = 20.0 * a, v = 20.0 * b, eye = 3.0 * kPlaneN;
    auto js = [](glm::dvec3 p) {
        return "[" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + "]";
    };
    return parseSceneJson(R"({
      "camera": {"lookfrom": )" + js(eye) + R"(, "lookat": [0, 0, 0], "vup": [0, 0, 1], "vfov": 30, "width": 16, "height": 16},
      "render": {"max_depth": 8, "seed": )" + std::to_string(seed) + R"(},
      "environment": {"file": ")" + map.filename().string() + R"(", "rotate_y": )" + std::to_string(rotateY) + R"(},
      "materials": {"m": {"type": "lambertian", "albedo": [0.6, 0.6, 0.6]}},
      "objects": [{"type": "quad", "Q": )" + js(q) + R"(, "u": )" + js(u) + R"(, "v": )" + js(v) + R"(, "material": "m"}]})",
                          map.parent_path() / "plane.json");
}

/// Irradiance at a surface of normal n under the loaded map (nearest lookup), per channel.
glm::dvec3 mapIrradiance(const Scene& scene, glm::dvec3 n) {
    const Image& img = scene.environment.image;
    const double rot = glm::radians(double(scene.environment.rotateY));
    const glm::vec2 cs(float(std::cos(rot)), float(std::sin(rot)));
    const int k = 64;
    glm::dvec3 e(0.0);
    for (std::uint32_t j = 0; j < img.height; ++j)
        for (std::uint32_t i = 0; i < img.width; ++i) {
            auto L = img.pixel(i, j);
            if (L[0] == 0.0f && L[1] == 0.0f && L[2] == 0.0f) continue;
            double w = 0.0;
            for (int sj = 0; sj < k; ++sj)
                for (int si = 0; si < k; ++si) {
                    const double u = (i + (si + 0.5) / k) / img.width, v = (j + (sj + 0.5) / k) / img.height;
                    const double theta = kPi * v, phi = 2.0 * kPi * u;
                    const glm::dvec3 m(-std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
                    const glm::dvec3 d(cs.x * m.x + cs.y * m.z, m.y, -cs.y * m.x + cs.x * m.z);  // envToWorld
                    w += std::max(0.0, glm::dot(n, d)) * std::sin(theta);
                }
            w *= (kPi / img.height) * (2.0 * kPi / img.width) / double(k * k);
            e += w * glm::dvec3(L[0], L[1], L[2]);
        }
    return e;
}

TEST(GpuAnalyticEnv, TiltedPlaneUnderBandMap) {
    VKP_REQUIRE_DEVICE(dev);
    Image map(32, 16);
    for (std::uint32_t j = 4; j < 7; ++j)  // a band 45..79 degrees from +y
        for (std::uint32_t i = 0; i < 32; ++i) map.set(i, j, 1.0f + 0.1f * float(i % 7), 2.0f, 0.5f + 0.05f * float(j));
    const std::filesystem::path file = writeMap(map, "band.exr");
    const Scene scene = planeScene(file, 50.0f, 5);
    const glm::dvec3 expected = 0.6 / kPi * mapIrradiance(scene, kPlaneN);
    for (Sampler s : samplersUnderTest()) {
        const PixelStats st(renderSums(dev, scene, s, 256, "env band"));
        const std::string name = std::string(samplerName(s)) + " env band plane";
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(withinNoise(average(st, rect(0, 0, 16, 16), c), expected[c], name + ", image, " + kChannel[c], true));
            for (std::uint32_t by = 0; by < 16; by += 8)
                for (std::uint32_t bx = 0; bx < 16; bx += 8)
                    EXPECT_TRUE(withinNoise(average(st, rect(bx, by, bx + 8, by + 8), c), expected[c],
                                            name + ", block " + std::to_string(bx) + "," + std::to_string(by) + ", " + kChannel[c]));
        }
    }
}

TEST(GpuAnalyticEnv, SunMapErrorBySampler) {
    VKP_REQUIRE_DEVICE(dev);
    Image map(128, 64);
    for (std::uint32_t j = 0; j < 64; ++j)
        for (std::uint32_t i = 0; i < 128; ++i) map.set(i, j, 0.1f, 0.15f, 0.25f);
    map.set(40, 20, 50000.0f, 45000.0f, 40000.0f);  // ~2e-4 sr, ~93% of the irradiance
    const std::filesystem::path file = writeMap(map, "sun.pfm");
    const Scene scene = planeScene(file, -20.0f, 9);
    const glm::dvec3 expected = 0.6 / kPi * mapIrradiance(scene, kPlaneN);
    const std::uint32_t spp = 64;
    double rmsBsdf = 0.0, rmsMis = 0.0;
    for (Sampler s : samplersUnderTest()) {
        const PixelStats st(renderSums(dev, scene, s, spp, "env sun"));
        const std::string name = std::string(samplerName(s)) + " env sun plane";
        // Relative RMS error of the pixel means (green) at this spp.
        double sq = 0.0;
        for (std::uint32_t y = 0; y < 16; ++y)
            for (std::uint32_t x = 0; x < 16; ++x) {
                const double e = st.mean.at(x, y, 1) / expected[1] - 1.0;
                sq += e * e;
            }
        const double rms = std::sqrt(sq / 256.0);
        std::printf("  %s: relative RMS pixel error at %u spp: %.4g\n", name.c_str(), spp, rms);
        if (s == Sampler::Bsdf) rmsBsdf = rms;
        if (s == Sampler::Mis) rmsMis = rms;
        if (s == Sampler::Bsdf) continue;  // heavy-tailed (file comment)
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(withinNoise(average(st, rect(0, 0, 16, 16), c), expected[c], name + ", image, " + kChannel[c], true));
    }
    std::printf("  env sun plane: bsdf / mis RMS error ratio at %u spp: %.3g\n", spp, rmsBsdf / rmsMis);
    // MIS samples the sun directly; BSDF sampling finds it by chance. A broken environment pdf
    // (or pick probability) makes MIS lose this comparison.
    EXPECT_LT(rmsMis, rmsBsdf);
}

}  // namespace
}  // namespace vkp::test
