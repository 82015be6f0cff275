// glTF COLOR_0 on the device (label gpu): scenes/gltf/vertex-colors.gltf, four 2 x 2 quads of a
// Lambertian base colour 0.8 whose corner colours are linear in x and y (uint16 RGBA, float RGBA
// under alphaMode MASK, float RGB, uint8 RGBA), seen from above in a white furnace (background 1,
// max_depth 2): a pixel is 0.8 x the interpolated colour averaged over its footprint, or 1 where
// the MASK quad's interpolated alpha is below its cutoff (a hole). The expected values interpolate
// the corners as the kernel stores them (half floats, per triangle).
//
// Suite: a budget of 400 z-tests at family-wise false-failure probability 0.01 (critical |z| ~ 4.2,
// test_gpu_analytic_common.h). Samples are bounded (every value is a colour x 0.8 or 1) and region
// means average >= 16 pixels x 256 samples, so they are close to normal.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include <glm/gtc/packing.hpp>

#include "gpu_env.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(400, 0.01));

// As tools/gen_gltf_scenes.py writes them (VC_C00, VC_DCDX, VC_DCDY).
const glm::dvec4 kC00(0.2, 0.9, 0.1, 0.0), kDcdx(0.3, -0.2, 0.1, 0.5), kDcdy(0.1, 0.0, 0.35, 0.0);

/// The colour of corner (x, y) of quad q as the kernel stores it: quantised as the file stores it
/// (uint16, float, float RGB, uint8), then rounded to half floats.
glm::dvec4 storedCorner(int q, double x, double y) {
    glm::dvec4 c = kC00 + x * kDcdx + y * kDcdy;
    if (q == 2) c.w = 1.0;  // RGB: alpha 1
    glm::vec4 f(c);
    if (q == 0 || q == 3) {
        const float scale = q == 0 ? 65535.0f : 255.0f;
        for (int k = 0; k < 4; ++k) f[k] = std::round(float(c[k]) * scale) / scale;
    }
    const glm::vec2 rg = glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(f.x, f.y)));
    const glm::vec2 ba = glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(f.z, f.w)));
    return glm::dvec4(rg.x, rg.y, ba.x, ba.y);
}

/// COLOR_0 at (x, y) in quad q's own coordinates ([0, 2]^2): barycentric over its triangle
/// ((0,0), (2,0), (2,2)) below the diagonal, ((0,0), (2,2), (0,2)) above.
glm::dvec4 colorAt(int q, double x, double y) {
    const glm::dvec4 c00 = storedCorner(q, 0, 0), c22 = storedCorner(q, 2, 2);
    if (y <= x) return c00 + x / 2.0 * (storedCorner(q, 2, 0) - c00) + y / 2.0 * (c22 - storedCorner(q, 2, 0));
    return c00 + x / 2.0 * (c22 - storedCorner(q, 0, 2)) + y / 2.0 * (storedCorner(q, 0, 2) - c00);
}

TEST(GpuVertexColors, Color0MultipliesTheBaseColourAndItsAlpha) {
    VKP_REQUIRE_DEVICE(dev);
    // The camera 100 above (5.5, 1) sees x in [-0.25, 11.25], y in [-0.25, 2.25]: 92 x 20 pixels of 0.125.
    const std::string file = (scenesDir() / "gltf" / "vertex-colors.gltf").generic_string();
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [5.5, 1, 100], "lookat": [5.5, 1, 0], "vup": [0, 1, 0], "vfov": 1.4323, "width": 92, "height": 20},
      "render": {"max_depth": 2, "background": [1, 1, 1]},
      "objects": [{"type": "gltf", "file": ")" + file + R"("}]})",
                                 scenesDir() / "gltf" / "vertex-colors-test.json");
    ASSERT_TRUE(sceneFeatures(scene).vertexColors);
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    // Expected per channel at a point of the plane z = 0.
    auto radiance = [](glm::dvec3 p, int c) {
        const int q = int(std::floor(p.x / 3.0));
        const double x = p.x - 3.0 * q, y = p.y;
        if (q < 0 || q > 3 || x > 2.0 || y < 0.0 || y > 2.0) return 1.0;  // the white background
        const glm::dvec4 col = colorAt(q, x, y);
        if (q == 1 && col.w < 0.5) return 1.0;  // MASK: a hole
        return 0.8 * col[c];
    };
    // Pixels whose footprint (one pixel of margin) lies inside one quad, away from the hole's edge
    // (quad 1, x = 1): quad 1's left part is the background through the hole.
    std::array<std::vector<Pixel>, 5> regions;  // quads 0-3, then quad 1's hole
    for (std::uint32_t j = 0; j < 20; ++j)
        for (std::uint32_t i = 0; i < 92; ++i) {
            const double x = -0.25 + 0.125 * (i + 0.5), y = 2.25 - 0.125 * (j + 0.5);
            const int q = int(std::floor(x / 3.0));
            const double lx = x - 3.0 * q;
            if (q < 0 || q > 3 || lx < 0.25 || lx > 1.75 || y < 0.25 || y > 1.75) continue;
            if (q == 1 && std::abs(lx - 1.0) < 0.25) continue;
            regions[q == 1 && lx < 1.0 ? 4 : std::size_t(q)].push_back({i, j});
        }
    const char* names[] = {"uint16 RGBA", "float RGBA under MASK", "float RGB", "uint8 RGBA", "MASK hole"};
    for (Sampler s : {Sampler::Bsdf, Sampler::Mis}) {
        scene.render.seed = 3 + std::uint32_t(s);
        const PixelStats st(renderSums(dev, scene, s, 256, std::string("vertex colours ") + samplerName(s)));
        for (std::size_t r = 0; r < regions.size(); ++r) {
            ASSERT_GE(regions[r].size(), 16u) << names[r];
            for (int c = 0; c < 3; ++c) {
                double expected = 0.0;
                for (const Pixel& p : regions[r])
                    expected += footprintMean(f, p.x, p.y, [&](glm::dvec3 x) { return radiance(x, c); });
                expected /= double(regions[r].size());
                EXPECT_TRUE(withinNoise(average(st, regions[r], c), expected,
                                        std::string(samplerName(s)) + ", " + names[r] + ", " + kChannel[c], true));
                // And in blocks of 4 x 4 pixels along each quad (the colour's gradient, not just its mean).
                if (r == 4) continue;
                std::vector<Pixel> block;
                for (const Pixel& p : regions[r]) {
                    block.push_back(p);
                    if (block.size() < 16) continue;
                    double e = 0.0;
                    for (const Pixel& b : block) e += footprintMean(f, b.x, b.y, [&](glm::dvec3 x) { return radiance(x, c); });
                    EXPECT_TRUE(withinNoise(average(st, block, c), e / double(block.size()),
                                            std::string(samplerName(s)) + ", " + names[r] + " pixels from " + std::to_string(block[0].x) +
                                                "," + std::to_string(block[0].y) + ", " + kChannel[c]));
                    block.clear();
                }
            }
        }
    }
}

}  // namespace
}  // namespace vkp::test
