// Textures of JSON scenes on the host (shaders/shared/solid_texture.h, the exact code the kernel
// runs; host/render/perlin_table.cpp; host/scene/scene_json_textures.cpp): the book's sphere UVs
// and checker, the Perlin table and noise, turbulence and marble, RGB9E5 texels, and what the
// loader makes of each texture kind (packed as the kernel reads it). Bad input is in
// test_scene_errors.cpp; the device's build against this one in tests/gpu/test_gpu_solid_textures.cpp.
#include "solid_texture_host.h"  // first: the host build of shared/solid_texture.h

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <random>
#include <set>

#include "core/image_io.h"
#include "core/input_file.h"
#include "render/perlin_table.h"
#include "scene/ldr_image.h"
#include "scene/scene.h"
#include "scene/solid_texture.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

using namespace gpu;

/// The table's noise at p (the scene-independent part of a pack).
struct PerlinPack {
    TexturePack pack;
    PerlinPack() {
        pack.info.assign(1, glm::uvec4(0, 0, 0, 1));     // the solid textures start at texel 1
        pack.info.emplace_back(0u, 0u, 0u, 1u);          // origin 0, table right after
        const std::vector<glm::uvec4> t = perlinTable();
        pack.info.insert(pack.info.end(), t.begin(), t.end());
        pack.texels.assign(1, 0u);
    }
    float noise(glm::vec3 p) const {
        gSolidPack = &pack;
        return perlinNoise(p, 1u);
    }
    float turb(glm::vec3 p) const {
        gSolidPack = &pack;
        return perlinTurbulence(p, 1u);
    }
};

TEST(SolidTexture, SphereUvIsTheBooks) {
    // "Ray Tracing: The Next Week", sec. 4.4: <1 0 0> -> <0.50 0.50>, <-1 0 0> -> <0.00 0.50>,
    // <0 1 0> -> <0.50 1.00>, <0 -1 0> -> <0.50 0.00>, <0 0 1> -> <0.25 0.50>, <0 0 -1> -> <0.75 0.50>.
    const struct {
        glm::vec3 n;
        glm::vec2 uv;
    } cases[] = {{{1, 0, 0}, {0.5f, 0.5f}}, {{0, 1, 0}, {0.5f, 1.0f}},   {{0, -1, 0}, {0.5f, 0.0f}},
                 {{0, 0, 1}, {0.25f, 0.5f}}, {{0, 0, -1}, {0.75f, 0.5f}}};
    for (const auto& c : cases) {
        const glm::vec2 uv = sphereUv(c.n);
        EXPECT_NEAR(uv.x, c.uv.x, 1e-6f) << c.n.x << "," << c.n.y << "," << c.n.z;
        EXPECT_NEAR(uv.y, c.uv.y, 1e-6f) << c.n.x << "," << c.n.y << "," << c.n.z;
    }
    // <-1 0 0>: phi = atan2(-0, -1) + pi is 0 or 2 pi depending on the sign of zero: the seam.
    const float u = sphereUv(glm::vec3(-1, 0, 0)).x;
    EXPECT_TRUE(std::abs(u) < 1e-6f || std::abs(u - 1.0f) < 1e-6f) << u;
}

TEST(SolidTexture, CheckerIsTheBooksIntegerFormula) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> d(-60.0f, 60.0f);
    const float invScale = 1.0f / 0.32f;
    for (int i = 0; i < 100000; ++i) {
        const glm::vec3 p(d(rng), d(rng), d(rng));
        // The book (sec. 4.3): (int(floor(inv_scale x)) + ... ) % 2 == 0.
        const long long s = (long long)std::floor(invScale * p.x) + (long long)std::floor(invScale * p.y) +
                            (long long)std::floor(invScale * p.z);
        ASSERT_EQ(checkerEven(p, invScale), s % 2 == 0) << p.x << "," << p.y << "," << p.z;
    }
    // Far away and special values: no integer overflow, a definite answer.
    EXPECT_TRUE(checkerEven(glm::vec3(3e38f, 3e38f, 0.5f), 1.0f));  // every float above 2^24 is an even integer
    EXPECT_FALSE(checkerEven(glm::vec3(1.5f, 0.0f, 0.0f), 1.0f));
    EXPECT_TRUE(checkerEven(glm::vec3(-0.5f, -0.5f, 0.5f), 1.0f));   // -1 + -1 + 0
}

TEST(SolidTexture, PerlinTableIsTheBooksAndTheSameEveryTime) {
    const std::vector<glm::uvec4> t = perlinTable();
    ASSERT_EQ(t.size(), PERLIN_POINTS);
    EXPECT_EQ(t, perlinTable());
    std::set<std::uint32_t> perm[3];
    glm::dvec3 mean(0.0);
    for (const glm::uvec4& e : t) {
        const glm::vec3 g(std::bit_cast<float>(e.x), std::bit_cast<float>(e.y), std::bit_cast<float>(e.z));
        EXPECT_NEAR(glm::length(g), 1.0f, 1e-6f);
        mean += glm::dvec3(g);
        for (int a = 0; a < 3; ++a) perm[a].insert((e.w >> (8 * a)) & 255u);
        EXPECT_EQ(e.w >> 24, 0u);
    }
    for (int a = 0; a < 3; ++a) EXPECT_EQ(perm[a].size(), 256u) << "axis " << a << " is a permutation of 0..255";
    // 256 directions of the cube made unit: each component has mean 0 and standard deviation
    // ~0.58, so the mean of 256 is within 4 standard errors (0.15) unless the table is broken.
    for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(mean[a] / 256.0), 0.15) << a;
}

TEST(SolidTexture, NoiseVanishesAtLatticePointsIsBoundedAndContinuous) {
    const PerlinPack pp;
    for (int i = -300; i <= 300; i += 7)
        for (int j = -5; j <= 5; ++j) EXPECT_EQ(pp.noise(glm::vec3(float(i), float(j), float(i + j))), 0.0f);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> d(-40.0f, 40.0f);
    float lo = 1, hi = -1;
    for (int i = 0; i < 50000; ++i) {
        const glm::vec3 p(d(rng), d(rng), d(rng));
        const float n = pp.noise(p);
        ASSERT_LE(std::abs(n), std::sqrt(3.0f)) << "the bound solidTextureBound uses";
        lo = std::min(lo, n);
        hi = std::max(hi, n);
        // Lipschitz: the gradient is bounded (a few units), so a step of 1e-3 changes little,
        // also across cell faces (Hermite smoothing makes it C1).
        const glm::vec3 q = p + glm::vec3(1e-3f, -1e-3f, 1e-3f);
        ASSERT_LT(std::abs(pp.noise(q) - n), 0.02f) << p.x << "," << p.y << "," << p.z;
    }
    EXPECT_LT(lo, -0.4f);
    EXPECT_GT(hi, 0.4f);
    // Across a cell face exactly.
    for (int k = -3; k <= 3; ++k) {
        const glm::vec3 a(float(k) - 1e-4f, 0.3f, 0.7f), b(float(k) + 1e-4f, 0.3f, 0.7f);
        EXPECT_LT(std::abs(pp.noise(a) - pp.noise(b)), 2e-3f) << k;
    }
}

TEST(SolidTexture, TurbulenceIsTheBooksSevenOctaveSum) {
    const PerlinPack pp;
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> d(-10.0f, 10.0f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 p(d(rng), d(rng), d(rng));
        double sum = 0, w = 1;
        glm::vec3 q = p;
        for (int o = 0; o < 7; ++o, w *= 0.5, q *= 2.0f) sum += w * pp.noise(q);
        const float t = pp.turb(p);
        EXPECT_GE(t, 0.0f);
        EXPECT_NEAR(t, std::abs(sum), 1e-5) << i;
        EXPECT_LE(t, 2.0f * std::sqrt(3.0f));
    }
}

TEST(SolidTexture, Rgb9e5KeepsNineBitsOfTheLargestChannel) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> e(-20.0f, 15.0f), f(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        const float scale = std::exp2(e(rng));
        const glm::vec3 c(f(rng) * scale, f(rng) * scale, f(rng) * scale);
        const glm::vec4 back = rgb9e5Decode(packRgb9e5(c));
        const float m = std::max({c.x, c.y, c.z});
        // Half a step of the shared exponent, at most 1/256 of the largest channel; the smallest
        // step is 2^-24 (exponent 0).
        for (int k = 0; k < 3; ++k) ASSERT_LE(std::abs(back[k] - c[k]), m * (1.0f / 256.0f) + std::exp2(-25.0f)) << c[k];
        EXPECT_EQ(back.w, 1.0f);
    }
    EXPECT_EQ(packRgb9e5(glm::vec3(0.0f)), 0u);
    EXPECT_EQ(rgb9e5Decode(packRgb9e5(glm::vec3(1.0f, 0.5f, 0.25f))), glm::vec4(1.0f, 0.5f, 0.25f, 1.0f));  // exact
    EXPECT_EQ(rgb9e5Decode(packRgb9e5(glm::vec3(1e9f, -1.0f, std::nanf("")))), glm::vec4(65408.0f, 0.0f, 0.0f, 1.0f));
}

/// A JSON scene with one sphere per material of `materials` and the named `textures`, loaded
/// from `dir` and packed as the kernel reads it.
struct Loaded {
    Scene scene;
    TexturePack pack;
};
Loaded load(const std::filesystem::path& dir, const std::string& textures, const std::string& materials) {
    std::string objects;
    int i = 0;
    for (std::size_t at = materials.find("\"m"); at != std::string::npos; at = materials.find("\"m", at + 1)) {
        const std::size_t end = materials.find('"', at + 1);
        objects += std::string(objects.empty() ? "" : ",") + R"({"type":"sphere","center":[0,0,)" + std::to_string(-5 - 3 * i++) +
                   R"(],"radius":1,"material":)" + materials.substr(at, end - at + 1) + "}";
        at = materials.find('}', materials.find('{', end));  // the material's own object ends there (no nesting is assumed)
        if (at == std::string::npos) break;
    }
    const std::string text = R"({"camera":{"lookfrom":[0,0,0],"lookat":[0,0,-1],"vfov":40,"width":8,"height":8},"textures":)" +
                             textures + R"(,"materials":)" + materials + R"(,"objects":[)" + objects + "]}";
    const std::filesystem::path file = dir / "scene.json";
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
    Loaded l;
    l.scene = loadSceneJson(file);
    l.pack = packTextures(l.scene, false);
    return l;
}

glm::vec3 eval(const Loaded& l, std::int32_t node, glm::vec3 p, glm::vec2 uv) {
    gSolidPack = &l.pack;
    return evalSolidTexture(std::uint32_t(node), p, uv);
}

TEST(SolidTexture, LoaderPacksEveryKindAsTheKernelReadsIt) {
    const auto dir = scratchDir("solid_texture_loader");
    Loaded l = load(dir,
                    R"({"check":{"type":"checker","scale":0.5,"even":[0.2,0.3,0.1],
                        "odd":{"type":"checker","scale":0.25,"even":[1,0,0],"odd":[0,0,1]}}})",
                    R"({"m0":{"type":"lambertian","albedo":"check"},
                        "m1":{"type":"metal","albedo":{"type":"noise","scale":4,"color":[0.5,1,1]}},
                        "m2":{"type":"lambertian","albedo":{"type":"turbulence","scale":2}},
                        "m3":{"type":"diffuse_light","emit":{"type":"marble","scale":3,"color":[4,4,4]}},
                        "m4":{"type":"lambertian","albedo":[0.1,0.2,0.3],"emit":"check"}})");
    const Scene& s = l.scene;
    ASSERT_EQ(s.materials.size(), 5u);
    const PerlinPack pp;
    // Checker: cells of 0.5, the odd ones a checker of 0.25.
    const std::int32_t c = s.materials[0].albedoTexture;
    ASSERT_GE(c, 0);
    EXPECT_EQ(eval(l, c, glm::vec3(0.1f, 0.1f, 0.1f), glm::vec2(0)), glm::vec3(0.2f, 0.3f, 0.1f));
    EXPECT_EQ(eval(l, c, glm::vec3(0.6f, 0.1f, 0.1f), glm::vec2(0)), glm::vec3(1, 0, 0));  // odd, then cell (2,0,0): even
    EXPECT_EQ(eval(l, c, glm::vec3(0.8f, 0.1f, 0.1f), glm::vec2(0)), glm::vec3(0, 0, 1));  // odd, then (3,0,0): odd
    // The same named texture read as an albedo and as an emission is two copies (two ranges checked).
    EXPECT_NE(s.materials[4].emitTexture, c);
    EXPECT_EQ(s.materials[4].emit, glm::vec3(1.0f, 0.3f, 1.0f)) << "an emission texture's bound: the larger side of each channel";
    EXPECT_TRUE(s.materials[4].emits());
    // Noise kinds, at points away from the origin (the scene's origin is the camera at 0 here).
    const glm::vec3 p(1.3f, -0.7f, 2.9f);
    EXPECT_EQ(eval(l, s.materials[1].albedoTexture, p, glm::vec2(0)),
              glm::vec3(0.5f, 1, 1) * (0.5f * (1.0f + pp.noise(4.0f * p))));
    EXPECT_EQ(eval(l, s.materials[2].albedoTexture, p, glm::vec2(0)), glm::vec3(pp.turb(2.0f * p)));
    EXPECT_EQ(eval(l, s.materials[3].emitTexture, p, glm::vec2(0)),
              glm::vec3(4.0f) * (0.5f * (1.0f + std::sin(3.0f * p.z + 10.0f * pp.turb(p)))));
    EXPECT_EQ(s.materials[3].emit, glm::vec3(4.0f));
    // The kernel's origin texel holds the scene's origin.
    EXPECT_EQ(l.pack.info[l.pack.info[0].w], glm::uvec4(0u, 0u, 0u, 1u + STEX_NODE_TEXELS * s.solidTextures.size()));
}

TEST(SolidTexture, ImageTexturesUseTheBooksUvAndDecodeSrgbOrHdr) {
    const auto dir = scratchDir("solid_texture_images");
    // A 4x2 PNG (through the writer's sRGB encoding) and a 3x1 PFM of linear values above 1.
    Image ldr(4, 2);
    for (std::size_t i = 0; i < ldr.rgb.size(); ++i) ldr.rgb[i] = float(i % 7) / 7.0f;
    writeImage(ldr, dir / "ldr.png");
    Image hdr(3, 1);
    hdr.rgb = {0.5f, 1.0f, 2.0f, 10.0f, 20.0f, 40.0f, 100.0f, 0.0f, 3.0f};
    writeImage(hdr, dir / "hdr.pfm");
    Loaded l = load(dir, "{}",
                    R"({"m0":{"type":"lambertian","albedo":{"type":"image","file":"ldr.png","filter":"nearest"}},
                        "m1":{"type":"diffuse_light","emit":{"type":"image","file":"hdr.pfm","filter":"nearest","color":[2,2,2]}}})");
    const Scene& s = l.scene;
    ASSERT_EQ(s.images.size(), 2u);
    // What the PNG holds, decoded as the loader decodes it.
    Rgba8Image png;
    const std::vector<unsigned char> bytes = readInputBytes(dir / "ldr.png");
    ASSERT_EQ(decodeLdrImage(bytes, 64, png), "");
    auto texel = [&](int x, int y) {
        const std::size_t at = 4 * (std::size_t(y) * 4 + std::size_t(x));
        const std::uint32_t packed = std::uint32_t(png.rgba[at]) | std::uint32_t(png.rgba[at + 1]) << 8 |
                                     std::uint32_t(png.rgba[at + 2]) << 16 | std::uint32_t(png.rgba[at + 3]) << 24;
        return glm::vec3(texDecode(packed, true));
    };
    // The book's UV: v up, so v = 0.75 is the top row, v = 0.25 the bottom one.
    EXPECT_EQ(eval(l, s.materials[0].albedoTexture, glm::vec3(0), glm::vec2(0.1f, 0.75f)), texel(0, 0));
    EXPECT_EQ(eval(l, s.materials[0].albedoTexture, glm::vec3(0), glm::vec2(0.9f, 0.25f)), texel(3, 1));
    EXPECT_EQ(eval(l, s.materials[0].albedoTexture, glm::vec3(0), glm::vec2(0.6f, 0.2f)), texel(2, 1));
    // The PFM: linear, through RGB9E5 (9 bits of the largest channel), times the colour.
    const std::int32_t e = s.materials[1].emitTexture;
    for (int x = 0; x < 3; ++x) {
        const glm::vec3 got = eval(l, e, glm::vec3(0), glm::vec2((float(x) + 0.5f) / 3.0f, 0.5f));
        const glm::vec3 want = 2.0f * glm::vec3(hdr.rgb[3 * x], hdr.rgb[3 * x + 1], hdr.rgb[3 * x + 2]);
        const float m = std::max({want.x, want.y, want.z});
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], m / 256.0f) << x << " " << k;
    }
    // Its bound, for the pick of lights by power: the largest texel per channel, times the colour.
    EXPECT_NEAR(s.materials[1].emit.x, 200.0f, 1.0f);
    EXPECT_NEAR(s.materials[1].emit.y, 40.0f, 0.2f);
    EXPECT_NEAR(s.materials[1].emit.z, 80.0f, 0.4f);
}

}  // namespace
}  // namespace vkp::test
