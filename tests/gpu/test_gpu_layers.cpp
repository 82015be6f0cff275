// Clear coat and sheen (KHR_materials_clearcoat, KHR_materials_sheen; shaders/shared/layers.h) on
// the device, label gpu:
//  1. Furnace: a layered sphere under a uniform background of radiance 1, every sampler, against a
//     host estimate of the same pixels with the C++ build of layers.h (as test_gpu_pbr.cpp does for
//     the base BRDF): a sample of a sphere pixel is the weight of one scattering, its expectation
//     the directional albedo at the pixel's view angle. Two-sided z-test of the difference; white
//     materials also one-sided "not above 1".
//  2. Textures: scenes/gltf/layer-textures.gltf (tools/gen_gltf_scenes.py) against the same scene
//     with each texture replaced by the constant it amounts to (half_quads.h): clearcoatTexture R,
//     clearcoatRoughnessTexture G, sheenColorTexture RGB (sRGB), sheenRoughnessTexture A.
//  3. The coat's normal map: the quad whose clearcoatNormalTexture tilts the coat, lit by a point
//     light, against the same quad without the texture but with its vertex normals tilted the same
//     way (its base is black with specularFactor 0, so only the coat, whose normal is then the
//     interpolated one, reflects); and, so that the comparison can fail, against the untilted coat,
//     which must differ by more than 10 standard errors.
// z-tests: Sidak-corrected over the budget below (family-wise false-failure probability <= 0.01).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "file_frame.h"
#include "furnace_sphere.h"
#include "gpu_env.h"
#include "half_quads.h"
#include "render/gpu_scene.h"
#include "render/texture_pack.h"
#include "shared/layers.h"
#include "shared/texture_sample.h"
#include "stat_suite.h"
#include "test_gpu_analytic_common.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(300, 0.01));

// ---- 1. Furnace ---------------------------------------------------------------------------------

struct LayerCase {
    const char* name;
    glm::vec3 base;
    float metallic, roughness, coat, coatRoughness;
    glm::vec3 sheen;
    float sheenRoughness;
};

Scene furnaceScene(const LayerCase& c, std::uint32_t seed) {
    Scene scene = furnaceSphereScene("layers-furnace.json");
    Material& m = scene.materials.at(0);
    m.type = MaterialType::Pbr;
    m.albedo = c.base;
    m.pbr.baseColor = glm::vec4(c.base, 1.0f);
    m.pbr.metallic = c.metallic;
    m.pbr.roughness = c.roughness;
    m.pbr.clearcoat = c.coat;
    m.pbr.clearcoatRoughness = c.coatRoughness;
    m.pbr.sheenColor = c.sheen;
    m.pbr.sheenRoughness = c.sheenRoughness;
    scene.render.seed = seed;
    return scene;
}

/// Host estimate of the sphere pixels' average (channel ch): one sample of the layered material
/// (layers.h, coat and base in one frame: a sphere has no normal map) per camera ray.
Estimate hostFurnace(const Scene& scene, const LayerCase& c, const std::vector<Pixel>& pixels, int ch, int n, std::uint32_t seed) {
    gpu::LayeredBrdf m;
    m.base = gpu::makeGltfBrdf(c.base, c.metallic, c.roughness, 1.0f, glm::vec3(1.0f));
    m.layers = gpu::makeGltfLayers(c.coat, c.coatRoughness, c.sheen, c.sheenRoughness);
    m.frame = gpu::onbFromNormal(glm::vec3(0, 0, 1));
    m.coatFrame = m.frame;
    return hostFurnaceEstimate(scene, pixels, n, seed, [&](glm::vec3 v, UniformSource& rng) {
        float pdf = 0.0f;
        const glm::vec3 l = gpu::sampleLayered(m, v, rng.next3(), pdf);
        return pdf > 0.0f ? double(gpu::evalLayeredCos(m, v, l)[ch]) / pdf : 0.0;
    });
}

TEST(GpuLayers, FurnaceMatchesHostAndNeverExceedsOne) {
    VKP_REQUIRE_DEVICE(dev);
    const LayerCase cases[] = {
        {"coat over white", glm::vec3(1.0f), 0.0f, 0.6f, 1.0f, 0.1f, glm::vec3(0.0f), 0.0f},
        {"sheen over white", glm::vec3(1.0f), 0.0f, 1.0f, 0.0f, 0.0f, glm::vec3(1.0f), 0.4f},
        {"coat and sheen over white metal", glm::vec3(1.0f), 1.0f, 0.3f, 1.0f, 0.5f, glm::vec3(1.0f), 0.8f},
        {"coloured", glm::vec3(0.7f, 0.3f, 0.1f), 0.2f, 0.5f, 0.7f, 0.3f, glm::vec3(0.2f, 0.6f, 0.9f), 0.6f},
    };
    const std::uint32_t spp = 256;
    std::uint32_t seed = 60;
    for (const LayerCase& lc : cases) {
        const Scene scene = furnaceScene(lc, 0);
        const std::vector<Pixel> px = spherePixels(scene);
        ASSERT_GT(px.size(), 150u);
        const bool white = lc.base == glm::vec3(1.0f) && (lc.sheen == glm::vec3(0.0f) || lc.sheen == glm::vec3(1.0f));
        for (Sampler s : samplersUnderTest()) {
            Scene sc = scene;
            sc.render.seed = seed++;
            const PixelStats st(renderSums(dev, sc, s, spp, lc.name));
            const std::string name = std::string(samplerName(s)) + " furnace, " + lc.name;
            for (int c = 0; c < 3; ++c) {
                if (white && c != 1) continue;  // every channel the same
                const Estimate g = average(st, px, c), h = hostFurnace(scene, lc, px, c, int(spp), 2000 + seed);
                EXPECT_TRUE(withinNoise(difference(g, h), 0.0, name + " device - host, " + kChannel[c], true));
                if (white) {
                    const double z = zBudget().take();
                    EXPECT_LE(g.mean, 1.0 + z * std::sqrt(g.var) + spp * std::ldexp(1.0, -24)) << name << " albedo above 1";
                }
            }
        }
    }
}

// ---- 2. Textures ------------------------------------------------------------------------------

constexpr int kQuads = 5;
constexpr std::uint32_t kSpp = 64;

/// layer-textures.gltf with every clear-coat and sheen texture replaced by the constant of its
/// left (or right) texels.
Scene reference(std::uint32_t seed, bool right) {
    Scene s = halfQuadsScene("layer-textures.gltf", kQuads, seed);
    Material& coat = namedMaterial(s, "clearcoat-half");
    coat.pbr.clearcoatTexture = TextureRef{};
    coat.pbr.clearcoat = right ? 1.0f : 0.0f;
    Material& coatRoughness = namedMaterial(s, "clearcoat-roughness-half");
    coatRoughness.pbr.clearcoatRoughnessTexture = TextureRef{};
    coatRoughness.pbr.clearcoatRoughness = right ? 1.0f : 0.0f;
    Material& sheen = namedMaterial(s, "sheen-color-half");
    sheen.pbr.sheenColorTexture = TextureRef{};
    sheen.pbr.sheenColor = right ? glm::vec3(0.0f, gpu::srgbToLinear(128.0f / 255.0f), 1.0f) : glm::vec3(1.0f);
    Material& sheenRoughness = namedMaterial(s, "sheen-roughness-half");
    sheenRoughness.pbr.sheenRoughnessTexture = TextureRef{};
    sheenRoughness.pbr.sheenRoughness = right ? 1.0f : 0.0f;
    return s;
}

TEST(GpuLayers, TexturesRenderLikeTheConstantFactorsTheyAmountTo) {
    VKP_REQUIRE_DEVICE(dev);
    for (Sampler smp : {Sampler::Bsdf, Sampler::Mis}) {
        const std::uint32_t k = 10 * std::uint32_t(smp);
        const Scene textured = halfQuadsScene("layer-textures.gltf", kQuads, 301 + k);
        const PixelStats a(renderSums(dev, textured, smp, kSpp, "layer-textures.gltf"));
        const PixelStats left(renderSums(dev, reference(302 + k, false), smp, kSpp, "reference, left texels"));
        const PixelStats right(renderSums(dev, reference(303 + k, true), smp, kSpp, "reference, right texels"));
        const std::string s = std::string(samplerName(smp)) + " ";
        const char* what[] = {"clearcoatTexture R", "clearcoatRoughnessTexture G", "sheenColorTexture", "sheenRoughnessTexture A"};
        for (int q = 0; q < 4; ++q) {
            expectSameWithinNoise(a, left, halfQuadPixels(textured, q, Half::Left), s + what[q] + ", left texels");
            expectSameWithinNoise(a, right, halfQuadPixels(textured, q, Half::Right), s + what[q] + ", right texels");
        }
    }
}

// ---- 3. The coat's normal map ---------------------------------------------------------------------

/// layer-textures.gltf lit by a point light beside the coat-normal quad (x in [10, 12]), no sky,
/// seen straight on (that quad alone: 80 x 80 pixels).
Scene litCoatScene(std::uint32_t seed) {
    const std::string json = R"({"camera": {"lookfrom": [11, 1, 20], "lookat": [11, 1, 0], "vup": [0, 1, 0],
        "vfov": 7.152669, "width": 80, "height": 80},
      "render": {"max_depth": 50, "background": [0, 0, 0]},
      "materials": {"unused": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "gltf", "file": "layer-textures.gltf"},
                  {"type": "point_light", "position": [17, 1, 6], "intensity": [200, 200, 200]}]})";
    Scene scene = parseSceneJson(json, scenesDir() / "gltf" / "layer-coat-test.json");
    scene.render.seed = seed;
    return scene;
}

/// The coat normal the quad's texel (171, 128, 247) gives in its frame (tangent +x, bitangent +y,
/// normal +z; lib/surface.glsl normalMapped with scale 1).
glm::vec3 mappedCoatNormal() {
    const glm::vec3 t(2.0f * 171.0f / 255.0f - 1.0f, 2.0f * 128.0f / 255.0f - 1.0f, 2.0f * 247.0f / 255.0f - 1.0f);
    return t / std::sqrt(glm::dot(t, t));
}

/// The scene without the coat's normal map; with tiltVertices, the coat-normal quad's vertex
/// normals are the mapped normal instead.
Scene coatReference(std::uint32_t seed, bool tiltVertices) {
    Scene s = litCoatScene(seed);
    Material& m = namedMaterial(s, "clearcoat-normal");
    m.pbr.clearcoatNormalTexture = TextureRef{};
    if (tiltVertices) {
        const std::uint32_t mi = std::uint32_t(&m - s.materials.data());
        for (const Shape& sh : s.shapes)
            if (sh.material == mi)
                for (std::uint32_t v : s.triangleVertices.at(sh.attributes).v) s.vertices.normal.at(v) = mappedCoatNormal();
    }
    return s;
}

TEST(GpuLayers, CoatNormalMapTiltsTheCoatOnly) {
    VKP_REQUIRE_DEVICE(dev);
    const Scene textured = litCoatScene(401);
    std::printf("  mapped coat normal (%.4f, %.4f, %.4f): %.1f degrees from the surface normal\n", mappedCoatNormal().x,
                mappedCoatNormal().y, mappedCoatNormal().z, std::acos(mappedCoatNormal().z) * 180.0 / kPi);
    const std::vector<Pixel> px = halfQuadPixels(textured, 4, Half::Whole);
    for (Sampler smp : {Sampler::Bsdf, Sampler::Light, Sampler::Mis}) {
        const std::uint32_t k = 10 * std::uint32_t(smp);
        const PixelStats a(renderSums(dev, litCoatScene(402 + k), smp, kSpp, "clearcoatNormalTexture"));
        const PixelStats tilted(renderSums(dev, coatReference(403 + k, true), smp, kSpp, "tilted vertex normals"));
        const std::string s = std::string(samplerName(smp)) + " ";
        expectSameWithinNoise(a, tilted, px, s + "coat normal map vs tilted vertex normals", SecondRender::Varied);
        // Teeth: the untilted coat reflects the light elsewhere; the comparison above must be able to fail.
        const PixelStats flat(renderSums(dev, coatReference(404 + k, false), smp, kSpp, "untilted coat"));
        const Estimate d = difference(average(a, px, 1), average(flat, px, 1));
        std::printf("  %s tilted - untilted coat: %.4g (%.1f standard errors)\n", s.c_str(), d.mean, d.mean / std::sqrt(d.var));
        EXPECT_GT(std::abs(d.mean), 10.0 * std::sqrt(d.var)) << s << "the coat normal map changes nothing";
    }
}

}  // namespace
}  // namespace vkp::test
