// Light-table build time for a mesh of ~1M emissive triangles under one 1024 x 1024 sRGB emissive
// texture (bilinear, repeat, a KHR_texture_transform), mostly black with bright squares (issue 6:
// "a mesh with a million emissive triangles must still work"). Label bench: prints the time of
// packLights (the per-triangle texture averages + the alias table); asserts only that the pick
// probabilities sum to 1 and that black triangles exist and get 0.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "render/light_table.h"
#include "scene/scene.h"

namespace vkp {
namespace {

TEST(BenchEmitterPower, OneMillionTexturedEmissiveTriangles) {
    const std::uint32_t n = 708;  // n x n quads, 2 triangles each: 1,002,528 triangles
    const std::uint32_t size = 1024;
    Scene s;
    TextureImage img;
    img.name = "blobs";
    img.width = img.height = size;
    img.rgba8.assign(std::size_t(4) * size * size, 0);
    for (std::uint32_t y = 0; y < size; ++y)
        for (std::uint32_t x = 0; x < size; ++x) {
            std::uint8_t* p = &img.rgba8[4 * (std::size_t(y) * size + x)];
            const bool bright = (x / 64 + y / 64) % 5 == 0 && x % 64 < 24 && y % 64 < 24;  // ~4 % of texels
            p[0] = bright ? 255 : 0;
            p[1] = bright ? 200 : 0;
            p[2] = bright ? 120 : 0;
            p[3] = 255;
        }
    s.images.push_back(img);
    Texture tex;
    tex.srgb = true;
    s.textures.push_back(tex);
    Material m;
    m.type = MaterialType::Pbr;
    m.emit = glm::vec3(4.0f);
    m.pbr.emissiveTexture.texture = 0;
    m.pbr.emissiveTexture.rotation = 0.3f;
    m.pbr.emissiveTexture.scale = glm::vec2(1.5f, 1.2f);
    s.materials.push_back(m);
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i) {
            s.vertices.normal.push_back(glm::vec3(0, 0, 1));
            s.vertices.uv.push_back(glm::vec2(float(i) / n, float(j) / n));
        }
    auto corner = [&](std::uint32_t i, std::uint32_t j) { return glm::vec3(float(i) / n, float(j) / n, 0.0f); };
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            for (const glm::uvec3 t : {glm::uvec3(a, b, c), glm::uvec3(a, c, d)}) {
                Shape sh;
                sh.type = ShapeType::Triangle;
                sh.p0 = corner(t.x % (n + 1), t.x / (n + 1));
                sh.p1 = corner(t.y % (n + 1), t.y / (n + 1));
                sh.p2 = corner(t.z % (n + 1), t.z / (n + 1));
                sh.sampled = true;
                sh.attributes = std::uint32_t(s.triangleVertices.size());
                s.triangleVertices.push_back({{t.x, t.y, t.z}, TriangleVertices::kHasNormal | TriangleVertices::kHasUv});
                s.lights.push_back(std::uint32_t(s.shapes.size()));
                s.shapes.push_back(sh);
            }
        }
    std::vector<std::uint32_t> primOfShape(s.shapes.size());
    for (std::size_t i = 0; i < primOfShape.size(); ++i) primOfShape[i] = std::uint32_t(i);
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<gpu::GpuLight> lights = packLights(s, primOfShape);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    double sum = 0.0;
    std::size_t zero = 0;
    for (const gpu::GpuLight& l : lights) {
        sum += l.l0.y;
        zero += l.l0.y == 0.0f;
    }
    EXPECT_NEAR(sum, 1.0, 1e-3);
    EXPECT_GT(zero, lights.size() / 2);
    std::printf("  %zu emissive triangles, 1024 x 1024 texture: packLights %.3f s; %zu (%.1f %%) never picked\n",
                lights.size(), seconds, zero, 100.0 * double(zero) / double(lights.size()));
}

}  // namespace
}  // namespace vkp
