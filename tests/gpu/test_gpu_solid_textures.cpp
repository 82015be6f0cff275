// Textures of JSON scenes on the device (shaders/shared/solid_texture.h, lib/solid_texture.glsl),
// label gpu:
//  1. The GLSL build against the C++ build, value by value, on one packed scene holding every kind
//     (nested checkers, noise, turbulence, marble, PNG images bilinear and nearest, an HDR image):
//     the device reads the uploaded Perlin table, the host the one it made (kernel
//     shaders/tests/solid_texture_test.comp), at 12,000 random points and UVs.
//  2. The path tracer applies them: a quad in the focal plane under a background of 1 reflects
//     exactly its albedo (light leaving a plane never returns to it; every sampler's weight is
//     albedo x 1), so a pixel whose footprint lies in one checker cell or one texel of a nearest
//     image is that colour; a pixel of a noise quad is the mean of the noise over its footprint.
//  3. Textured emitters: next-event estimation reads the emission at the point it samples on the
//     light (a checker on a quad light, marble on a sphere light): the `light`, `mixture` and `mis`
//     images agree with `bsdf`'s, which only sees emission where its rays hit.
//
// Statistics: z-tests with the standard error from the per-pixel sums; |z| <= 5 per pixel in 2
// (at most 256 pixels, false-failure probability 1.5e-4 in all, normal tails) and |z| <= 4.5 per
// pooled mean in 3 (9 tests, 6e-5 in all).
#include "solid_texture_host.h"  // first: the host build of shared/solid_texture.h

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <span>

#include "core/image_io.h"
#include "gpu_env.h"
#include "render_helpers.h"
#include "scene/scene.h"
#include "solid_texture_test.spv.h"
#include "test_paths.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp::test {
namespace {

/// Writes the images the scenes below read into dir: a 5x3 PNG and a 3x2 PFM.
void writeImages(const std::filesystem::path& dir) {
    Image ldr(5, 3);
    for (std::size_t i = 0; i < ldr.rgb.size(); ++i) ldr.rgb[i] = float((i * 37) % 11) / 10.0f;
    writeImage(ldr, dir / "ldr.png");
    Image hdr(3, 2);
    hdr.rgb = {0.5f, 1.0f, 2.0f, 10.0f, 20.0f, 40.0f, 100.0f, 0.0f, 3.0f, 0.25f, 0.125f, 7.0f, 1.0f, 1.0f, 1.0f, 0.0f, 9.0f, 0.0f};
    writeImage(hdr, dir / "hdr.pfm");
    Image big(3, 2);  // texels larger than a pixel of the quad test
    for (std::size_t i = 0; i < big.rgb.size(); ++i) big.rgb[i] = float((i * 5) % 7) / 6.0f;
    writeImage(big, dir / "big.png");
}

// ---- 1. GLSL against C++ ------------------------------------------------------------------------

TEST(GpuSolidTextures, GlslMatchesCppValueByValue) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_solid_textures_kernel");
    writeImages(dir);
    const Scene scene = loadSceneText(dir, R"({
      "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 40, "width": 8, "height": 8},
      "materials": {
        "a": {"type": "lambertian", "albedo": {"type": "checker", "scale": 0.7, "even": [0.2, 0.3, 0.1],
              "odd": {"type": "checker", "scale": 0.3, "even": {"type": "noise", "scale": 3}, "odd": [0.9, 0.1, 0.5]}}},
        "b": {"type": "lambertian", "albedo": {"type": "turbulence", "scale": 1.5, "color": [0.3, 0.6, 0.9]}},
        "c": {"type": "lambertian", "albedo": {"type": "marble", "scale": 4}},
        "d": {"type": "lambertian", "albedo": {"type": "image", "file": "ldr.png"}},
        "e": {"type": "lambertian", "albedo": {"type": "image", "file": "ldr.png", "filter": "nearest"}},
        "f": {"type": "diffuse_light", "emit": {"type": "image", "file": "hdr.pfm", "color": [2, 1, 0.5]}}},
      "objects": [{"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "a"},
                  {"type": "sphere", "center": [0, 0, -8], "radius": 1, "material": "b"},
                  {"type": "sphere", "center": [0, 0, -11], "radius": 1, "material": "c"},
                  {"type": "sphere", "center": [0, 0, -14], "radius": 1, "material": "d"},
                  {"type": "sphere", "center": [0, 0, -17], "radius": 1, "material": "e"},
                  {"type": "sphere", "center": [0, 0, -20], "radius": 1, "material": "f"}]})");
    const TexturePack pack = packTextures(scene, false);
    std::vector<std::uint32_t> nodes;
    for (const Material& m : scene.materials) nodes.push_back(std::uint32_t(m.albedoTexture >= 0 ? m.albedoTexture : m.emitTexture));

    std::mt19937 rng(29);
    std::uniform_real_distribution<float> pd(-20.0f, 20.0f), ud(-0.2f, 1.2f);
    std::vector<glm::vec4> items;
    const int perNode = 2000;
    for (std::size_t k = 0; k < nodes.size(); ++k)
        for (int i = 0; i < perNode; ++i) {
            items.emplace_back(pd(rng), pd(rng), pd(rng), float(nodes[k]));
            items.emplace_back(ud(rng), ud(rng), 0.0f, 0.0f);
        }
    const std::uint32_t count = std::uint32_t(items.size() / 2);

    ComputePipelineDesc d;
    d.spirv = std::span<const std::uint32_t>(kSolidTextureTestSpv);
    d.bindings = {vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eUniformTexelBuffer,
                  vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer};
    d.pushConstantBytes = sizeof(std::uint32_t);
    ComputePipeline pipe(dev, d);
    GpuBuffer info(dev, pack.info.size() * 16, vk::BufferUsageFlagBits::eUniformTexelBuffer);
    info.upload(pack.info.data(), pack.info.size() * 16);
    GpuBuffer texels(dev, pack.texels.size() * 4, vk::BufferUsageFlagBits::eUniformTexelBuffer);
    texels.upload(pack.texels.data(), pack.texels.size() * 4);
    const vk::raii::BufferView infoView = info.texelView(vk::Format::eR32G32B32A32Uint);
    const vk::raii::BufferView texelView = texels.texelView(vk::Format::eR32Uint);
    GpuBuffer in(dev, items.size() * 16, vk::BufferUsageFlagBits::eStorageBuffer);
    GpuBuffer out(dev, items.size() * 16, vk::BufferUsageFlagBits::eStorageBuffer);
    in.upload(items.data(), items.size() * 16);
    pipe.bindTexelView(0, *infoView);
    pipe.bindTexelView(1, *texelView);
    pipe.bindBuffer(2, in.buffer());
    pipe.bindBuffer(3, out.buffer());
    dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) { pipe.recordDispatch(cmd, (count + 63) / 64, 1, &count, sizeof count); });
    std::vector<glm::vec4> got(items.size());
    out.download(got.data(), got.size() * 16);
    dev.instance().throwIfValidationMessages("solid texture test kernel");

    gSolidPack = &pack;
    const std::uint32_t pt = pack.info[pack.info[0].w].w;
    double worstValue[6] = {0, 0, 0, 0, 0, 0}, worstNoise = 0, worstTurb = 0, worstUv = 0;
    int bad = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
        const glm::vec3 p(items[2 * i]);
        const glm::vec2 uv(items[2 * i + 1]);
        const std::uint32_t node = std::uint32_t(items[2 * i].w);
        const glm::vec3 want = gpu::evalSolidTexture(node, p, uv);
        const float n = gpu::perlinNoise(p, pt), t = gpu::perlinTurbulence(p, pt);
        const glm::vec2 su = gpu::sphereUv(glm::normalize(p));
        double err = 0;
        for (int c = 0; c < 3; ++c) err = std::max(err, double(std::abs(got[2 * i][c] - want[c])) / (1.0 + std::abs(want[c])));
        const std::size_t k = i / perNode;
        worstValue[k] = std::max(worstValue[k], err);
        worstNoise = std::max(worstNoise, double(std::abs(got[2 * i + 1].x - n)));
        worstTurb = std::max(worstTurb, double(std::abs(got[2 * i + 1].y - t)));
        // u near the seam (phi = 0 or 2 pi) may land on either side in either build.
        const double du = std::abs(got[2 * i + 1].z - su.x);
        worstUv = std::max({worstUv, std::min(du, std::abs(du - 1.0)), double(std::abs(got[2 * i + 1].w - su.y))});
        // Float rounding only: the builds differ by fused multiply-adds and the device's sin, acos
        // and atan (a few ulps); a wrong table, a wrong node or a wrong texel differs by far more.
        if ((err > 2e-5 || std::abs(got[2 * i + 1].x - n) > 1e-5 || std::abs(got[2 * i + 1].y - t) > 2e-5) && bad++ < 5)
            ADD_FAILURE() << "item " << i << " node " << node << " p " << p.x << "," << p.y << "," << p.z << " uv " << uv.x << ","
                          << uv.y << ": device " << got[2 * i].x << "," << got[2 * i].y << "," << got[2 * i].z << " host "
                          << want.x << "," << want.y << "," << want.z << "; noise " << got[2 * i + 1].x << " vs " << n;
    }
    std::printf("  %u items: worst relative difference per material %.2g %.2g %.2g %.2g %.2g %.2g; noise %.2g, turbulence %.2g, sphere UV %.2g\n",
                count, worstValue[0], worstValue[1], worstValue[2], worstValue[3], worstValue[4], worstValue[5], worstNoise,
                worstTurb, worstUv);
    // acos near the poles turns an ulp of difference in y into up to sqrt(2 ulp) / pi ~ 1e-4.
    EXPECT_LT(worstUv, 2e-4);
    EXPECT_EQ(bad, 0);
}

// ---- 2. In the path tracer ----------------------------------------------------------------------

TEST(GpuSolidTextures, AQuadUnderAUniformSkyShowsItsTexture) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_solid_textures_quads");
    writeImages(dir);
    // Three quads side by side in the plane z = -4.1 (the camera is at z = 4 of the file: the
    // kernel's points are the file's minus (0, 0, 4), which the textures must add back).
    const Scene scene = loadSceneText(dir, R"({
      "camera": {"lookfrom": [0, 0, 4], "lookat": [0, 0, -4], "vfov": 40, "width": 48, "height": 16},
      "render": {"background": [1, 1, 1], "max_depth": 8},
      "materials": {
        "check": {"type": "lambertian", "albedo": {"type": "checker", "scale": 1, "even": [0.2, 0.3, 0.1], "odd": [0.9, 0.8, 0.7]}},
        "image": {"type": "lambertian", "albedo": {"type": "image", "file": "big.png", "filter": "nearest"}},
        "noise": {"type": "lambertian", "albedo": {"type": "noise", "scale": 2}}},
      "objects": [{"type": "quad", "Q": [-8.4, -2.7, -4.1], "u": [5.4, 0, 0], "v": [0, 5.4, 0], "material": "check"},
                  {"type": "quad", "Q": [-2.7, -2.7, -4.1], "u": [5.4, 0, 0], "v": [0, 5.4, 0], "material": "image"},
                  {"type": "quad", "Q": [3.0, -2.7, -4.1], "u": [5.4, 0, 0], "v": [0, 5.4, 0], "material": "noise"}]})");
    const gpu::GpuFrame frame = packGpuArrays(scene, buildSceneBvh(scene), RenderOptions{}).frame;
    const TexturePack pack = packTextures(scene, false);
    gSolidPack = &pack;
    const glm::vec3 origin(scene.origin);
    const double z = -4.1 - 4.0;  // the quads' plane in the kernel's (camera-relative) coordinates
    int exact = 0, averaged = 0, worstZ = 0;
    double worst = 0;
    for (Sampler sampler : {Sampler::Bsdf, Sampler::Mis}) {
        const PixelSums s = renderSums(dev, scene, sampler, 256, "textured quads");
        const Image mean = s.mean(), var = s.varianceOfMean();
        for (std::uint32_t py = 0; py < 16; ++py)
            for (std::uint32_t px = 0; px < 48; ++px) {
                // The quad under the pixel's whole footprint, and its value there on the host.
                int quad = -1;
                glm::vec3 corners[4];
                glm::vec2 uvs[4];
                bool inside = true;
                for (int c = 0; c < 4; ++c) {
                    const glm::dvec3 w = rayPlanePoint(frame, px - 0.5 + (c & 1), py - 0.5 + (c >> 1), z);
                    const int q = int(std::floor((w.x + 8.4) / 5.7));
                    const double a = (w.x - (-8.4 + 5.7 * q)) / 5.4, b = (w.y + 2.7) / 5.4;
                    if (q < 0 || q > 2 || a < 0 || a > 1 || b < 0 || b > 1 || (quad >= 0 && q != quad)) inside = false;
                    quad = q;
                    corners[c] = glm::vec3(w) + origin;
                    uvs[c] = glm::vec2(float(a), float(b));
                }
                if (!inside) continue;
                const std::uint32_t node = std::uint32_t(scene.materials[std::size_t(quad)].albedoTexture);
                const std::size_t at = 3 * (std::size_t(py) * 48 + px);
                if (quad < 2) {
                    // Checker cells and nearest texels span several pixels: a pixel whose footprint
                    // (9 x 9 points, edges included) sees one value lies in one cell or texel.
                    const glm::vec3 v = gpu::evalSolidTexture(node, corners[0], uvs[0]);
                    bool uniform = true;
                    for (int j = 0; j <= 8 && uniform; ++j)
                        for (int i = 0; i <= 8 && uniform; ++i) {
                            const glm::dvec3 w = rayPlanePoint(frame, px - 0.5 + i / 8.0, py - 0.5 + j / 8.0, z);
                            const double a = (w.x - (-8.4 + 5.7 * quad)) / 5.4, b = (w.y + 2.7) / 5.4;
                            uniform = gpu::evalSolidTexture(node, glm::vec3(w) + origin, glm::vec2(float(a), float(b))) == v;
                        }
                    if (!uniform) continue;
                    for (int c = 0; c < 3; ++c) {
                        const double e = std::abs(mean.rgb[at + c] - v[c]);
                        worst = std::max(worst, e);
                        EXPECT_LE(e, 2e-6 * (1.0 + v[c])) << samplerName(sampler) << " pixel " << px << "," << py << " quad " << quad
                                                          << ": " << mean.rgb[at + c] << " vs " << v[c] << " uv " << uvs[0].x << ","
                                                          << uvs[0].y << " .. " << uvs[3].x << "," << uvs[3].y;
                    }
                    ++exact;
                } else {
                    // Noise: the mean over the footprint (32 x 32 midpoints; the noise is smooth
                    // at this scale, so the midpoint rule's error is far below the noise of 256 spp).
                    glm::dvec3 sum(0.0);
                    for (int j = 0; j < 32; ++j)
                        for (int i = 0; i < 32; ++i) {
                            const glm::dvec3 w = rayPlanePoint(frame, px - 0.5 + (i + 0.5) / 32.0, py - 0.5 + (j + 0.5) / 32.0, z);
                            const double a = (w.x - 3.0) / 5.4, b = (w.y + 2.7) / 5.4;
                            sum += glm::dvec3(gpu::evalSolidTexture(node, glm::vec3(w) + origin, glm::vec2(float(a), float(b))));
                        }
                    const glm::dvec3 want = sum / 1024.0;
                    for (int c = 0; c < 3; ++c) {
                        const double zc = (mean.rgb[at + c] - want[c]) / std::sqrt(var.rgb[at + c] + 1e-14);
                        worstZ = std::max(worstZ, int(std::ceil(std::abs(zc))));
                        EXPECT_LE(std::abs(zc), 5.0) << samplerName(sampler) << " pixel " << px << "," << py << " channel " << c
                                                     << ": " << mean.rgb[at + c] << " vs " << want[c];
                    }
                    ++averaged;
                }
            }
    }
    std::printf("  %d pixels on one cell or texel (worst difference %.2g), %d noise pixels (|z| <= %d)\n", exact, worst, averaged,
                worstZ);
    EXPECT_GT(exact, 250);
    EXPECT_GT(averaged, 250);
}

// ---- 3. Textured emitters and next-event estimation ---------------------------------------------

TEST(GpuSolidTextures, NextEventEstimationReadsTheEmissionWhereItSamples) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dir = scratchDir("gpu_solid_textures_lights");
    const Scene scene = loadSceneText(dir, R"({
      "camera": {"lookfrom": [0, 3, 6], "lookat": [0, 0, 0], "vfov": 50, "width": 16, "height": 16},
      "render": {"background": [0, 0, 0], "max_depth": 6},
      "materials": {
        "floor": {"type": "lambertian", "albedo": [0.7, 0.7, 0.7]},
        "panel": {"type": "diffuse_light", "emit": {"type": "checker", "scale": 0.5, "even": [6, 1, 0.2], "odd": [0.1, 3, 8]}},
        "ball": {"type": "diffuse_light", "emit": {"type": "marble", "scale": 6, "color": [4, 4, 4]}}},
      "objects": [{"type": "quad", "Q": [-3, 0, 3], "u": [6, 0, 0], "v": [0, 0, -6], "material": "floor"},
                  {"type": "quad", "Q": [-1.5, 2.5, -1], "u": [2.2, 0, 0], "v": [0, -0.3, 1.6], "material": "panel"},
                  {"type": "sphere", "center": [1.6, 0.6, 0.4], "radius": 0.35, "material": "ball"}]})");
    expectSamplersAgreeWithBsdf(dev, scene, 2048, 512, "textured lights", 4.5, 1e-2);
}

}  // namespace
}  // namespace vkp::test
