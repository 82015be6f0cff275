// glTF emissiveTexture on the device (lib/surface.glsl: surfaceAt for emission found by rays,
// emissiveTextureAt for next-event estimation), label gpu. scenes/gltf/emissive-texture.gltf:
//  1. The lamp seen straight on (texture_scene.h), black background: a pixel inside one texel is
//     exactly emissiveFactor x strength x the decoded texel (the camera ray's emission, weight 1).
//  2. A floor lit by a panel of the same textured material: next-event estimation (mis, light)
//     must see the texture at the point it samples, or it disagrees with bsdf, which only finds the
//     emission by hitting it (z-tests of block differences; ignoring the texture in NEE makes mis
//     about 3x brighter than bsdf, the texture's mean luminance being ~0.3).
//  3. The light pick's power of a textured emitter: factor x the image's mean linear colour.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gpu_env.h"
#include "render/light_table.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"
#include "texture_scene.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(100, 0.01));

Scene emissiveScene(const std::string& camera, std::uint32_t seed) {
    Scene scene = parseSceneJson(R"({"camera": )" + camera + R"(,
      "render": {"max_depth": 8, "background": [0, 0, 0]},
      "materials": {"unused": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "gltf", "file": "emissive-texture.gltf"}]})",
                                 scenesDir() / "gltf" / "emissive-texture-test.json");
    scene.render.seed = seed;
    return scene;
}

const char* const kLampCamera = R"({"lookfrom": [1, 1, 20], "lookat": [1, 1, 0], "vup": [0, 1, 0], "vfov": 7.152669,
                                    "width": 80, "height": 80})";
const char* const kFloorCamera = R"({"lookfrom": [12, -4.2, 7], "lookat": [12, -4.6, 0], "vup": [0, 1, 0], "vfov": 40,
                                     "width": 32, "height": 32})";

TEST(GpuEmissiveTexture, LampPixelsAreTheTexturedEmission) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 8;
    for (Sampler s : {Sampler::Bsdf, Sampler::Light, Sampler::Mis}) {
        const Scene scene = emissiveScene(kLampCamera, 2);
        const PixelStats st(renderSums(dev, scene, s, spp, "emissive-texture.gltf"));
        const TexturePack pack = packTextures(scene);
        gTexels = &pack.texels;
        gpu::GpuFrame f{};
        packCamera(scene.camera, f);
        const std::uint32_t mi = materialNamed(scene, "lamp");
        const glm::vec3 emit = scene.materials[mi].emit;  // factor x strength
        const Slot tex = slotOf(pack, mi, kTexSlotEmissive);
        ASSERT_TRUE(tex.valid && (tex.header.w & gpu::TEXF_SRGB));
        const std::vector<Pixel> px = insideTexels(f, 80, 80, 1, 0, {tex});
        ASSERT_GT(px.size(), 1500u);
        int bad = 0;
        for (const Pixel& p : px) {
            const glm::vec4 texel = gpu::texSample(tex.header, tex.uvOf(centreUv(f, p, 1)));
            for (int c = 0; c < 3; ++c) {
                const double want = double(emit[c] * texel[c]), got = st.mean.at(p.x, p.y, c);
                if (std::abs(got - want) > 1e-5 * want + spp * std::ldexp(1.0, -24) && bad++ < 5)
                    ADD_FAILURE() << samplerName(s) << " pixel " << p.x << "," << p.y << " channel " << c << ": " << got
                                  << ", want " << want;
            }
        }
        EXPECT_EQ(bad, 0) << samplerName(s);
        std::printf("  %s: %zu lamp pixels equal factor x strength x texel\n", samplerName(s), px.size());
    }
}

TEST(GpuEmissiveTexture, NextEventEstimationSeesTheTexture) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 1024;
    const PixelStats ref(renderSums(dev, emissiveScene(kFloorCamera, 11), Sampler::Bsdf, spp, "emissive floor"));
    for (Sampler s : {Sampler::Light, Sampler::Mis}) {
        const PixelStats st(renderSums(dev, emissiveScene(kFloorCamera, 12 + std::uint32_t(s)), s, spp, "emissive floor"));
        double worst = 0.0;
        for (std::uint32_t by = 0; by < 32; by += 8)
            for (std::uint32_t bx = 0; bx < 32; bx += 8) {
                const std::vector<Pixel> block = rect(bx, by, bx + 8, by + 8);
                for (int c = 0; c < 3; ++c) {
                    const Estimate a = average(st, block, c), b = average(ref, block, c);
                    Estimate d = a;
                    d.mean = a.mean - b.mean;
                    d.var = a.var + b.var;
                    EXPECT_TRUE(withinNoise(d, 0.0, std::string(samplerName(s)) + " - bsdf, block " + std::to_string(bx) +
                                                        "," + std::to_string(by) + " " + kChannel[c]));
                    if (b.mean > 0.0) worst = std::max(worst, std::abs(d.mean) / b.mean);
                }
            }
        const Estimate all = average(st, rect(0, 0, 32, 32), 1);
        EXPECT_GT(all.mean, 0.005);  // lit (0.0104 at these seeds)
        std::printf("  %s vs bsdf: 16 blocks x 3 channels agree (largest relative difference %.3f), image mean G %.4f\n",
                    samplerName(s), worst, all.mean);
    }
}

TEST(GpuEmissiveTexture, LightPowerUsesTheTextureMean) {
    const Scene scene = emissiveScene(kLampCamera, 1);
    const std::uint32_t mi = materialNamed(scene, "lamp");
    const TextureImage& img = scene.images.at(scene.textures.at(std::size_t(scene.materials[mi].pbr.emissiveTexture.texture)).image);
    glm::dvec3 mean(0.0);
    for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i)
        for (int c = 0; c < 3; ++c) mean[c] += gpu::srgbToLinear(float(img.rgba8[4 * i + c]) / 255.0f);
    mean /= double(img.width * img.height);
    for (std::uint32_t shape : scene.lights) {
        const Shape& sh = scene.shapes[shape];
        if (sh.material != mi) continue;
        const glm::dvec3 e = glm::dvec3(scene.materials[mi].emit) * mean;
        const double want = (0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z) * double(shapeArea(sh));  // single-sided
        EXPECT_NEAR(lightPower(scene, shape), want, 1e-5 * want);
    }
}

}  // namespace
}  // namespace vkp::test
