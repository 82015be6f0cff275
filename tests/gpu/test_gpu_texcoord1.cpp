// textureInfo.texCoord 1 on the device (lib/surface.glsl attributeUv1, sampleSlot; HAS_TEXCOORD1),
// label gpu: scenes/gltf/texcoord1.gltf (tools/gen_gltf_scenes.py), whose TEXCOORD_0 is mirrored
// and whose TEXCOORD_1 is not, against the same scene with the two UV sets swapped and every
// texture read through texCoord 0: the two must render alike (glTF 2.0 textureInfo.texCoord: the
// lookup uses TEXCOORD_<texCoord>). Quads under a uniform sky (tests/gpu/half_quads.h):
//   uv1-base      baseColorTexture (sRGB (255, 64, 0) | (0, 64, 255)) through TEXCOORD_1;
//   uv1-specular  specularTexture (alpha 0 | 1) through TEXCOORD_1.
// Read through TEXCOORD_0 instead, each half would show the other half's texel and the test fails.
// 2 quads x 2 halves x 3 channels x 2 samplers (bsdf, mis) = 24 z-tests of the difference of two
// independent renders, family-wise false-failure probability <= 0.01 (Sidak,
// test_gpu_analytic_common.h); samples are bounded (a Lambertian base and a GGX lobe under
// radiance 1, each plane sees only the sky), 64 spp x > 500 pixels.
#include <gtest/gtest.h>

#include <utility>

#include "gpu_env.h"
#include "half_quads.h"
#include "render/features.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(24, 0.01));

constexpr int kQuads = 2;
constexpr std::uint32_t kSpp = 64;

/// The scene with TEXCOORD_0 and TEXCOORD_1 swapped and every texture on texCoord 0.
Scene swapped(std::uint32_t seed) {
    Scene s = halfQuadsScene("texcoord1.gltf", kQuads, seed);
    std::swap(s.vertices.uv, s.vertices.uv1);  // both primitives have both sets (flags unchanged)
    for (Material& m : s.materials) {
        m.pbr.baseColorTexture.texCoord = 0;
        m.pbr.specularTexture.texCoord = 0;
    }
    return s;
}

TEST(GpuTexCoord1, RendersLikeTexCoord0WithTheUvSetsSwapped) {
    VKP_REQUIRE_DEVICE(dev);
    for (Sampler smp : {Sampler::Bsdf, Sampler::Mis}) {
        const std::uint32_t k = 10 * std::uint32_t(smp);
        const Scene textured = halfQuadsScene("texcoord1.gltf", kQuads, 301 + k);
        ASSERT_TRUE(sceneFeatures(textured, RenderOptions{.sampler = smp}).texCoord1);
        ASSERT_FALSE(sceneFeatures(swapped(0), RenderOptions{.sampler = smp}).texCoord1);  // the reference runs without it
        const PixelStats a(renderSums(dev, textured, smp, kSpp, "texcoord1.gltf"));
        const PixelStats b(renderSums(dev, swapped(302 + k), smp, kSpp, "texcoord1.gltf, UV sets swapped"));
        const std::string s = std::string(samplerName(smp)) + " ";
        const char* names[kQuads] = {"uv1-base (baseColorTexture)", "uv1-specular (specularTexture)"};
        for (int q = 0; q < kQuads; ++q)
            for (Half h : {Half::Left, Half::Right})
                expectSameWithinNoise(a, b, halfQuadPixels(textured, q, h),
                                      s + names[q] + (h == Half::Left ? " left" : " right") +
                                          " half: texCoord 1 vs texCoord 0 on the swapped sets");
    }
}

}  // namespace
}  // namespace vkp::test
