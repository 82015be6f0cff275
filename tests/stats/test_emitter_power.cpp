// The light pick's power of triangles under an emissive texture (render/emitter_power.h, issue 6):
// each triangle's own UV footprint, with the sampler's wrap modes and KHR_texture_transform as the
// kernel applies them. Scenes built in memory; expected values worked out by hand from the texture.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "render/emitter_power.h"
#include "render/light_table.h"
#include "scene/scene.h"

namespace vkp {
namespace {

/// A w x h image whose texel (x, y) is white (255) where white(x, y), else black; alpha 255.
template <class F>
TextureImage image(std::uint32_t w, std::uint32_t h, F white) {
    TextureImage img;
    img.name = "test";
    img.width = w;
    img.height = h;
    img.rgba8.resize(std::size_t(4) * w * h, 0);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            std::uint8_t* p = &img.rgba8[4 * (std::size_t(y) * w + x)];
            const std::uint8_t v = white(x, y) ? 255 : 0;
            p[0] = p[1] = p[2] = v;
            p[3] = 255;
        }
    return img;
}

constexpr glm::vec3 kEmit{2.0f, 1.0f, 0.5f};
const double kLum = luminance709(2.0, 1.0, 0.5);

/// A glTF emitter (single-sided) with emissiveTexture `tex` (transform in ref) as material 0.
Material emitter(const TextureRef& ref) {
    Material m;
    m.name = "lamp";
    m.type = MaterialType::Pbr;
    m.emit = kEmit;
    m.pbr.emissiveTexture = ref;
    return m;
}

/// Appends a sampled triangle in the plane z = 0 with corners p[k] (x, y) and UVs uv[k].
void addTriangle(Scene& s, std::uint32_t material, const glm::vec2 p[3], const glm::vec2 uv[3]) {
    Shape t;
    t.type = ShapeType::Triangle;
    t.p0 = glm::vec3(p[0], 0.0f);
    t.p1 = glm::vec3(p[1], 0.0f);
    t.p2 = glm::vec3(p[2], 0.0f);
    t.material = material;
    t.sampled = true;
    t.attributes = std::uint32_t(s.triangleVertices.size());
    TriangleVertices tv;
    for (int k = 0; k < 3; ++k) {
        tv.v[k] = std::uint32_t(s.vertices.normal.size());
        s.vertices.normal.push_back(glm::vec3(0, 0, 1));
        s.vertices.uv.push_back(uv[k]);
    }
    tv.flags = TriangleVertices::kHasNormal | TriangleVertices::kHasUv;
    s.triangleVertices.push_back(tv);
    s.lights.push_back(std::uint32_t(s.shapes.size()));
    s.shapes.push_back(t);
}

/// Scene s gets image 0: 16 x 16, white where x < whiteColumns; texture 0 on it (clamped, sRGB,
/// nearest or bilinear filtering); and material 0, an emitter with emissiveTexture 0.
void addHalfWhiteEmitter(Scene& s, std::uint32_t whiteColumns, bool nearest) {
    s.images.push_back(image(16, 16, [whiteColumns](std::uint32_t x, std::uint32_t) { return x < whiteColumns; }));
    Texture tex;
    tex.image = 0;
    tex.wrapS = tex.wrapT = TextureWrap::ClampToEdge;
    tex.nearest = nearest;
    tex.srgb = true;
    s.textures.push_back(tex);
    TextureRef ref;
    ref.texture = 0;
    s.materials.push_back(emitter(ref));
}

/// A quad [x0, x1] x [0, 1] (world = UV) as two triangles.
void addQuad(Scene& s, std::uint32_t material, float x0, float x1) {
    const glm::vec2 a[3] = {{x0, 0}, {x1, 0}, {x1, 1}}, b[3] = {{x0, 0}, {x1, 1}, {x0, 1}};
    addTriangle(s, material, a, a);
    addTriangle(s, material, b, b);
}

// A 1 x 1 quad, UV = position, of 8 triangles in 4 vertical strips, under a 16 x 16 texture white
// in its left half (columns 0-7), black in the right, nearest filtering, clamp. Per triangle, the
// emission luminance is kLum x (1, 1, 1, 1, 0, 0, 0, 0) exactly. The third strip (u in [0.5,
// 0.75], texels 8-11) is black but its lookups' 2-texel safety margin reaches white texels 6-7: it
// gets the floor, 1 % of the image's mean (0.5 kLum). The fourth (texels 12-15, margin 10-15) is
// black with no white within reach: power 0, never picked.
TEST(EmitterPower, HalfBlackTexturePicksByTrianglePower) {
    Scene s;
    addHalfWhiteEmitter(s, 8, true);
    for (int i = 0; i < 4; ++i) addQuad(s, 0, 0.25f * float(i), 0.25f * float(i + 1));
    const double area = 0.125, floor = 0.01 * 0.5 * kLum;
    const double want[8] = {kLum, kLum, kLum, kLum, floor, floor, 0.0, 0.0};
    double sum = 0.0;
    for (double w : want) sum += w * area;
    std::vector<std::uint32_t> primOfShape(s.shapes.size());
    for (std::size_t i = 0; i < primOfShape.size(); ++i) primOfShape[i] = std::uint32_t(i);
    const std::vector<gpu::GpuLight> lights = packLights(s, primOfShape);
    for (std::uint32_t i = 0; i < 8; ++i) {
        EXPECT_NEAR(lightPower(s, i), want[i] * area, 1e-6 * kLum * area) << "triangle " << i;
        EXPECT_NEAR(lights[i].l0.y, want[i] * area / sum, 1e-6) << "triangle " << i;
    }
    EXPECT_EQ(lights[6].l0.y, 0.0f);  // black wherever the kernel can read: never picked
    EXPECT_EQ(lights[7].l0.y, 0.0f);
}

// Bilinear filtering reaches past a texel: the same texture (white for x < 8 in texel units),
// filtered bilinearly, on a quad x in [8.45, 16]: the lookup blends white texel 7 into
// [8.45, 8.5) (a sliver of 0.7 % of the quad), which no centroid of the subdivision hits (the first
// lies ~0.3 texel in), so the samples average to 0 although the emission is not 0 there. Every
// pick of such a triangle would be missing: the floor (1 % of the image mean 0.5) must apply. A
// quad at x in [12.8, 16] has no white texel within reach: exactly 0.
TEST(EmitterPower, BlackButWithinReachOfBrightTexelsIsNeverZero) {
    Scene s;
    addHalfWhiteEmitter(s, 8, false);
    addQuad(s, 0, 8.45f / 16.0f, 1.0f);
    addQuad(s, 0, 12.8f / 16.0f, 1.0f);
    const double floor = 0.01 * 0.5 * kLum;
    for (std::uint32_t i = 0; i < 2; ++i)
        EXPECT_NEAR(lightPower(s, i), floor * double(shapeArea(s.shapes[i])), 1e-6 * floor) << i;
    for (std::uint32_t i = 2; i < 4; ++i) EXPECT_EQ(lightPower(s, i), 0.0) << i;
}

// Wrap modes and KHR_texture_transform: a 16 x 16 texture white in columns 0-3 (u < 0.25), black
// elsewhere, nearest. Each triangle (corners (0,0), (0.2,0), (0,0.2) in UV, moved by a UV shift in
// the file) has a constant value over its transformed footprint (1 or 0, far from the edges); in
// 8 of the 11 cases the lookup with the transform or wrap mode left out has the opposite value.
TEST(EmitterPower, WrapModesAndTextureTransformMoveTheFootprint) {
    struct Case {
        const char* what;
        TextureWrap wrap;
        glm::vec2 uvShift;    // added to the file's UVs
        glm::vec2 offset;     // KHR_texture_transform
        float rotation;       // radians
        glm::vec2 scale;
        double want;          // mean of the texture over the footprint
    };
    const float halfPi = 1.5707963f;
    const Case cases[] = {
        {"repeat, u in [2.02, 2.22] -> [0.02, 0.22]: white", TextureWrap::Repeat, {2.02f, 0.1f}, {0, 0}, 0, {1, 1}, 1.0},
        {"mirror, u in [1.02, 1.22] -> [0.78, 0.98]: black (repeat: white)", TextureWrap::MirroredRepeat, {1.02f, 0.1f}, {0, 0}, 0, {1, 1}, 0.0},
        {"mirror, u in [-0.22, -0.02] -> [0.02, 0.22]: white (repeat: black)", TextureWrap::MirroredRepeat, {-0.22f, 0.1f}, {0, 0}, 0, {1, 1}, 1.0},
        {"clamp, u in [-3, -2.8] -> texel 0: white", TextureWrap::ClampToEdge, {-3.0f, 0.1f}, {0, 0}, 0, {1, 1}, 1.0},
        {"clamp, u in [1.5, 1.7] -> texel 15: black", TextureWrap::ClampToEdge, {1.5f, 0.1f}, {0, 0}, 0, {1, 1}, 0.0},
        {"offset -0.5: u in [0.52, 0.72] -> [0.02, 0.22]: white", TextureWrap::ClampToEdge, {0.52f, 0.3f}, {-0.5f, 0}, 0, {1, 1}, 1.0},
        {"offset +0.5: u in [0.02, 0.22] -> [0.52, 0.72]: black", TextureWrap::ClampToEdge, {0.02f, 0.3f}, {0.5f, 0}, 0, {1, 1}, 0.0},
        {"rotation pi/2: u' = v in [0.02, 0.22]: white, though u in [0.6, 0.8]", TextureWrap::Repeat, {0.6f, 0.02f}, {0, 0}, halfPi, {1, 1}, 1.0},
        {"rotation pi/2: u' = v in [0.6, 0.8]: black, though u in [0.02, 0.22]", TextureWrap::Repeat, {0.02f, 0.6f}, {0, 0}, halfPi, {1, 1}, 0.0},
        {"scale 0.25: u in [1.2, 1.4] -> [0.3, 0.35]: black", TextureWrap::ClampToEdge, {1.2f, 0.1f}, {0, 0}, 0, {0.25f, 0.25f}, 0.0},
        {"scale 0.1: u in [1.2, 1.4] -> [0.12, 0.14]: white", TextureWrap::ClampToEdge, {1.2f, 0.1f}, {0, 0}, 0, {0.1f, 0.1f}, 1.0},
    };
    Scene s;
    s.images.push_back(image(16, 16, [](std::uint32_t x, std::uint32_t) { return x < 4; }));
    for (const Case& c : cases) {
        Texture tex;
        tex.image = 0;
        tex.wrapS = tex.wrapT = c.wrap;
        tex.nearest = true;
        tex.srgb = true;
        TextureRef ref;
        ref.texture = std::int32_t(s.textures.size());
        ref.offset = c.offset;
        ref.rotation = c.rotation;
        ref.scale = c.scale;
        s.textures.push_back(tex);
        const std::uint32_t mi = std::uint32_t(s.materials.size());
        s.materials.push_back(emitter(ref));
        const glm::vec2 p[3] = {{0, 0}, {0.2f, 0}, {0, 0.2f}};
        const glm::vec2 uv[3] = {p[0] + c.uvShift, p[1] + c.uvShift, p[2] + c.uvShift};
        addTriangle(s, mi, p, uv);
    }
    std::size_t i = 0;
    for (const Case& c : cases) {
        const double got = lightPower(s, std::uint32_t(i)) / (kLum * 0.02);
        // 0 may be the floor (1 % of the image mean 0.25) when white texels are within 2 texels.
        if (c.want == 0.0)
            EXPECT_LE(got, 0.01 * 0.25 * (1 + 1e-6)) << c.what;
        else
            EXPECT_NEAR(got, c.want, 1e-6) << c.what;
        ++i;
    }
}

// Half a footprint: corners (0,0), (0.5,0), (0,0.5) in UV under offset (0, 0) cover u in [0, 0.5],
// white for u < 0.25: 3/4 of the triangle's area (the part with u > 0.25 is a similar triangle of
// half the size). The footprint is 32 texels, subdivided 6-fold, whose lines include u = 0.25: the
// centroid average is exactly 3/4. With offset (0.25, 0) the white part is u' < 0.25, u < 0: none.
TEST(EmitterPower, PartlyBrightFootprintAveragesByArea) {
    Scene s;
    addHalfWhiteEmitter(s, 4, true);
    TextureRef ref;
    ref.texture = 0;
    ref.offset = glm::vec2(0.25f, 0.0f);
    s.materials.push_back(emitter(ref));
    const glm::vec2 p[3] = {{0, 0}, {0.5f, 0}, {0, 0.5f}};
    addTriangle(s, 0, p, p);
    addTriangle(s, 1, p, p);
    EXPECT_NEAR(lightPower(s, 0), 0.75 * kLum * 0.125, 1e-6 * kLum);
    EXPECT_LE(lightPower(s, 1), 0.01 * 0.25 * kLum * 0.125 * (1 + 1e-6));
}

// An untextured emitter and a textured material on a triangle without UVs: the factor alone (the
// kernel applies no texture there).
TEST(EmitterPower, NoUvMeansNoTexture) {
    Scene s;
    s.images.push_back(image(4, 4, [](std::uint32_t, std::uint32_t) { return false; }));
    Texture tex;
    tex.image = 0;
    s.textures.push_back(tex);
    TextureRef ref;
    ref.texture = 0;
    s.materials.push_back(emitter(ref));
    const glm::vec2 p[3] = {{0, 0}, {1, 0}, {0, 1}};
    addTriangle(s, 0, p, p);
    EXPECT_EQ(lightPower(s, 0), 0.0);  // black texture
    s.triangleVertices[0].flags = TriangleVertices::kHasNormal;
    EXPECT_NEAR(lightPower(s, 0), kLum * 0.5, 1e-6 * kLum);
}

}  // namespace
}  // namespace vkp
