// host/render/texture_pack.cpp: what the kernel's texture and vertex-attribute buffers hold for
// scenes/gltf/textures.gltf (the refusal of a scene whose texels exceed the device's limit: test_gpu_arrays).
#include <gtest/gtest.h>

#include <bit>
#include <string>

#include <glm/gtc/packing.hpp>

#include "bvh/two_level.h"
#include "render/features.h"
#include "render/texture_pack.h"
#include "shared/kernel_interface.h"
#include "scene/gltf.h"
#include "test_paths.h"

namespace vkp {
namespace {

Scene texturesScene() { return loadSceneGltf(test::scenesDir() / "gltf" / "textures.gltf"); }

TEST(TexturePack, HeadersPointAtEachImagesTexels) {
    const Scene scene = texturesScene();
    const TexturePack pack = packTextures(scene);
    ASSERT_EQ(pack.info[0].y, scene.materials.size());
    ASSERT_EQ(pack.info[0].z, scene.textures.size());
    std::size_t texels = 0;
    for (const TextureImage& img : scene.images) texels += std::size_t(img.width) * img.height;
    EXPECT_EQ(pack.texels.size(), texels);
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        const glm::uvec4 h = pack.info[pack.info[0].x + t];
        const TextureImage& img = scene.images[scene.textures[t].image];
        EXPECT_EQ(h.y, img.width);
        EXPECT_EQ(h.z, img.height);
        for (std::uint32_t i = 0; i < img.width * img.height; ++i)  // R in the low byte
            ASSERT_EQ(pack.texels[h.x + i] & 255u, img.rgba8[4 * i]) << "texture " << t << " texel " << i;
    }
}

TEST(TexturePack, SpecularTexturesFillTheirSlotsAndTheirVariant) {
    const Scene scene = loadSceneGltf(test::scenesDir() / "gltf" / "specular-textures.gltf");
    const TexturePack pack = packTextures(scene);
    auto slot = [&](std::uint32_t m, std::uint32_t s) { return pack.info.at(1 + kMatTexTexels * m + 2 * s + 1).z; };
    auto header = [&](std::int32_t t) { return std::uint32_t(t); };
    EXPECT_EQ(slot(0, kTexSlotSpecular), header(scene.materials[0].pbr.specularTexture.texture));
    EXPECT_EQ(slot(0, kTexSlotSpecularColor), kNoTexture);
    EXPECT_EQ(slot(0, kTexSlotBaseColor), kNoTexture);
    EXPECT_EQ(slot(2, kTexSlotSpecular), kNoTexture);
    EXPECT_EQ(slot(2, kTexSlotSpecularColor), header(scene.materials[2].pbr.specularColorTexture.texture));
    // The alpha texel follows the slots: (mode, cutoff, normal scale, alpha factor).
    EXPECT_EQ(std::bit_cast<float>(pack.info.at(1 + kMatTexTexels * 2 + gpu::MAT_TEX_ALPHA_TEXEL).y), 0.5f);
    EXPECT_TRUE(sceneHasTextures(scene));
    EXPECT_TRUE(sceneHasExtensionTextures(scene));
    EXPECT_FALSE(sceneHasExtensionTextures(texturesScene()));  // base colour, metallicRoughness, normal only
    // The variant: HAS_EXTENSION_TEXTURES on for this scene only.
    const std::vector<std::uint32_t> on = sceneFeatures(scene).specConstants();
    ASSERT_EQ(on.size(), std::size_t(VKP_SPEC_COUNT));
    EXPECT_EQ(on[VKP_SPEC_HAS_EXTENSION_TEXTURES], 1u);
    EXPECT_EQ(sceneFeatures(texturesScene()).specConstants().at(VKP_SPEC_HAS_EXTENSION_TEXTURES), 0u);
    EXPECT_NE(sceneFeatures(scene).name().find(" extension-textures"), std::string::npos);
}

// COLOR_0: each triangle's record points (n0's w) at its two texels of half floats, which hold its
// corners' colours; the variant compiles the lookup in for this scene only.
TEST(TexturePack, VertexColoursGetTheirOwnRecords) {
    const Scene scene = loadSceneGltf(test::scenesDir() / "gltf" / "vertex-colors.gltf");
    const FlatBvh bvh = buildSceneBvh(scene);
    const std::vector<glm::uvec4> attrs = packVertexAttributes(scene, bvh);
    std::size_t records = 0;
    for (std::size_t i = 0; i < bvh.primToShape.size(); ++i) {
        const Shape& s = scene.shapes.at(bvh.primToShape[i]);
        const TriangleVertices& tv = scene.triangleVertices.at(s.attributes);
        const glm::uvec4* rec = &attrs[i * kAttributeTexels];
        ASSERT_TRUE(rec[1].z & gpu::ATTR_HAS_COLOR) << "primitive " << i;
        const std::uint32_t at = rec[2].w;
        ASSERT_GE(at, bvh.primToShape.size() * kAttributeTexels);
        ASSERT_LT(at + 1, attrs.size());
        for (int k = 0; k < 3; ++k) {
            const glm::uvec4& t = attrs[at + std::size_t(k / 2)];
            const std::uint32_t rg = (k % 2 == 0) ? t.x : t.z, ba = (k % 2 == 0) ? t.y : t.w;
            const glm::vec4 got(glm::unpackHalf2x16(rg), glm::unpackHalf2x16(ba));
            const glm::vec4 want = scene.vertices.color.at(tv.v[k]);
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], want[c], 1e-3f * std::max(1.0f, want[c])) << "primitive " << i << " corner " << k;
        }
        ++records;
    }
    EXPECT_EQ(attrs.size(), bvh.primToShape.size() * kAttributeTexels + 2 * records);
    EXPECT_TRUE(sceneFeatures(scene).vertexColors);
    EXPECT_FALSE(sceneFeatures(texturesScene()).vertexColors);
    EXPECT_NE(sceneFeatures(scene).name().find(" vertex-colors"), std::string::npos);
}

}  // namespace
}  // namespace vkp
