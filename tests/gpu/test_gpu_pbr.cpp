// The glTF metallic-roughness vertex of the kernel (MAT_PBR, shaders/shared/bsdf.h) on the
// device, every sampler (label gpu):
//  1. Furnace: a PBR sphere under a uniform background of radiance 1 and nothing else. Light leaving
//     a convex object never returns to it, so a sample of a sphere pixel is the weight of ONE
//     scattering, f cos / pdf (bsdf, light, mis), or the mixture's weight; its expectation is the
//     BRDF's directional albedo at that pixel's view angle. Checked (a) against a host estimate of
//     the same pixels (the camera's jitter and the C++ build of microfacet.h, independent samples),
//     two-sided z-test of the difference; (b) one-sided: not above 1 (white base); (c) metallic 0,
//     roughness 1, specularFactor 0 equals the Lambertian answer 1 in every pixel up to float
//     rounding (bsdf, light, mis: every weight is 1) or within noise (mixture).
//  2. All samplers agree on a box lit by a quad light holding a rough metal sphere, a near-specular
//     (roughness 0.05) dielectric sphere and a glossy floor: region differences against mis.
// z-tests: Sidak-corrected (test_gpu_analytic_common.h) over the budget declared below.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "gpu_env.h"
#include "render/gpu_scene.h"
#include "shared/microfacet.h"
#include "stat_suite.h"
#include "furnace_sphere.h"
#include "test_gpu_analytic_common.h"
#include "file_frame.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(400, 0.01));

void makePbr(Material& m, glm::vec3 base, float metallic, float roughness, float specular) {
    m.type = MaterialType::Pbr;
    m.albedo = base;
    m.pbr.baseColor = glm::vec4(base, 1.0f);
    m.pbr.metallic = metallic;
    m.pbr.roughness = roughness;
    m.pbr.specular = specular;
    m.pbr.specularColor = glm::vec3(1.0f);
}

Scene furnaceScene(glm::vec3 base, float metallic, float roughness, float specular, std::uint32_t seed) {
    Scene scene = furnaceSphereScene("pbr-furnace.json");
    makePbr(scene.materials.at(0), base, metallic, roughness, specular);
    scene.render.seed = seed;
    return scene;
}

/// Host estimate of the sphere pixels' average (channel c): per pixel n camera rays with the
/// kernel's box-filter jitter, one BRDF sample each (weight f cos / pdf, background 1).
Estimate hostFurnace(const Scene& scene, const std::vector<Pixel>& pixels, int c, int n, std::uint32_t seed) {
    const Material& m = scene.materials.at(0);
    const gpu::GltfBrdf b = gpu::makeGltfBrdf(glm::vec3(m.pbr.baseColor), m.pbr.metallic, m.pbr.roughness, m.pbr.specular,
                                              m.pbr.specularColor);
    return hostFurnaceEstimate(scene, pixels, n, seed, [&](glm::vec3 v, UniformSource& rng) {
        float pdf = 0.0f;
        const glm::vec3 l = gpu::sampleGltfBrdf(b, v, rng.next3(), pdf);
        return (l.z > 0.0f && pdf > 0.0f) ? double(gpu::evalGltfBrdf(b, v, l)[c]) * l.z / pdf : 0.0;
    });
}

struct FurnaceCase {
    glm::vec3 base;
    float metallic, roughness, specular;
};

TEST(GpuPbr, FurnaceMatchesHostAndNeverExceedsOne) {
    VKP_REQUIRE_DEVICE(dev);
    const FurnaceCase cases[] = {
        {glm::vec3(1.0f), 0.0f, 1.0f, 1.0f}, {glm::vec3(1.0f), 0.0f, 0.3f, 1.0f}, {glm::vec3(1.0f), 0.0f, 0.0f, 1.0f},
        {glm::vec3(1.0f), 1.0f, 0.2f, 1.0f}, {glm::vec3(1.0f), 1.0f, 1.0f, 1.0f}, {glm::vec3(0.9f, 0.5f, 0.2f), 0.5f, 0.5f, 0.6f},
    };
    const std::uint32_t spp = 256;
    std::uint32_t seed = 40;
    for (const FurnaceCase& fc : cases) {
        const Scene scene = furnaceScene(fc.base, fc.metallic, fc.roughness, fc.specular, 0);
        const std::vector<Pixel> px = spherePixels(scene);
        ASSERT_GT(px.size(), 150u);
        const bool white = fc.base == glm::vec3(1.0f);
        char label[96];
        std::snprintf(label, sizeof label, "metallic %.1f roughness %.1f specular %.1f", fc.metallic, fc.roughness, fc.specular);
        for (Sampler s : samplersUnderTest()) {
            Scene sc = scene;
            sc.render.seed = seed++;
            const PixelStats st(renderSums(dev, sc, s, spp, label));
            const std::string name = std::string(samplerName(s)) + " furnace " + label;
            for (int c = 0; c < 3; ++c) {
                if (white && c != 1) continue;  // a white base: every channel is the same
                // No litAndNotConstant here: in a white furnace a lossless material is exactly 1
                // everywhere, background included, so a constant image can be right; the host's
                // estimate (about 1, never 0) is what a black device image would fail against.
                const Estimate g = average(st, px, c), h = hostFurnace(scene, px, c, int(spp), 1000 + seed);
                EXPECT_TRUE(withinNoise(difference(g, h), 0.0, name + " device - host, " + kChannel[c], true));
                if (white) {
                    const double z = zBudget().take();
                    EXPECT_LE(g.mean, 1.0 + z * std::sqrt(g.var) + spp * std::ldexp(1.0, -24)) << name << " albedo above 1";
                }
            }
        }
    }
}

TEST(GpuPbr, NoSpecularEqualsLambertian) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 256;
    std::uint32_t seed = 80;
    for (Sampler s : samplersUnderTest()) {
        const Scene scene = furnaceScene(glm::vec3(1.0f), 0.0f, 1.0f, 0.0f, seed++);
        const std::vector<Pixel> px = spherePixels(scene);
        const PixelStats st(renderSums(dev, scene, s, spp, "lambertian pbr"));
        const std::string name = std::string(samplerName(s)) + " specularFactor 0";
        if (s == Sampler::Mixture) {
            for (int c = 0; c < 3; ++c) EXPECT_TRUE(withinNoise(average(st, px, c), 1.0, name + ", " + kChannel[c], true));
            continue;
        }
        // Every weight is (1/pi) cos / (cos/pi) = 1 up to rounding: n u per pixel sum, as for a
        // white Lambertian sphere (test_gpu_analytic_furnace.cpp).
        for (const Pixel& p : px)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(st.mean.at(p.x, p.y, c), 1.0, spp * std::ldexp(1.0, -24) + 1e-6) << name << " at " << p.x << "," << p.y;
    }
}

// ---- All samplers agree -------------------------------------------------------------------------

Scene glossyBox(std::uint32_t seed) {
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 1, 3.4], "lookat": [0, 0.9, 0], "vup": [0, 1, 0], "vfov": 45, "width": 16, "height": 16},
      "render": {"max_depth": 8, "background": [0, 0, 0]},
      "materials": {
        "white": {"type": "lambertian", "albedo": [0.7, 0.7, 0.7]},
        "red": {"type": "lambertian", "albedo": [0.6, 0.1, 0.1]},
        "floor": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
        "metal": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
        "gloss": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
        "light": {"type": "diffuse_light", "emit": [8, 8, 8]}},
      "objects": [
        {"type": "quad", "Q": [-1, 0, -1], "u": [0, 0, 2], "v": [2, 0, 0], "material": "floor"},
        {"type": "quad", "Q": [-1, 0, -1], "u": [2, 0, 0], "v": [0, 2, 0], "material": "white"},
        {"type": "quad", "Q": [-1, 0, -1], "u": [0, 2, 0], "v": [0, 0, 2], "material": "red"},
        {"type": "quad", "Q": [1, 0, -1], "u": [0, 2, 0], "v": [0, 0, 2], "material": "white"},
        {"type": "quad", "Q": [-1, 2, -1], "u": [2, 0, 0], "v": [0, 0, 2], "material": "white"},
        {"type": "quad", "Q": [-0.4, 1.99, -0.4], "u": [0.8, 0, 0], "v": [0, 0, 0.8], "material": "light"},
        {"type": "sphere", "center": [0.4, 0.4, -0.2], "radius": 0.4, "material": "metal"},
        {"type": "sphere", "center": [-0.45, 0.35, 0.25], "radius": 0.35, "material": "gloss"}]})",
                                 "pbr-box.json");
    for (Material& m : scene.materials) {
        if (m.name == "floor") makePbr(m, glm::vec3(0.6f, 0.5f, 0.4f), 0.0f, 0.3f, 1.0f);
        if (m.name == "metal") makePbr(m, glm::vec3(0.9f, 0.7f, 0.4f), 1.0f, 0.35f, 1.0f);
        if (m.name == "gloss") makePbr(m, glm::vec3(0.2f, 0.3f, 0.8f), 0.0f, 0.05f, 1.0f);
    }
    scene.render.seed = seed;
    return scene;
}

TEST(GpuPbr, AllSamplersAgreeOnAGlossyBox) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 1024;
    int pbrMaterials = 0;
    for (const Material& m : glossyBox(0).materials) pbrMaterials += kernelMaterial(m).type == MaterialType::Pbr;
    ASSERT_EQ(pbrMaterials, 3);
    const PixelStats ref(renderSums(dev, glossyBox(501), Sampler::Mis, spp, "glossy box"));
    EXPECT_TRUE(litAndNotConstant(ref.mean, "glossy box, mis"));
    for (Sampler s : samplersUnderTest()) {
        if (s == Sampler::Mis) continue;
        const PixelStats st(renderSums(dev, glossyBox(510 + std::uint32_t(s)), s, spp, "glossy box"));
        EXPECT_TRUE(litAndNotConstant(st.mean, std::string("glossy box, ") + samplerName(s)));
        for (const auto& [name, px] : imageAndBlocks(16, 4))
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(withinNoise(difference(st, ref, px, c), 0.0,
                                        std::string(samplerName(s)) + " - mis, glossy box, " + name + ", " + kChannel[c],
                                        name == "image"));
    }
}

}  // namespace
}  // namespace vkp::test
