// host/render/texture_pack.cpp: what the kernel's texture and vertex-attribute buffers hold for
// scenes/gltf/textures.gltf (the refusal of a scene whose texels exceed the device's limit: test_gpu_arrays).
#include <gtest/gtest.h>

#include <bit>
#include <string>

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

}  // namespace
}  // namespace vkp
