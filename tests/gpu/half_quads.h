// Helpers of the device tests that compare a textured glTF material with the same material
// without the texture (test_gpu_specular_textures.cpp): a file of n quads of size 2 in the plane
// z = 0 facing +z, quad i at x in [2.5 i, 2.5 i + 2], y in [0, 2], UV (0, 0) at its top left and
// (1, 1) at its bottom right (tools/gen_gltf_scenes.py), under a uniform sky of radiance 1, seen
// straight on by a camera 20 units away with 80 x 80 pixels per 2.5 x 2.5 units.
//
// The comparison is a z-test of the difference of two independent renders (different seeds) over
// the same pixels, so the viewing directions (which vary over the image) are the same in both.
#pragma once
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gpu_scene.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"
#include "file_frame.h"

namespace vkp::test {

/// The material of `s` called `name` (the reference scenes replace a texture by a constant in it).
inline Material& namedMaterial(Scene& s, const std::string& name) {
    for (Material& m : s.materials)
        if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
}

/// The scene: gltf file `file` of scenes/gltf/ with `quads` quads, rendered with `seed`.
inline Scene halfQuadsScene(const std::string& file, int quads, std::uint32_t seed) {
    const double cx = (2.5 * quads - 0.5) / 2.0;
    const std::string json = R"({"camera": {"lookfrom": [)" + std::to_string(cx) + R"(, 1, 20], "lookat": [)" +
                             std::to_string(cx) + R"(, 1, 0], "vup": [0, 1, 0], "vfov": 7.152669, "width": )" +
                             std::to_string(80 * quads) + R"(, "height": 80},
      "render": {"max_depth": 50, "background": [1, 1, 1]},
      "materials": {"unused": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "gltf", "file": ")" + file + R"("}]})";
    Scene scene = parseSceneJson(json, scenesDir() / "gltf" / "half-quads-test.json");
    scene.render.seed = seed;
    return scene;
}

/// Which part of a quad: its left half (u < 1/2), its right half, or all of it.
enum class Half { Left, Right, Whole };

/// The pixels whose footprint (corners pushed out by 0.02 pixel) lies on quad q, in `half`.
inline std::vector<Pixel> halfQuadPixels(const Scene& scene, int q, Half half) {
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    auto plane = [&](double px, double py) {  // where the ray through image point (px, py) meets z = 0
        const glm::dvec3 o(f.origin), t = glm::dvec3(f.pixel00) + px * glm::dvec3(f.pixelDu) + py * glm::dvec3(f.pixelDv);
        const double s = o.z / (o.z - t.z);
        return glm::dvec2(o + s * (t - o));
    };
    const double x0 = 2.5 * q;
    std::vector<Pixel> out;
    for (std::uint32_t y = 0; y < scene.camera.height; ++y)
        for (std::uint32_t x = 0; x < scene.camera.width; ++x) {
            bool ok = true;
            for (double sx : {-0.52, 0.52})
                for (double sy : {-0.52, 0.52}) {
                    const glm::dvec2 p = plane(x + sx, y + sy);
                    const double u = (p.x - x0) / 2.0;
                    ok = ok && u > 0.0 && u < 1.0 && p.y > 0.0 && p.y < 2.0;
                    if (half == Half::Left) ok = ok && u < 0.5;
                    if (half == Half::Right) ok = ok && u > 0.5;
                }
            if (ok) out.push_back({x, y});
        }
    return out;
}

/// What the comparison below asks of its second render: lit and not constant, as two renders of
/// nothing would agree, or (when the call says why that is right) only not all black.
enum class SecondRender { Varied, MayBeOneColour };

/// z-tests (one per channel, against zBudget()) that the average of `pixels` is the same in two
/// independent renders a and b: the difference of the averages has variance var_a + var_b. Image a
/// must be lit and not constant (litAndNotConstant), b too unless `second` says otherwise
/// (named "<what> [first render]" and "[second render]" in the failures).
inline void expectSameWithinNoise(const PixelStats& a, const PixelStats& b, const std::vector<Pixel>& pixels,
                                  const std::string& what, SecondRender second = SecondRender::Varied) {
    EXPECT_TRUE(litAndNotConstant(a.mean, what + " [first render]"));
    if (second == SecondRender::Varied)
        EXPECT_TRUE(litAndNotConstant(b.mean, what + " [second render]"));
    else
        EXPECT_TRUE(notAllBlack(b.mean, what + " [second render]"));
    ASSERT_GT(pixels.size(), 500u) << what;
    for (int c = 0; c < 3; ++c) {
        const Estimate ea = average(a, pixels, c), eb = average(b, pixels, c);
        EXPECT_TRUE(withinNoise(difference(ea, eb), 0.0, what + " (" + std::to_string(ea.mean) + " vs " + std::to_string(eb.mean) + "), " + kChannel[c],
                                true));
    }
}

}  // namespace vkp::test
