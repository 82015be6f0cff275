// glTF alphaMode on the device (shaders/lib/alpha.glsl, the traversal's any-hit test), label gpu.
// scenes/gltf/alpha.gltf under a uniform background of radiance 1, pure Lambertian glTF materials
// (specularFactor 0) in the camera's focal plane, seen straight on (texture_scene.h):
//  - MASK: alpha = factor 0.6 x texture alpha (1 or 128/255) against cutoff 0.5: pixels inside a
//    solid texel are exactly factor x texel (every weight is 1 x albedo, as in test_gpu_textures),
//    pixels inside a hole exactly the background 1 (the ray passes; nothing behind). Ignoring the
//    factor's alpha would close the holes; ignoring the texture's would open none.
//  - A grey quad behind a fully cut-out one: exactly its albedo 0.6, which needs the cut-out to let
//    through the camera rays, the bounce rays and (mis) the shadow rays towards the sky.
//  - BLEND, alpha 0.25: stochastic transparency averages to 0.25 x albedo + 0.75 x 1 (z-test).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gpu_env.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"
#include "texture_scene.h"
#include "file_frame.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(20, 0.01));

constexpr std::uint32_t kWidth = 240, kHeight = 80;
constexpr int kQuads = 3;  // quads in the plane z = 0 (the ghost sits in front of quad 2)

Scene alphaScene(std::uint32_t seed) {
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [3.5, 1, 20], "lookat": [3.5, 1, 0], "vup": [0, 1, 0], "vfov": 7.152669,
                 "width": 240, "height": 80},
      "render": {"max_depth": 50, "background": [1, 1, 1]},
      "materials": {"unused": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "gltf", "file": "alpha.gltf"}]})",
                                 scenesDir() / "gltf" / "alpha-test.json");
    scene.render.seed = seed;
    return scene;
}

TEST(GpuAlpha, MaskHolesShowTheBackgroundExactly) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 16;
    for (Sampler s : {Sampler::Bsdf, Sampler::Mis}) {
        const Scene scene = alphaScene(3);
        const PixelStats st(renderSums(dev, scene, s, spp, "alpha.gltf"));
        const TexturePack pack = packTextures(scene);
        gTexels = &pack.texels;
        gpu::GpuFrame f{};
        packFileFrameCamera(scene, f);
        const std::uint32_t mi = materialNamed(scene, "mask");
        const float factorAlpha = scene.materials[mi].pbr.baseColor.w, cutoff = scene.materials[mi].pbr.alphaCutoff;
        const Slot base = slotOf(pack, mi, kTexSlotBaseColor);
        ASSERT_TRUE(base.valid);
        int solid = 0, holes = 0, bad = 0;
        for (const Pixel& p : insideTexels(f, kWidth, kHeight, kQuads, 0, {base})) {
            const glm::vec4 texel = gpu::texSample(base.header, base.uvOf(centreUv(f, p, kQuads)));
            const bool hole = factorAlpha * texel.w < cutoff;
            (hole ? holes : solid)++;
            for (int c = 0; c < 3; ++c) {
                const double want = hole ? 1.0 : double(glm::vec3(scene.materials[mi].pbr.baseColor)[c] * texel[c]);
                const double got = st.mean.at(p.x, p.y, c);
                if (std::abs(got - want) > 1e-5 * want + spp * std::ldexp(1.0, -24) && bad++ < 5)
                    ADD_FAILURE() << samplerName(s) << (hole ? " hole" : " solid") << " pixel " << p.x << "," << p.y
                                  << " channel " << c << ": " << got << ", want " << want;
            }
        }
        EXPECT_EQ(bad, 0) << samplerName(s);
        EXPECT_GT(solid, 900);
        EXPECT_GT(holes, 900);
        // The grey quad behind the fully cut-out ghost: its albedo, exactly.
        int behind = 0;
        for (const Pixel& p : insideTexels(f, kWidth, kHeight, kQuads, 2, {})) {
            ++behind;
            for (int c = 0; c < 3; ++c)
                if (std::abs(st.mean.at(p.x, p.y, c) - 0.6) > 1e-5 + spp * std::ldexp(1.0, -24) && bad++ < 5)
                    ADD_FAILURE() << samplerName(s) << " behind the ghost, pixel " << p.x << "," << p.y << ": "
                                  << st.mean.at(p.x, p.y, c) << ", want 0.6";
        }
        EXPECT_EQ(bad, 0) << samplerName(s);
        EXPECT_GT(behind, 3000);
        std::printf("  %s: %d solid and %d hole pixels of the mask, %d pixels behind the cut-out, all exact\n",
                    samplerName(s), solid, holes, behind);
    }
}

TEST(GpuAlpha, BlendAveragesSurfaceAndBackground) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 256;
    for (Sampler s : {Sampler::Bsdf, Sampler::Mis}) {
        const Scene scene = alphaScene(4 + std::uint32_t(s));
        const PixelStats st(renderSums(dev, scene, s, spp, "alpha.gltf"));
        gpu::GpuFrame f{};
        packFileFrameCamera(scene, f);
        const Material& m = scene.materials.at(materialNamed(scene, "blend"));
        const std::vector<Pixel> px = insideTexels(f, kWidth, kHeight, kQuads, 1, {});
        ASSERT_GT(px.size(), 3000u);
        for (int c = 0; c < 3; ++c) {
            const double a = m.pbr.baseColor.w, want = a * m.pbr.baseColor[c] + (1.0 - a);
            EXPECT_TRUE(withinNoise(average(st, px, c), want,
                                    std::string(samplerName(s)) + " blend alpha 0.25, " + kChannel[c], true));
        }
    }
}

}  // namespace
}  // namespace vkp::test
