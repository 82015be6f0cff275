// The one place where the GPU and stress tests build a Renderer (so that a change of the Renderer
// constructor touches only this file): a scene, its BVH and the renderer over them, kept together;
// and renderSums, a whole render's per-pixel sums with the checks every render must pass; the pooled
// mean of a render and where a camera ray meets a plane, for tests that compare with closed forms.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>

#include "bvh/flatten.h"
#include "bvh/two_level.h"
#include "render/gpu_arrays.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "vk/device.h"

namespace vkp::test {

/// A renderer with its scene, BVH and packed arrays kept alive beside it.
struct TestRender {
    Scene scene;
    FlatBvh bvh;
    GpuArrays arrays;
    std::unique_ptr<Renderer> renderer;
};

/// The pipeline of the CLI (render/render_job.h): the BVH of `scene` (two-level when the scene has
/// instances), the packed arrays (packGpuArrays) and the renderer with options `o`. Throws what the
/// Renderer throws (DeviceError beyond the device's limits). `limits` (optional): pretend the
/// device has these (to force bands of rows on a small image). `bvhOptions`: how the BVH is built
/// (RenderJob::bvh).
inline TestRender makeRender(VulkanDevice& dev, Scene scene, const RenderOptions& o, const DeviceLimits* limits = nullptr,
                             const BvhBuildOptions& bvhOptions = {}) {
    TestRender r;
    r.scene = std::move(scene);
    r.bvh = buildSceneBvh(r.scene, bvhOptions);
    r.arrays = packGpuArrays(r.scene, r.bvh, o);
    r.renderer = std::make_unique<Renderer>(dev, r.arrays, o, limits);
    return r;
}

/// makeRender with `sampler` and `samplesPerDispatch` (RenderOptions), every other option default.
inline TestRender makeRender(VulkanDevice& dev, Scene scene, Sampler sampler, std::uint32_t samplesPerDispatch = 4) {
    RenderOptions o;
    o.sampler = sampler;
    o.samplesPerDispatch = samplesPerDispatch;
    return makeRender(dev, std::move(scene), o);
}

/// Loads the JSON scene `file`, sets the image size to width x height (the scene's other settings
/// kept) and makes its renderer with `sampler`, `samplesPerDispatch` samples per dispatch.
inline TestRender makeRender(VulkanDevice& dev, const std::filesystem::path& file, std::uint32_t width,
                             std::uint32_t height, Sampler sampler, std::uint32_t samplesPerDispatch = 1) {
    Scene scene = loadSceneJson(file);
    scene.camera.width = width;
    scene.camera.height = height;
    return makeRender(dev, std::move(scene), sampler, samplesPerDispatch);
}

/// Renders `scene` with options `o` for spp samples and returns the sums; expects no non-finite
/// sample and no path cut by the loop guard (`what` names the render in the messages).
inline PixelSums renderSums(VulkanDevice& dev, const Scene& scene, const RenderOptions& o, std::uint32_t spp,
                            const std::string& what) {
    TestRender r = makeRender(dev, scene, o);
    r.renderer->addSamples(spp);
    const RenderCounters c = r.renderer->counters();
    EXPECT_EQ(c.nonfinite, 0u) << what << " " << samplerName(o.sampler);
    EXPECT_EQ(c.loopGuard, 0u) << what << " " << samplerName(o.sampler);
    return r.renderer->readSums();
}

/// renderSums with `sampler` and 4 samples per dispatch.
inline PixelSums renderSums(VulkanDevice& dev, const Scene& scene, Sampler sampler, std::uint32_t spp,
                            const std::string& what) {
    RenderOptions o;
    o.sampler = sampler;
    o.samplesPerDispatch = 4;
    return renderSums(dev, scene, o, spp, what);
}

/// Pooled mean and its standard error of channel c over every pixel of `s` (each pixel's samples
/// are one group: the standard error comes from the per-pixel sums of squares).
inline void pooledMean(const PixelSums& s, int c, double& mean, double& stderrOfMean) {
    double sum = 0, sq = 0, n = 0;
    for (std::size_t i = 0; i < s.sum.size() / 4; ++i) {
        sum += s.sum[4 * i + c];
        sq += s.sumSq[4 * i + c];
        n += s.sum[4 * i + 3];
    }
    mean = sum / n;
    const double var = std::max(0.0, (sq / n - mean * mean) * n / (n - 1));
    stderrOfMean = std::sqrt(var / n);
}

/// Renders `scene` under every sampler, `bsdf` with bsdfSpp samples and the others with
/// otherSpp, and expects the pooled means of `light`, `mixture` and `mis` to agree with `bsdf`'s
/// in every channel: |z| <= maxZ, z from the sums' standard errors (9 z-tests). Fails at once if
/// `bsdf`'s mean of a channel is not above minMean (a black image agrees with anything).
/// The test that calls it states the false-failure probability of maxZ.
inline void expectSamplersAgreeWithBsdf(VulkanDevice& dev, const Scene& scene, std::uint32_t bsdfSpp,
                                        std::uint32_t otherSpp, const std::string& what, double maxZ, double minMean) {
    double mean[4][3], se[4][3];
    for (std::size_t k = 0; k < 4; ++k) {
        const Sampler sampler = kAllSamplers[k];
        const PixelSums s = renderSums(dev, scene, sampler, sampler == Sampler::Bsdf ? bsdfSpp : otherSpp, what);
        for (int c = 0; c < 3; ++c) pooledMean(s, c, mean[k][c], se[k][c]);
    }
    static_assert(kAllSamplers[0] == Sampler::Bsdf, "bsdf first");
    for (int c = 0; c < 3; ++c) {
        ASSERT_GT(mean[0][c], minMean) << what << ": channel " << c << " is lit";
        for (std::size_t j = 1; j < 4; ++j) {
            const double z = (mean[j][c] - mean[0][c]) / std::hypot(se[j][c], se[0][c]);
            std::printf("  %s, channel %d: %-7s %.5f vs bsdf %.5f (z %.2f)\n", what.c_str(), c, samplerName(kAllSamplers[j]),
                        mean[j][c], mean[0][c], z);
            EXPECT_LE(std::abs(z), maxZ) << what << ": " << samplerName(kAllSamplers[j]) << " channel " << c;
        }
    }
}

/// Writes `text` to dir/scene.json and loads it (its relative file references resolve in `dir`).
inline Scene loadSceneText(const std::filesystem::path& dir, const std::string& text) {
    const std::filesystem::path file = dir / "scene.json";
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
    return loadSceneJson(file);
}

/// Where the camera ray through image point (px, py) of `f` meets the plane z = zPlane; pixel
/// units, the centre of pixel (i, j) at (i, j) (GpuFrame::pixel00), so pixel (i, j) spans
/// [i - 0.5, i + 0.5] x [j - 0.5, j + 0.5].
inline glm::dvec3 rayPlanePoint(const gpu::GpuFrame& f, double px, double py, double zPlane) {
    const glm::dvec3 o(f.origin), t = glm::dvec3(f.pixel00) + px * glm::dvec3(f.pixelDu) + py * glm::dvec3(f.pixelDv);
    const double s = (zPlane - o.z) / (t.z - o.z);
    return o + s * (t - o);
}

}  // namespace vkp::test
