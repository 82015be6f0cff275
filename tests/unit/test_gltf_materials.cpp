// glTF materials, textures and emissive lights: scenes/gltf/materials.gltf and emissive.glb
// (tools/gen_gltf_scenes.py), and what the current kernel renders for them (kernelMaterial).
#include <gtest/gtest.h>

#include <cmath>

#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace {

using namespace vkp;

std::filesystem::path gltfScene(const std::string& name) { return test::scenesDir() / "gltf" / name; }

/// Pixel (x, y) of an image as RGBA.
glm::uvec4 pixel(const TextureImage& img, std::uint32_t x, std::uint32_t y) {
    const std::size_t i = 4 * (std::size_t(y) * img.width + x);
    return {img.rgba8.at(i), img.rgba8.at(i + 1), img.rgba8.at(i + 2), img.rgba8.at(i + 3)};
}

class Materials : public ::testing::Test {
protected:
    void SetUp() override { s_ = loadSceneGltf(gltfScene("materials.gltf")); }
    /// Scene material of glTF material i (appended in order of first use, which is file order here).
    const Material& mat(std::size_t i) const { return s_.materials.at(i); }
    Scene s_;
};

TEST_F(Materials, EveryExtensionIsReadWithoutWarnings) {
    EXPECT_TRUE(s_.warnings.empty()) << s_.warnings.front();
    ASSERT_EQ(s_.materials.size(), 9u);  // 8 of the file + the default material
    for (const Material& m : s_.materials) EXPECT_EQ(m.type, MaterialType::Pbr);
}

TEST_F(Materials, Factors) {
    const Material& m = mat(0);
    EXPECT_EQ(m.name, "factors");
    EXPECT_EQ(m.pbr.baseColor, glm::vec4(0.8f, 0.2f, 0.1f, 1.0f));
    EXPECT_EQ(m.albedo, glm::vec3(0.8f, 0.2f, 0.1f));
    EXPECT_EQ(m.pbr.metallic, 0.25f);
    EXPECT_EQ(m.pbr.roughness, 0.6f);
    EXPECT_TRUE(m.twoSided);
    EXPECT_FALSE(m.emits());
    EXPECT_EQ(m.ior, 1.5f);
    EXPECT_EQ(m.pbr.specular, 1.0f);
    EXPECT_EQ(m.pbr.alphaMode, AlphaMode::Opaque);
    EXPECT_FALSE(m.pbr.baseColorTexture.valid());
    const Material k = kernelMaterial(m);  // opaque: the glTF BRDF itself
    EXPECT_EQ(k.type, MaterialType::Pbr);
    EXPECT_EQ(k.albedo, glm::vec3(0.8f, 0.2f, 0.1f));
    EXPECT_EQ(k.pbr.metallic, 0.25f);
    EXPECT_EQ(k.pbr.roughness, 0.6f);
}

TEST_F(Materials, TexturesSamplersAndTextureTransform) {
    const Material& m = mat(1);
    ASSERT_TRUE(m.pbr.baseColorTexture.valid());
    ASSERT_TRUE(m.pbr.metallicRoughnessTexture.valid());
    ASSERT_TRUE(m.pbr.normalTexture.valid());
    // Two glTF textures; each is used in one colour space only: two Scene textures, two images.
    ASSERT_EQ(s_.textures.size(), 2u);
    ASSERT_EQ(s_.images.size(), 2u);
    const Texture& base = s_.textures.at(std::size_t(m.pbr.baseColorTexture.texture));
    EXPECT_TRUE(base.srgb);
    EXPECT_EQ(base.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(base.wrapT, TextureWrap::MirroredRepeat);
    EXPECT_TRUE(base.nearest);
    const TextureImage& img = s_.images.at(base.image);  // the data-URI PNG
    ASSERT_EQ(img.width, 2u);
    ASSERT_EQ(img.height, 2u);
    ASSERT_EQ(img.rgba8.size(), 16u);
    EXPECT_EQ(pixel(img, 0, 0), glm::uvec4(255, 0, 0, 255));
    EXPECT_EQ(pixel(img, 1, 0), glm::uvec4(0, 255, 0, 255));
    EXPECT_EQ(pixel(img, 0, 1), glm::uvec4(0, 0, 255, 255));
    EXPECT_EQ(pixel(img, 1, 1), glm::uvec4(255, 255, 255, 128));

    EXPECT_EQ(m.pbr.metallicRoughnessTexture.texture, m.pbr.normalTexture.texture);  // same texture, both linear
    const Texture& data = s_.textures.at(std::size_t(m.pbr.normalTexture.texture));
    EXPECT_FALSE(data.srgb);
    EXPECT_EQ(data.wrapS, TextureWrap::Repeat);  // no sampler: repeat, bilinear
    EXPECT_FALSE(data.nearest);
    const TextureImage& checker = s_.images.at(data.image);  // textures/checker.png
    ASSERT_EQ(checker.width, 4u);
    EXPECT_EQ(pixel(checker, 0, 0), glm::uvec4(0, 128, 255, 255));
    EXPECT_EQ(pixel(checker, 1, 0), glm::uvec4(255, 64, 0, 255));

    const TextureRef& n = m.pbr.normalTexture;
    EXPECT_EQ(m.pbr.normalScale, 0.5f);
    EXPECT_EQ(n.offset, glm::vec2(0.5f, 0.0f));
    EXPECT_EQ(n.rotation, 0.3f);
    EXPECT_EQ(n.scale, glm::vec2(2.0f));
    // KHR_texture_transform: uv' = T R S uv with R = [cos sin; -sin cos].
    const glm::vec2 t = n.transform({1.0f, 0.0f});
    EXPECT_NEAR(t.x, 0.5f + 2.0f * std::cos(0.3f), 1e-6f);
    EXPECT_NEAR(t.y, -2.0f * std::sin(0.3f), 1e-6f);
    EXPECT_EQ(m.pbr.baseColorTexture.transform({0.25f, 0.75f}), glm::vec2(0.25f, 0.75f));  // identity
}

TEST_F(Materials, TangentsAreGeneratedForANormalMapOrTakenFromTheFile) {
    // Node "textured" (material 1, normal map, no TANGENT): u grows along +x, v along -y.
    const Shape& gen = s_.shapes.at(2);
    const TriangleVertices& tg = s_.triangleVertices.at(gen.attributes);
    EXPECT_EQ(tg.flags, TriangleVertices::kHasNormal | TriangleVertices::kHasUv | TriangleVertices::kHasTangent);
    for (std::uint32_t v : tg.v) {
        const glm::vec4 t = s_.vertices.tangent.at(v);
        EXPECT_NEAR(t.x, 1.0f, 1e-6f);
        EXPECT_NEAR(t.y, 0.0f, 1e-6f);
        EXPECT_NEAR(t.z, 0.0f, 1e-6f);
        EXPECT_EQ(t.w, -1.0f);  // bitangent = w cross(n, t) = -y: the direction of growing v
    }
    // Node "tangents" (the last one) has TANGENT (1,0,0,-1) in the file.
    const Shape& given = s_.shapes.back();
    const TriangleVertices& tt = s_.triangleVertices.at(given.attributes);
    EXPECT_EQ(tt.flags & TriangleVertices::kHasTangent, TriangleVertices::kHasTangent);
    for (std::uint32_t v : tt.v) EXPECT_EQ(s_.vertices.tangent.at(v), glm::vec4(1, 0, 0, -1));
    // A primitive without a normal map has no tangents (zeros keep the arrays aligned).
    const TriangleVertices& plain = s_.triangleVertices.at(s_.shapes.at(0).attributes);
    EXPECT_EQ(plain.flags & TriangleVertices::kHasTangent, 0u);
    EXPECT_EQ(s_.vertices.tangent.size(), s_.vertices.normal.size());
    EXPECT_EQ(s_.vertices.uv.size(), s_.vertices.normal.size());
}

TEST_F(Materials, EmissionWithStrengthIsALightOnItsFrontOnlyUnlessDoubleSided) {
    const Material& lamp = mat(2);
    EXPECT_EQ(lamp.emit, glm::vec3(4.0f, 2.0f, 1.0f));  // emissiveFactor x emissiveStrength 4
    EXPECT_FALSE(lamp.twoSided);
    ASSERT_TRUE(lamp.pbr.emissiveTexture.valid());
    EXPECT_TRUE(s_.textures.at(std::size_t(lamp.pbr.emissiveTexture.texture)).srgb);
    const Material& lamp2 = mat(7);
    EXPECT_EQ(lamp2.emit, glm::vec3(1.0f));
    EXPECT_TRUE(lamp2.twoSided);
    // Lights: the two triangles of each lamp quad, in order.
    ASSERT_EQ(s_.lights.size(), 4u);
    for (std::uint32_t l : s_.lights) {
        EXPECT_TRUE(s_.shapes[l].sampled);
        EXPECT_TRUE(s_.materials[s_.shapes[l].material].emits());
    }
    std::size_t sampled = 0;
    for (const Shape& sh : s_.shapes) sampled += sh.sampled;
    EXPECT_EQ(sampled, 4u);
    const Material k = kernelMaterial(lamp), k2 = kernelMaterial(lamp2);
    EXPECT_EQ(k.type, MaterialType::DiffuseLight);
    EXPECT_FALSE(k.twoSided);
    EXPECT_EQ(k.emit, lamp.emit);
    EXPECT_EQ(k2.type, MaterialType::DiffuseLight);
    EXPECT_TRUE(k2.twoSided);
}

TEST_F(Materials, TransmissionIorSpecularAlphaAndDefault) {
    const Material& glass = mat(3);
    EXPECT_EQ(glass.pbr.transmission, 1.0f);
    EXPECT_EQ(glass.ior, 1.33f);
    EXPECT_EQ(glass.pbr.roughness, 0.0f);
    const Material kg = kernelMaterial(glass);
    EXPECT_EQ(kg.type, MaterialType::Dielectric);
    EXPECT_EQ(kg.ior, 1.33f);
    EXPECT_TRUE(kg.fresnelExact);

    const Material& coated = mat(4);
    EXPECT_EQ(coated.pbr.specular, 0.0f);
    EXPECT_EQ(coated.pbr.specularColor, glm::vec3(1.0f, 0.9f, 0.8f));
    ASSERT_TRUE(coated.pbr.specularTexture.valid());
    EXPECT_FALSE(s_.textures.at(std::size_t(coated.pbr.specularTexture.texture)).srgb);
    EXPECT_FALSE(coated.pbr.specularColorTexture.valid());

    EXPECT_EQ(mat(5).pbr.alphaMode, AlphaMode::Mask);
    EXPECT_EQ(mat(5).pbr.alphaCutoff, 0.3f);
    EXPECT_EQ(mat(6).pbr.alphaMode, AlphaMode::Blend);
    EXPECT_EQ(mat(6).pbr.baseColor.w, 0.5f);

    const Material& def = mat(8);  // the primitive without a material
    EXPECT_EQ(def.pbr.metallic, 1.0f);
    EXPECT_EQ(def.pbr.roughness, 1.0f);
    const Material kd = kernelMaterial(def);
    EXPECT_EQ(kd.type, MaterialType::Pbr);  // the glTF BRDF of the default material: a rough white metal
    EXPECT_EQ(kd.albedo, glm::vec3(1.0f));
    EXPECT_EQ(kd.pbr.metallic, 1.0f);
    EXPECT_EQ(kd.pbr.roughness, 1.0f);
}

// KHR_materials_specular textures (github.com/KhronosGroup/glTF, extensions/2.0/Khronos/
// KHR_materials_specular/README.md): specularTexture is linear, its A channel scales
// specularFactor; specularColorTexture is sRGB, its RGB scales specularColorFactor.
TEST(GltfSpecularTextures, ReadWithTheirColourSpacesAndNoWarning) {
    const Scene s = loadSceneGltf(gltfScene("specular-textures.gltf"));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.materials.size(), 3u);
    const Material& half = s.materials[0];
    EXPECT_EQ(half.name, "specular-half");
    EXPECT_EQ(half.pbr.specular, 1.0f);  // the default factor
    ASSERT_TRUE(half.pbr.specularTexture.valid());
    EXPECT_EQ(half.pbr.specularTexture.texCoord, 0u);
    EXPECT_FALSE(half.pbr.specularColorTexture.valid());
    const Texture& st = s.textures.at(std::size_t(half.pbr.specularTexture.texture));
    EXPECT_FALSE(st.srgb);
    EXPECT_TRUE(st.nearest);
    EXPECT_EQ(st.wrapS, TextureWrap::ClampToEdge);
    const TextureImage& a = s.images.at(st.image);  // alpha 0 | 255, RGB a decoy
    EXPECT_EQ(pixel(a, 0, 0), glm::uvec4(255, 255, 255, 0));
    EXPECT_EQ(pixel(a, 1, 0), glm::uvec4(0, 0, 0, 255));

    const Material& color = s.materials[2];
    EXPECT_EQ(color.name, "specular-color-half");
    EXPECT_EQ(color.pbr.specularColor, glm::vec3(1.0f));
    EXPECT_FALSE(color.pbr.specularTexture.valid());
    ASSERT_TRUE(color.pbr.specularColorTexture.valid());
    const Texture& ct = s.textures.at(std::size_t(color.pbr.specularColorTexture.texture));
    EXPECT_TRUE(ct.srgb);
    EXPECT_EQ(pixel(s.images.at(ct.image), 1, 0), glm::uvec4(0, 128, 255, 0));
    for (const Material& m : s.materials) EXPECT_EQ(kernelMaterial(m).type, MaterialType::Pbr);
}

// KHR_materials_transmission transmissionTexture (github.com/KhronosGroup/glTF, extensions/2.0/
// Khronos/KHR_materials_transmission/README.md): linear, its R channel scales transmissionFactor.
TEST(GltfTransmissionTexture, ReadLinearAndDecidedPerHit) {
    const Scene s = loadSceneGltf(gltfScene("transmission-textures.gltf"));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.materials.size(), 2u);
    const Material& half = s.materials[0];
    EXPECT_EQ(half.pbr.transmission, 1.0f);
    ASSERT_TRUE(half.pbr.transmissionTexture.valid());
    EXPECT_EQ(half.pbr.transmissionTexture.texCoord, 0u);
    const Texture& t = s.textures.at(std::size_t(half.pbr.transmissionTexture.texture));
    EXPECT_FALSE(t.srgb);
    EXPECT_EQ(pixel(s.images.at(t.image), 1, 0), glm::uvec4(255, 0, 0, 0));  // R 1, the rest decoys
    // With a texture the kernel keeps the glTF BRDF and decides per hit; without, any factor > 0
    // is glass, as before.
    EXPECT_TRUE(transmissionTextured(half));
    EXPECT_EQ(kernelMaterial(half).type, MaterialType::Pbr);
    EXPECT_EQ(transmittedMaterial(half).type, MaterialType::Dielectric);
    EXPECT_EQ(transmittedMaterial(half).ior, 1.5f);
    Material plain = half;
    plain.pbr.transmissionTexture = TextureRef{};
    EXPECT_FALSE(transmissionTextured(plain));
    EXPECT_EQ(kernelMaterial(plain).type, MaterialType::Dielectric);
    plain.pbr.transmission = 0.0f;
    plain.pbr.transmissionTexture = half.pbr.transmissionTexture;  // factor 0: the texture changes nothing
    EXPECT_FALSE(transmissionTextured(plain));
    EXPECT_EQ(kernelMaterial(plain).type, MaterialType::Pbr);
}

// textureInfo.texCoord 1: the texture reads TEXCOORD_1, which the loader stores (here normalized
// uint16) beside TEXCOORD_0.
TEST(GltfTexCoord1, ReadForEverySlotWithoutWarnings) {
    const Scene s = loadSceneGltf(gltfScene("texcoord1.gltf"));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].pbr.baseColorTexture.texCoord, 1u);
    EXPECT_TRUE(s.textures.at(std::size_t(s.materials[0].pbr.baseColorTexture.texture)).srgb);
    EXPECT_EQ(s.materials[1].pbr.specularTexture.texCoord, 1u);
    EXPECT_FALSE(s.textures.at(std::size_t(s.materials[1].pbr.specularTexture.texture)).srgb);
    EXPECT_STREQ(texCoord1Slot(s.materials[0]), "baseColorTexture");
    EXPECT_STREQ(texCoord1Slot(s.materials[1]), "specularTexture");
    ASSERT_EQ(s.vertices.uv1.size(), s.vertices.normal.size());
    const TriangleVertices& tv = s.triangleVertices.at(s.shapes.at(0).attributes);
    EXPECT_EQ(tv.flags & TriangleVertices::kHasUv1, TriangleVertices::kHasUv1);
    // Quad corners top left, top right, bottom right, bottom left: TEXCOORD_1 (u, v), TEXCOORD_0 (1 - u, v).
    const glm::vec2 uv1[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (std::uint32_t v = 0; v < 4; ++v) {
        EXPECT_EQ(s.vertices.uv1.at(v), uv1[v]) << v;
        EXPECT_EQ(s.vertices.uv.at(v), glm::vec2(1.0f - uv1[v].x, uv1[v].y)) << v;
    }
}

TEST(GltfEmissive, GlbWithEmbeddedImageAndSingleAndDoubleSidedLights) {
    const Scene s = loadSceneGltf(gltfScene("emissive.glb"));
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.shapes.size(), 5u);  // floor 2, panel 2, sign 1
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights, (std::vector<std::uint32_t>{2, 3, 4}));
    const Material& panel = s.materials.at(s.shapes[2].material);
    EXPECT_EQ(panel.emit, glm::vec3(8.0f));
    EXPECT_FALSE(panel.twoSided);
    const glm::vec3 n = glm::cross(s.shapes[2].p1 - s.shapes[2].p0, s.shapes[2].p2 - s.shapes[2].p0);
    EXPECT_LT(n.y, 0.0f);  // emits downwards
    EXPECT_TRUE(s.materials.at(s.shapes[4].material).twoSided);
    // The floor's texture is a PNG inside the GLB's binary chunk.
    const Material& floor = s.materials.at(s.shapes[0].material);
    ASSERT_TRUE(floor.pbr.baseColorTexture.valid());
    const TextureImage& img = s.images.at(s.textures.at(std::size_t(floor.pbr.baseColorTexture.texture)).image);
    ASSERT_EQ(img.width, 4u);
    EXPECT_EQ(pixel(img, 0, 0), glm::uvec4(0, 128, 255, 255));
    EXPECT_EQ(pixel(img, 3, 0), glm::uvec4(255, 64, 0, 255));
    EXPECT_EQ(s.camera.width, 512u);  // aspectRatio 1.5
    EXPECT_EQ(s.camera.height, 341u);
}

// KHR_materials_unlit: an emitter of the base colour that reflects nothing (docs/gltf.md).
TEST(GltfMaterials, UnlitEmitsItsBaseColour) {
    const Scene s = loadSceneGltf(gltfScene("unlit.gltf"));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    EXPECT_TRUE(m.pbr.unlit);
    EXPECT_EQ(m.emit, glm::vec3(0.2f, 0.4f, 0.6f));
    const Material k = kernelMaterial(m);
    EXPECT_EQ(k.type, MaterialType::DiffuseLight);
    EXPECT_FALSE(k.twoSided);
    EXPECT_EQ(k.emit, glm::vec3(0.2f, 0.4f, 0.6f));
    EXPECT_EQ(s.lights.size(), 4u);
}

}  // namespace

namespace vkp {
namespace {
// KHR_materials_clearcoat and KHR_materials_sheen (github.com/KhronosGroup/glTF, extensions/2.0/
// Khronos/KHR_materials_clearcoat and KHR_materials_sheen): factors, and textures with their
// colour spaces (sheenColorTexture sRGB, the others linear); scenes/gltf/layer-textures.gltf.
TEST(GltfLayers, ClearcoatAndSheenAreReadWithTheirColourSpaces) {
    const Scene s = loadSceneGltf(gltfScene("layer-textures.gltf"));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.materials.size(), 5u);
    const auto texture = [&](const TextureRef& r) -> const Texture& { return s.textures.at(std::size_t(r.texture)); };
    const Material& coat = s.materials[0];
    EXPECT_EQ(coat.name, "clearcoat-half");
    EXPECT_EQ(coat.pbr.clearcoat, 1.0f);
    EXPECT_FLOAT_EQ(coat.pbr.clearcoatRoughness, 0.2f);
    ASSERT_TRUE(coat.pbr.clearcoatTexture.valid());
    EXPECT_FALSE(texture(coat.pbr.clearcoatTexture).srgb);
    EXPECT_EQ(coat.pbr.layers(), gpu::LAYER_COAT);
    const Material& coatRoughness = s.materials[1];
    ASSERT_TRUE(coatRoughness.pbr.clearcoatRoughnessTexture.valid());
    EXPECT_FALSE(texture(coatRoughness.pbr.clearcoatRoughnessTexture).srgb);
    const Material& sheen = s.materials[2];
    EXPECT_EQ(sheen.pbr.sheenColor, glm::vec3(1.0f));
    EXPECT_FLOAT_EQ(sheen.pbr.sheenRoughness, 0.5f);
    ASSERT_TRUE(sheen.pbr.sheenColorTexture.valid());
    EXPECT_TRUE(texture(sheen.pbr.sheenColorTexture).srgb);
    EXPECT_EQ(sheen.pbr.layers(), gpu::LAYER_SHEEN);
    const Material& sheenRoughness = s.materials[3];
    ASSERT_TRUE(sheenRoughness.pbr.sheenRoughnessTexture.valid());
    EXPECT_FALSE(texture(sheenRoughness.pbr.sheenRoughnessTexture).srgb);
    const Material& normal = s.materials[4];
    ASSERT_TRUE(normal.pbr.clearcoatNormalTexture.valid());
    EXPECT_FALSE(texture(normal.pbr.clearcoatNormalTexture).srgb);
    EXPECT_EQ(normal.pbr.clearcoatNormalScale, 1.0f);
    EXPECT_FALSE(normal.pbr.normalTexture.valid());  // the coat's map is not the base's
}
}  // namespace
}  // namespace vkp
