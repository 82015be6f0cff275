// glTF textures on the device (shaders/shared/texture_sample.h, shaders/lib/surface.glsl), label gpu:
//  1. The GLSL build of texSample / texTransform (kernel shaders/tests/texture_test.comp, texels in
//     an R32UI texel buffer as in the path tracer) against the C++ build on the same lookups: a
//     5x3 and a 1x1 image, every wrap mode, bilinear and nearest, sRGB and linear, 16,000 random
//     UVs in [-3, 3]^2 and special values (texel centres and edges, 1e6, NaN).
//  2. scenes/gltf/textures.gltf under a uniform background of radiance 1 (a JSON scene including
//     it): quads in the camera's focal plane with pure Lambertian glTF materials (specularFactor 0)
//     seen straight on. Light leaving a plane never returns to it, so every sample of a quad pixel
//     is the base colour at the point the camera ray hit (bsdf, light, mis: every weight is exactly
//     1 x albedo). With NEAREST filtering and a pixel footprint inside one texel, the pixel is
//     baseColorFactor x the decoded texel to float rounding: REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT
//     and KHR_texture_transform, the texel predicted by the C++ texSample at the pixel centre.
//  3. Bilinear filtering: where a pixel's footprint lies inside one bilinear cell (between four
//     texel centres) the filtered value is bilinear in the image plane, so its mean over the
//     pixel's box is its value at the centre: z-tests of cell averages.
//  4. metallicRoughnessTexture (metallicFactor 1 x B): pixels on metallic-0 texels exactly the
//     Lambertian answer, pixels on metallic-1 texels far from it (a rough metal).
//  5. normalTexture (on a mesh with NORMAL and on one without): a constant tangent-space normal
//     tilted by theta; with directions below the
//     geometric surface given f = 0 (lib/surface.glsl), a Lambertian plane under a uniform sky
//     reflects albedo x (1 + cos theta) / 2 (the part of the tilted cosine lobe above the plane).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "gpu_env.h"
#include "render/texture_pack.h"
#include "stat_suite.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"
#include "texture_scene.h"
#include "texture_test.spv.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"
#include "file_frame.h"


namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(600, 0.01));

// ---- 1. GLSL against C++ ------------------------------------------------------------------------

struct KernelPush {
    glm::uvec4 headers[4];
    glm::vec4 rs;
    glm::vec4 offset;
    std::uint32_t count;
};

std::vector<glm::vec4> runTextureKernel(VulkanDevice& dev, const std::vector<std::uint32_t>& texels, KernelPush push,
                                        const std::vector<glm::vec4>& items) {
    ComputePipelineDesc d;
    d.spirv = std::span<const std::uint32_t>(kTextureTestSpv);
    d.bindings = {vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eStorageBuffer,
                  vk::DescriptorType::eStorageBuffer};
    d.pushConstantBytes = sizeof(KernelPush);
    ComputePipeline pipe(dev, d);
    push.count = std::uint32_t(items.size());
    GpuBuffer tex(dev, texels.size() * 4, vk::BufferUsageFlagBits::eUniformTexelBuffer);
    tex.upload(texels.data(), texels.size() * 4);
    const vk::raii::BufferView view = tex.texelView(vk::Format::eR32Uint);
    GpuBuffer in(dev, items.size() * 16, vk::BufferUsageFlagBits::eStorageBuffer);
    GpuBuffer out(dev, items.size() * 32, vk::BufferUsageFlagBits::eStorageBuffer);
    in.upload(items.data(), items.size() * 16);
    pipe.bindTexelView(0, *view);
    pipe.bindBuffer(1, in.buffer());
    pipe.bindBuffer(2, out.buffer());
    dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) {
        pipe.recordDispatch(cmd, (push.count + 63) / 64, 1, &push, sizeof push);
    });
    std::vector<glm::vec4> result(items.size() * 2);
    out.download(result.data(), result.size() * 16);
    dev.instance().throwIfValidationMessages("texture test kernel");
    return result;
}

TEST(GpuTextures, GlslMatchesCppOnTheSameLookups) {
    VKP_REQUIRE_DEVICE(dev);
    UniformSource src(17);
    std::vector<std::uint32_t> texels(16);  // a 5x3 image at 0, a 1x1 image at 15
    for (std::uint32_t& t : texels) t = std::uint32_t(src.next() * 16777216.0f) | (std::uint32_t(src.next() * 256.0f) << 24u);
    KernelPush push{};
    push.headers[0] = glm::uvec4(0, 5, 3, gpu::TEXF_WRAP_REPEAT | (gpu::TEXF_WRAP_MIRROR << 2u) | gpu::TEXF_SRGB);
    push.headers[1] = glm::uvec4(0, 5, 3, gpu::TEXF_WRAP_CLAMP | (gpu::TEXF_WRAP_REPEAT << 2u));
    push.headers[2] = glm::uvec4(0, 5, 3, gpu::TEXF_WRAP_MIRROR | (gpu::TEXF_WRAP_CLAMP << 2u) | gpu::TEXF_NEAREST | gpu::TEXF_SRGB);
    push.headers[3] = glm::uvec4(15, 1, 1, gpu::TEXF_WRAP_REPEAT | (gpu::TEXF_WRAP_REPEAT << 2u) | gpu::TEXF_SRGB);
    const float rot = 0.7f;
    push.rs = glm::vec4(std::cos(rot) * 1.5f, std::sin(rot) * 0.5f, -std::sin(rot) * 1.5f, std::cos(rot) * 0.5f);
    push.offset = glm::vec4(0.25f, -2.0f, 0.0f, 0.0f);
    std::vector<glm::vec4> items;
    const float special[] = {0.0f, 0.1f, 0.2f, 0.5f, 1.0f, -1.0f, 1.0f / 3.0f, 1e-8f, -1e-8f, 1e6f, std::nanf("")};
    for (int h = 0; h < 4; ++h) {
        for (float a : special)
            for (float b : special) items.emplace_back(a, b, float(h), 0.0f);
        for (int i = 0; i < 4000; ++i) items.emplace_back(src.next() * 6.0f - 3.0f, src.next() * 6.0f - 3.0f, float(h), 0.0f);
    }
    const std::vector<glm::vec4> got = runTextureKernel(dev, texels, push, items);
    gTexels = &texels;
    double worst = 0.0, worstT = 0.0;
    int bad = 0, edges = 0;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const glm::uvec4 header = push.headers[int(items[i].z)];
        const glm::vec2 uv(items[i]);
        const glm::vec4 want = gpu::texSample(header, uv);
        const glm::vec2 tw = gpu::texTransform(uv, push.rs, glm::vec2(push.offset));
        if ((header.w & gpu::TEXF_NEAREST) != 0u) {
            // Nearest is discontinuous at texel edges: a point within rounding of one may pick the
            // neighbour in one build. Such items are counted, not compared.
            // (Clamped coordinates beyond the image are on no edge.)
            auto onEdge = [](float u, std::uint32_t mode, std::uint32_t n) {
                const float f = gpu::texReduce(u, mode) * float(n), k = std::round(f);
                const bool inside = mode != gpu::TEXF_WRAP_CLAMP || (k > 0.0f && k < float(n));
                return inside && std::abs(f - k) < 1e-4f;
            };
            if (onEdge(uv.x, header.w & 3u, header.y) || onEdge(uv.y, (header.w >> 2u) & 3u, header.z)) {
                edges += (i % 4121) >= 121 ? 1 : 0;  // random items only (most special values sit on edges)
                continue;
            }
        }
        double err = 0.0;
        for (int c = 0; c < 4; ++c) err = std::max(err, double(std::abs(got[2 * i][c] - want[c])));
        const double errT = std::max(std::abs(got[2 * i + 1].x - tw.x), std::abs(got[2 * i + 1].y - tw.y));
        worst = std::max(worst, err);
        worstT = std::max(worstT, errT);
        if ((err > 2e-6 || errT > 1e-5 * (1.0 + std::abs(tw.x) + std::abs(tw.y))) && bad++ < 5)
            ADD_FAILURE() << "item " << i << " uv " << uv.x << "," << uv.y << " header " << items[i].z << ": device "
                          << got[2 * i].x << "," << got[2 * i].y << "," << got[2 * i].z << "," << got[2 * i].w << " host "
                          << want.x << "," << want.y << "," << want.z << "," << want.w;
    }
    std::printf("  %zu lookups: worst texel difference %.3g, worst transform difference %.3g, %d random nearest items on an edge\n",
                items.size(), worst, worstT, edges);
    EXPECT_EQ(bad, 0);
    EXPECT_LT(edges, 10);  // of 4000 random nearest items: 1e-4 of a texel on either side of ~16 edges
}

// ---- 2-5. Renders of scenes/gltf/textures.gltf ------------------------------------------------


Scene texturesScene(std::uint32_t seed) {
    // Quad i covers x in [2.5 i, 2.5 i + 2], y in [0, 2] at z = 0, which is the focal plane: the
    // point a camera ray aims at is the point it hits.
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [9.75, 1, 20], "lookat": [9.75, 1, 0], "vup": [0, 1, 0], "vfov": 7.152669,
                 "width": 640, "height": 80},
      "render": {"max_depth": 50, "background": [1, 1, 1]},
      "materials": {"unused": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "gltf", "file": "textures.gltf"}]})",
                                 scenesDir() / "gltf" / "textures-test.json");
    scene.render.seed = seed;
    return scene;
}

struct TexturedRender {
    Scene scene;
    TexturePack pack;
    gpu::GpuFrame frame{};
    PixelStats stats;
};

constexpr std::uint32_t kWidth = 640, kHeight = 80;
constexpr int kQuads = 8;

TexturedRender renderTextures(VulkanDevice& dev, Sampler s, std::uint32_t spp, std::uint32_t seed) {
    Scene scene = texturesScene(seed);
    EXPECT_EQ(scene.camera.width, kWidth);
    PixelStats st(renderSums(dev, scene, s, spp, "textures.gltf"));
    TexturedRender r{scene, packTextures(scene), gpu::GpuFrame{}, st};
    packFileFrameCamera(r.scene, r.frame);
    return r;
}

const glm::vec3 kFactor(1.0f, 0.5f, 1.0f);  // baseColorFactor of every quad

TEST(GpuTextures, NearestWrapAndTransformGiveTheTexelExactly) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 16;
    for (Sampler s : {Sampler::Bsdf, Sampler::Mis}) {
        TexturedRender r = renderTextures(dev, s, spp, 5);
        gTexels = &r.pack.texels;
        const char* names[] = {"repeat", "clamp", "mirror", "transform"};
        for (int q = 0; q < 4; ++q) {
            const Slot base = slotOf(r.pack, materialNamed(r.scene, names[q]), kTexSlotBaseColor);
            ASSERT_TRUE(base.valid && (base.header.w & gpu::TEXF_NEAREST) && (base.header.w & gpu::TEXF_SRGB)) << names[q];
            const std::vector<Pixel> px = insideTexels(r.frame, kWidth, kHeight, kQuads, q, {base});
            EXPECT_GT(px.size(), 2000u) << names[q];  // of ~4300 pixels on the quad
            int bad = 0;
            std::map<std::pair<int, int>, int> seen;
            for (const Pixel& p : px) {
                const glm::vec2 uv = centreUv(r.frame, p, kQuads);
                const glm::vec4 texel = gpu::texSample(base.header, base.uvOf(uv));
                const glm::ivec2 t = base.texel(uv);
                ++seen[{t.x, t.y}];
                for (int c = 0; c < 3; ++c) {
                    const double want = double(kFactor[c] * texel[c]);
                    const double got = r.stats.mean.at(p.x, p.y, c);
                    if (std::abs(got - want) > 1e-5 * want + spp * std::ldexp(1.0, -24) && bad++ < 5)
                        ADD_FAILURE() << samplerName(s) << " " << names[q] << " pixel " << p.x << "," << p.y << " uv "
                                      << uv.x << "," << uv.y << " channel " << c << ": " << got << ", texel (" << t.x
                                      << "," << t.y << ") gives " << want;
                }
            }
            EXPECT_EQ(bad, 0) << samplerName(s) << " " << names[q];
            // Every mode shows all 16 texels at least once over UVs in [-0.75, 1.75]; clamp and
            // mirror repeat edge texels where repeat shows the opposite edge.
            EXPECT_EQ(seen.size(), 16u) << names[q];
            std::printf("  %s %s: %zu pixels inside one texel, all equal to factor x texel\n", samplerName(s), names[q],
                        px.size());
        }
    }
}

TEST(GpuTextures, BilinearCellMeansAreTheCentreValues) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 256;
    TexturedRender r = renderTextures(dev, Sampler::Mis, spp, 6);
    gTexels = &r.pack.texels;
    const Slot base = slotOf(r.pack, materialNamed(r.scene, "bilinear"), kTexSlotBaseColor);
    ASSERT_TRUE(base.valid && !(base.header.w & gpu::TEXF_NEAREST));
    // A bilinear cell: between four texel centres of the unwrapped grid. Every wrap mode keeps
    // texel centres at (k + 0.5) / n (mirroring maps texel k to -1 - k), so the filtered value is
    // bilinear inside such a cell; across it (a centre) it has a kink.
    const CellOf cell = [&](glm::vec2 uv) {
        const glm::vec2 t = base.uvOf(uv);
        return glm::ivec2(int(std::floor(t.x * float(base.header.y) - 0.5f)), int(std::floor(t.y * float(base.header.z) - 0.5f)));
    };
    const std::vector<Pixel> px = insideCells(r.frame, kWidth, kHeight, kQuads, 4, {cell});
    ASSERT_GT(px.size(), 2000u);
    // Grouped by cell; each pixel has its own expected value, so any grouping is a valid test.
    std::map<std::pair<int, int>, std::vector<Pixel>> byCell;
    for (const Pixel& p : px) {
        const glm::ivec2 c = cell(centreUv(r.frame, p, kQuads));
        byCell[{c.x, c.y}].push_back(p);
    }
    int tests = 0;
    for (const auto& [cell, pixels] : byCell) {
        if (pixels.size() < 8) continue;
        for (int c = 0; c < 3; ++c) {
            double want = 0.0;
            for (const Pixel& p : pixels) want += double(kFactor[c] * gpu::texSample(base.header, centreUv(r.frame, p, kQuads))[c]);
            want /= double(pixels.size());
            EXPECT_TRUE(withinNoise(average(r.stats, pixels, c), want, "bilinear cell, " + std::string(kChannel[c])));
            ++tests;
        }
    }
    std::printf("  bilinear: %d cell averages (%zu pixels) against the filtered value at the pixel centres\n", tests,
                px.size());
    EXPECT_GT(tests, 60);
}

TEST(GpuTextures, MetallicRoughnessMapSelectsTheMetal) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 64;
    TexturedRender r = renderTextures(dev, Sampler::Mis, spp, 7);
    gTexels = &r.pack.texels;
    const std::uint32_t mi = materialNamed(r.scene, "metalrough");
    const Slot base = slotOf(r.pack, mi, kTexSlotBaseColor), mr = slotOf(r.pack, mi, kTexSlotMetallicRoughness);
    ASSERT_TRUE(base.valid && mr.valid);
    const std::vector<Pixel> px = insideTexels(r.frame, kWidth, kHeight, kQuads, 5, {base, mr});
    int dielectric = 0, bad = 0;
    std::vector<Pixel> metal;
    for (const Pixel& p : px) {
        const glm::vec2 uv = centreUv(r.frame, p, kQuads);
        const glm::vec4 m = gpu::texSample(mr.header, mr.uvOf(uv));
        const glm::vec4 texel = gpu::texSample(base.header, base.uvOf(uv));
        if (m.z == 0.0f) {  // metallic 0: the Lambertian base, exactly
            ++dielectric;
            for (int c = 0; c < 3; ++c) {
                const double want = double(kFactor[c] * texel[c]), got = r.stats.mean.at(p.x, p.y, c);
                if (std::abs(got - want) > 1e-5 * want + spp * std::ldexp(1.0, -24) && bad++ < 5)
                    ADD_FAILURE() << "metallic-0 pixel " << p.x << "," << p.y << " channel " << c << ": " << got
                                  << ", want " << want;
            }
        } else {
            metal.push_back(p);
        }
    }
    EXPECT_EQ(bad, 0);
    EXPECT_GT(dielectric, 800);
    ASSERT_GT(metal.size(), 800u);
    // A rough metal (alpha 1) under a uniform sky reflects F0 x its directional albedo (< 1, GGX
    // loses energy at alpha 1) plus a Fresnel rise: far from the Lambertian base in the dark
    // channel (G: factor 0.5), where F0 = base, the Lambertian answer would be that base itself.
    // The mean over metal pixels of (pixel - Lambertian answer) / Lambertian answer:
    double rel = 0.0;
    for (const Pixel& p : metal) {
        const glm::vec4 texel = gpu::texSample(base.header, base.uvOf(centreUv(r.frame, p, kQuads)));
        rel += (r.stats.mean.at(p.x, p.y, 1) - double(kFactor[1] * texel[1])) / double(kFactor[1] * texel[1]);
    }
    rel /= double(metal.size());
    std::printf("  metallicRoughness: %d metallic-0 pixels exact, %zu metal pixels, mean relative difference from "
                "Lambertian %.3f\n", dielectric, metal.size(), rel);
    EXPECT_GT(std::abs(rel), 0.05);
}

TEST(GpuTextures, NormalMapTiltsTheCosineLobe) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 256;
    for (Sampler s : {Sampler::Bsdf, Sampler::Mis}) {
      TexturedRender r = renderTextures(dev, s, spp, 8 + std::uint32_t(s));
      gTexels = &r.pack.texels;
      // Quad 6 has NORMAL (0, 0, 1); quad 7 none: the map perturbs the flat normal, the same here.
      for (const int quad : {6, 7}) {
        const std::uint32_t mi = materialNamed(r.scene, quad == 6 ? "normal" : "normal-flat");
        const Slot base = slotOf(r.pack, mi, kTexSlotBaseColor), nm = slotOf(r.pack, mi, kTexSlotNormal);
        ASSERT_TRUE(base.valid && nm.valid);
        // The kernel's tangent-space normal from the 1x1 map at scale 0.8 (glTF: (2 c - 1) x scale in xy).
        const glm::vec4 c = gpu::texSample(nm.header, glm::vec2(0.5f));
        const float scale = r.scene.materials[mi].pbr.normalScale;
        const glm::dvec3 tn((2.0 * c.x - 1.0) * scale, (2.0 * c.y - 1.0) * scale, 2.0 * c.z - 1.0);
        const double cosTheta = tn.z / glm::length(tn), expectFraction = 0.5 * (1.0 + cosTheta);
        const std::vector<Pixel> px = insideTexels(r.frame, kWidth, kHeight, kQuads, quad, {base});
        ASSERT_GT(px.size(), 2000u);
        for (int ch = 0; ch < 3; ++ch) {
            // Average over the pixels of pixel / albedo: expected (1 + cos theta) / 2.
            Estimate e;
            for (const Pixel& p : px) {
                const double a = double(kFactor[ch] * gpu::texSample(base.header, base.uvOf(centreUv(r.frame, p, kQuads)))[ch]);
                e.mean += r.stats.mean.at(p.x, p.y, ch) / a;
                e.var += r.stats.var.at(p.x, p.y, ch) / (a * a);
                e.n = spp;
            }
            e.mean /= double(px.size());
            e.var /= double(px.size()) * double(px.size());
            EXPECT_TRUE(withinNoise(e, expectFraction,
                                    std::string(samplerName(s)) + " " + r.scene.materials[mi].name + " (theta " +
                                        std::to_string(std::acos(cosTheta) * 180.0 / kPi) + " deg), " + kChannel[ch],
                                    true));
        }
      }
    }
}

}  // namespace
}  // namespace vkp::test
