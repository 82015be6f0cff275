// shared/texture_sample.h, the C++ build of the texture lookups the kernel runs: sRGB decoding,
// wrap modes, bilinear weights, KHR_texture_transform (against the loader's TextureRef::transform).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "scene/scene.h"

#include "render/texture_sample_host.h"

namespace {
std::vector<std::uint32_t> gTexels;  // the "texel buffer" texSample reads in these tests
[[maybe_unused]] const bool kBound = (vkp::gHostTexels = &gTexels, true);  // the host build reads it (texture_sample_host.h)
}  // namespace

namespace vkp::gpu {
namespace {

uint rgba(uint r, uint g, uint b, uint a) { return r | (g << 8u) | (b << 16u) | (a << 24u); }

// A 2x2 image whose four texels differ in R: (0,0) = 0, (1,0) = 60, (0,1) = 120, (1,1) = 240
// (x right, y down); G, B, A constant.
uvec4 twoByTwo(uint wrapS, uint wrapT, uint extra = 0u) {
    gTexels = {rgba(0, 10, 20, 255), rgba(60, 10, 20, 255), rgba(120, 10, 20, 255), rgba(240, 10, 20, 255)};
    return uvec4(0u, 2u, 2u, wrapS | (wrapT << 2u) | extra);
}
float r255(vec4 c) { return c.x * 255.0f; }

TEST(TextureSample, SrgbDecodeMatchesTheStandard) {
    EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_NEAR(srgbToLinear(1.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.214041140f, 1e-6f);
    EXPECT_NEAR(srgbToLinear(0.04045f), 0.0031308f, 1e-7f);  // the two pieces meet here
    EXPECT_NEAR(srgbToLinear(0.04046f), 0.04046f / 12.92f, 1e-7f);
    const vec4 c = texDecode(rgba(255, 128, 0, 128), true);
    EXPECT_NEAR(c.x, 1.0f, 1e-6f);
    EXPECT_NEAR(c.y, 0.215860500f, 1e-6f);  // 128/255 decoded
    EXPECT_EQ(c.z, 0.0f);
    EXPECT_NEAR(c.w, 128.0f / 255.0f, 1e-7f);  // alpha stays linear
    const vec4 d = texDecode(rgba(255, 128, 0, 128), false);
    EXPECT_NEAR(d.y, 128.0f / 255.0f, 1e-7f);
}

TEST(TextureSample, WrapModesMapEveryIndexIntoTheImage) {
    const int n = 4;
    const int repeat[] = {2, 3, 0, 1, 2, 3, 0, 1, 2};  // i = -6 .. 2
    for (int i = -6; i <= 2; ++i) EXPECT_EQ(texWrap(i, n, TEXF_WRAP_REPEAT), repeat[i + 6]) << i;
    EXPECT_EQ(texWrap(-1, n, TEXF_WRAP_CLAMP), 0);
    EXPECT_EQ(texWrap(7, n, TEXF_WRAP_CLAMP), 3);
    EXPECT_EQ(texWrap(2, n, TEXF_WRAP_CLAMP), 2);
    // Mirrored: ... 1 0 | 0 1 2 3 | 3 2 1 0 | 0 1 ...
    const int mirror[] = {1, 0, 0, 1, 2, 3, 3, 2, 1, 0, 0, 1};  // i = -2 .. 9
    for (int i = -2; i <= 9; ++i) EXPECT_EQ(texWrap(i, n, TEXF_WRAP_MIRROR), mirror[i + 2]) << i;
    EXPECT_EQ(texWrap(-5, n, TEXF_WRAP_MIRROR), 3);
    EXPECT_EQ(texReduce(3.25f, TEXF_WRAP_REPEAT), 0.25f);
    EXPECT_EQ(texReduce(-0.75f, TEXF_WRAP_REPEAT), 0.25f);
    EXPECT_EQ(texReduce(3.25f, TEXF_WRAP_MIRROR), 1.25f);
    EXPECT_EQ(texReduce(-1e30f, TEXF_WRAP_CLAMP), -1.0f);
    EXPECT_EQ(texReduce(std::nanf(""), TEXF_WRAP_REPEAT), 0.0f);
    const float tiny = texReduce(-1e-9f, TEXF_WRAP_REPEAT);
    EXPECT_TRUE(tiny >= 0.0f && tiny < 1.0f);
}

TEST(TextureSample, BilinearHitsTexelCentresAndBlendsBetween) {
    const uvec4 h = twoByTwo(TEXF_WRAP_CLAMP, TEXF_WRAP_CLAMP);
    EXPECT_NEAR(r255(texSample(h, vec2(0.25f, 0.25f))), 0.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(h, vec2(0.75f, 0.25f))), 60.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(h, vec2(0.25f, 0.75f))), 120.0f, 1e-4f);  // v grows downwards
    EXPECT_NEAR(r255(texSample(h, vec2(0.75f, 0.75f))), 240.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(h, vec2(0.5f, 0.5f))), 105.0f, 1e-4f);    // mean of the four
    EXPECT_NEAR(r255(texSample(h, vec2(0.375f, 0.25f))), 15.0f, 1e-4f);  // a quarter of the way
    EXPECT_NEAR(texSample(h, vec2(0.6f, 0.3f)).y * 255.0f, 10.0f, 1e-4f);
}

TEST(TextureSample, EdgesFollowTheWrapMode) {
    // At u = 0 (the image's left edge, between texel -1 and texel 0), v at row 0's centre.
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_REPEAT, TEXF_WRAP_CLAMP), vec2(0.0f, 0.25f))), 30.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_CLAMP, TEXF_WRAP_CLAMP), vec2(0.0f, 0.25f))), 0.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_MIRROR, TEXF_WRAP_CLAMP), vec2(0.0f, 0.25f))), 0.0f, 1e-4f);
    // u = 1.25: repeat -> texel 0; mirrored -> texel 1 (the image flipped); clamp -> texel 1.
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_REPEAT, TEXF_WRAP_CLAMP), vec2(1.25f, 0.25f))), 0.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_MIRROR, TEXF_WRAP_CLAMP), vec2(1.25f, 0.25f))), 60.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_CLAMP, TEXF_WRAP_CLAMP), vec2(1.25f, 0.25f))), 60.0f, 1e-4f);
    // The same along v (wrap T in bits 2-3): v = -0.25 repeat -> row 1, mirror -> row 0.
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_CLAMP, TEXF_WRAP_REPEAT), vec2(0.25f, -0.25f))), 120.0f, 1e-4f);
    EXPECT_NEAR(r255(texSample(twoByTwo(TEXF_WRAP_CLAMP, TEXF_WRAP_MIRROR), vec2(0.25f, -0.25f))), 0.0f, 1e-4f);
}

TEST(TextureSample, NearestAndSrgbFlags) {
    const uvec4 h = twoByTwo(TEXF_WRAP_CLAMP, TEXF_WRAP_CLAMP, TEXF_NEAREST);
    EXPECT_EQ(r255(texSample(h, vec2(0.49f, 0.49f))), 0.0f);
    EXPECT_NEAR(r255(texSample(h, vec2(0.51f, 0.49f))), 60.0f, 1e-4f);
    // sRGB: filtered after decoding (the mean of decoded values, not the decoded mean).
    const uvec4 s = twoByTwo(TEXF_WRAP_CLAMP, TEXF_WRAP_CLAMP, TEXF_SRGB);
    const float expect = 0.25f * (srgbToLinear(0.0f) + srgbToLinear(60.0f / 255.0f) + srgbToLinear(120.0f / 255.0f) +
                                  srgbToLinear(240.0f / 255.0f));
    EXPECT_NEAR(texSample(s, vec2(0.5f, 0.5f)).x, expect, 1e-6f);
    EXPECT_GT(std::fabs(expect - srgbToLinear(105.0f / 255.0f)), 0.02f);
}

TEST(TextureSample, TransformMatchesTheLoadersTextureRef) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    for (int k = 0; k < 1000; ++k) {
        vkp::TextureRef r;
        r.offset = glm::vec2(u(rng), u(rng));
        r.rotation = u(rng);
        r.scale = glm::vec2(u(rng), u(rng));
        const vec4 rs(std::cos(r.rotation) * r.scale.x, std::sin(r.rotation) * r.scale.y,
                      -std::sin(r.rotation) * r.scale.x, std::cos(r.rotation) * r.scale.y);
        const vec2 uv(u(rng), u(rng));
        const vec2 a = texTransform(uv, rs, r.offset), b = r.transform(uv);
        EXPECT_NEAR(a.x, b.x, 1e-5f);
        EXPECT_NEAR(a.y, b.y, 1e-5f);
    }
    // A quarter turn: (1, 0) -> (0, -1) (R = [cos sin; -sin cos]), then the offset.
    const vec2 q = texTransform(vec2(1.0f, 0.0f), vec4(0.0f, 1.0f, -1.0f, 0.0f), vec2(0.5f, 0.5f));
    EXPECT_NEAR(q.x, 0.5f, 1e-7f);
    EXPECT_NEAR(q.y, -0.5f, 1e-7f);
}

}  // namespace
}  // namespace vkp::gpu
