// KHR_materials_transmission transmissionTexture on the device (lib/surface.glsl transmitsAt,
// HAS_EXTENSION_TEXTURES), label gpu: scenes/gltf/transmission-textures.gltf (tools/
// gen_gltf_scenes.py) against the same scene with the texture replaced by the constant factor it
// amounts to (transmission = transmissionFactor x texture R; github.com/KhronosGroup/glTF,
// extensions/2.0/Khronos/KHR_materials_transmission). vkpath renders any transmission > 0 as clear
// glass (kernelMaterial), so per hit: R = 0 renders like transmissionFactor 0 (the opaque glTF
// BRDF, base 0.5), R > 0 like a factor > 0. Quads under a uniform sky (tests/gpu/half_quads.h):
//   transmission-half     R 0 | 1 (nearest; G, B, A the opposite): left like factor 0, right like 1;
//   transmission-uniform  R 128/255: like factor 128/255.
// Glass under a uniform sky of radiance 1 returns exactly 1 (reflected or transmitted, every
// sample), the opaque BRDF about 0.5: with the texture ignored every glass region fails.
// 3 regions x 3 channels x 2 samplers (bsdf, mis) = 18 z-tests of the difference of two
// independent renders, family-wise false-failure probability <= 0.01 (Sidak,
// test_gpu_analytic_common.h); samples are bounded (<= 1), 64 spp x > 500 pixels.
#include <gtest/gtest.h>

#include "gpu_env.h"
#include "half_quads.h"
#include "render/features.h"
#include "render/texture_pack.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(18, 0.01));

constexpr int kQuads = 2;
constexpr std::uint32_t kSpp = 64;

/// The scene with the transmission textures replaced by constants: `right` picks the value of
/// the half texture's right texel (else its left).
Scene reference(std::uint32_t seed, bool right) {
    Scene s = halfQuadsScene("transmission-textures.gltf", kQuads, seed);
    Material& half = namedMaterial(s, "transmission-half");
    half.pbr.transmissionTexture = TextureRef{};
    half.pbr.transmission = right ? 1.0f : 0.0f;
    Material& uniform = namedMaterial(s, "transmission-uniform");
    uniform.pbr.transmissionTexture = TextureRef{};
    uniform.pbr.transmission = 128.0f / 255.0f;
    return s;
}

TEST(GpuTransmissionTexture, RendersLikeTheConstantFactorItAmountsTo) {
    VKP_REQUIRE_DEVICE(dev);
    for (Sampler smp : {Sampler::Bsdf, Sampler::Mis}) {
        const std::uint32_t k = 10 * std::uint32_t(smp);
        const Scene textured = halfQuadsScene("transmission-textures.gltf", kQuads, 201 + k);
        const Features f = sceneFeatures(textured, RenderOptions{.sampler = smp});
        ASSERT_TRUE(f.extensionTextures && f.hasMaterial(gpu::MAT_DIELECTRIC) && f.hasMaterial(gpu::MAT_PBR));  // both renderings compiled in
        const PixelStats a(renderSums(dev, textured, smp, kSpp, "transmission-textures.gltf"));
        const PixelStats left(renderSums(dev, reference(202 + k, false), smp, kSpp, "reference, left texels"));
        const PixelStats right(renderSums(dev, reference(203 + k, true), smp, kSpp, "reference, right texels"));
        const std::string s = std::string(samplerName(smp)) + " ";
        expectSameWithinNoise(a, left, halfQuadPixels(textured, 0, Half::Left), s + "transmissionTexture R 0 vs factor 0");
        // `right` is clear glass on both quads under the uniform sky: exactly 1 in every pixel, a
        // render of one colour that is right (file comment). The textured render, which must
        // differ from it where its texture is 0, is the one checked for being lit and not constant.
        expectSameWithinNoise(a, right, halfQuadPixels(textured, 0, Half::Right), s + "transmissionTexture R 1 vs factor 1",
                              SecondRender::MayBeOneColour);
        expectSameWithinNoise(a, right, halfQuadPixels(textured, 1, Half::Whole),
                              s + "transmissionTexture R 128/255 vs factor 128/255", SecondRender::MayBeOneColour);
    }
}

}  // namespace
}  // namespace vkp::test
