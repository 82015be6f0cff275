// KHR_materials_specular textures on the device (lib/surface.glsl, HAS_EXTENSION_TEXTURES), label
// gpu: scenes/gltf/specular-textures.gltf (tools/gen_gltf_scenes.py) against the same scene with
// each texture replaced by the constant factor it should amount to (the extension's README:
// specular = specularFactor x specularTexture.a, specularColor = specularColorFactor x
// specularColorTexture.rgb decoded from sRGB; github.com/KhronosGroup/glTF, extensions/2.0/
// Khronos/KHR_materials_specular). Quads under a uniform sky (tests/gpu/half_quads.h):
//   specular-half        alpha 0 | 1 (nearest): the left half renders like specularFactor 0, the
//                        right like 1;
//   specular-uniform     alpha 128/255 everywhere: like specularFactor 128/255 (0.502; the 8-bit
//                        texel closest to 0.5, decoded exactly as the factor is stored);
//   specular-color-half  RGB white | sRGB (0, 128, 255): like specularColorFactor 1 and
//                        (0, 0.2159, 1) (sRGB 128/255 decoded); read as linear the right half's
//                        G would be 0.502 and the test fails.
// Each comparison is a z-test of the difference of two independent renders (seeds differ) per
// channel, bsdf and mis: 5 regions x 3 channels x 2 samplers = 30 z-tests, family-wise false-
// failure probability <= 0.01 (Sidak, test_gpu_analytic_common.h). The samples are bounded (a
// Lambertian base 0.1 and a GGX lobe under radiance 1, throughput <= 1 per bounce, each plane
// sees only the sky), so the normal approximation holds at 64 spp x > 500 pixels.
#include <gtest/gtest.h>

#include "gpu_env.h"
#include "half_quads.h"
#include "render/texture_pack.h"
#include "shared/texture_sample.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(30, 0.01));

constexpr int kQuads = 3;
constexpr std::uint32_t kSpp = 64;

/// The scene with every specular texture replaced by a constant: `right` picks the value of the
/// halves' right texels (else the left's).
Scene reference(std::uint32_t seed, bool right) {
    Scene s = halfQuadsScene("specular-textures.gltf", kQuads, seed);
    Material& half = namedMaterial(s, "specular-half");
    half.pbr.specularTexture = TextureRef{};
    half.pbr.specular = right ? 1.0f : 0.0f;
    Material& uniform = namedMaterial(s, "specular-uniform");
    uniform.pbr.specularTexture = TextureRef{};
    uniform.pbr.specular = 128.0f / 255.0f;
    Material& color = namedMaterial(s, "specular-color-half");
    color.pbr.specularColorTexture = TextureRef{};
    color.pbr.specularColor = right ? glm::vec3(0.0f, gpu::srgbToLinear(128.0f / 255.0f), 1.0f) : glm::vec3(1.0f);
    return s;
}

TEST(GpuSpecularTextures, RenderLikeTheConstantFactorsTheyAmountTo) {
    VKP_REQUIRE_DEVICE(dev);
    for (Sampler smp : {Sampler::Bsdf, Sampler::Mis}) {
        const std::uint32_t k = 10 * std::uint32_t(smp);
        const Scene textured = halfQuadsScene("specular-textures.gltf", kQuads, 101 + k);
        ASSERT_TRUE(sceneHasExtensionTextures(textured));
        ASSERT_FALSE(sceneHasExtensionTextures(reference(0, false)));  // the references run without the lookups
        const PixelStats a(renderSums(dev, textured, smp, kSpp, "specular-textures.gltf"));
        const PixelStats left(renderSums(dev, reference(102 + k, false), smp, kSpp, "reference, left texels"));
        const PixelStats right(renderSums(dev, reference(103 + k, true), smp, kSpp, "reference, right texels"));
        const std::string s = std::string(samplerName(smp)) + " ";
        expectSameWithinNoise(a, left, halfQuadPixels(textured, 0, Half::Left), s + "specularTexture alpha 0 vs specularFactor 0");
        expectSameWithinNoise(a, right, halfQuadPixels(textured, 0, Half::Right), s + "specularTexture alpha 1 vs specularFactor 1");
        expectSameWithinNoise(a, left, halfQuadPixels(textured, 1, Half::Whole),
                              s + "specularTexture alpha 128/255 vs specularFactor 128/255");
        expectSameWithinNoise(a, left, halfQuadPixels(textured, 2, Half::Left), s + "specularColorTexture white vs factor 1");
        expectSameWithinNoise(a, right, halfQuadPixels(textured, 2, Half::Right),
                              s + "specularColorTexture sRGB (0,128,255) vs factor (0,0.216,1)");
    }
}

}  // namespace
}  // namespace vkp::test
