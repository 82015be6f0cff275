// The progressive renderer: uploads a scene, owns the accumulation buffers, and adds samples per
// pixel batch after batch. It knows nothing of files, progress bars or time limits (render/session).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/image.h"
#include "render/features.h"
#include "scene/scene.h"

namespace vkp {

class VulkanDevice;
struct FlatBvh;

struct RendererOptions {
    Sampler sampler = Sampler::Mis;
    Sequence sequence = Sequence::Sobol;  ///< where samples' random numbers come from (`--sequence`)
    bool fullVariant = false;              ///< compile every feature in (`--variant full`)
    LightPick lightPick = LightPick::Power;  ///< how NEE picks an emitter (`--light-pick`)
    LightSampling lightSampling = LightSampling::Auto;  ///< NEE on quads/triangles (`--light-sampling`)
    float solidAngleMinSize = kSolidAngleMinSize;       ///< Auto's switch, sr (`--solid-angle-min`)
    /// Workgroup size of the kernel (x * y invocations, each one pixel) and the order its tiles are
    /// visited in: scrambled (default; balances lavapipe's threads) or row by row (`--tile-order
    /// linear`). Neither changes the image, only the speed.
    std::uint32_t workgroupX = 8, workgroupY = 8;
    bool linearTiles = false;
    /// Samples one dispatch adds per pixel; 0 = automatic: as many (up to 8) as keep the busiest
    /// invocation at half of lavapipe's loop budget, measured after every submission.
    std::uint32_t samplesPerDispatch = 0;
    /// Adaptive sampling (render/adaptive.h): a pixel stops receiving samples once its estimated
    /// relative standard error is <= this (0 = off: every pixel gets every sample).
    double adaptiveThreshold = 0.0;
    /// Samples every pixel receives before the first adaptive decision.
    std::uint32_t adaptiveMinSpp = 64;
};

/// Totals since the render began.
struct RenderCounters {
    std::uint64_t rays = 0;       ///< rays traced: camera, bounce and shadow rays (counted on the device)
    std::uint64_t nonfinite = 0;  ///< samples dropped because they were NaN or Inf
    std::uint64_t loopGuard = 0;  ///< paths cut short by the loop-pass guard (a bug if not 0)
};

/// Per-pixel sums as the device holds them (each a compensated float pair, read as one double): for pixel i, sum[4i..4i+2] = sum of samples (RGB),
/// sum[4i+3] = number of finite samples, sumSq[4i..4i+2] = sum of squares.
struct PixelSums {
    std::uint32_t width = 0, height = 0;
    std::vector<double> sum, sumSq;  ///< compensated device sums, combined in double
    /// The mean image (radiance); pixels without a sample are 0.
    Image mean() const;
    /// The variance of each pixel's mean (sample variance / n), per channel.
    Image varianceOfMean() const;
};

class Renderer {
public:
    /// Uploads `scene` (with its BVH) and builds the pipeline variant for it.
    Renderer(VulkanDevice& device, const Scene& scene, const FlatBvh& bvh, const RendererOptions& options);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Adds samples [samplesDone(), samplesDone() + count) to every active pixel (every pixel unless
    /// adaptive sampling is on), in one submission, and waits for it; then, with adaptive sampling,
    /// stops the pixels that have converged. Throws VulkanError on a device failure or a validation
    /// message.
    void addSamples(std::uint32_t count);
    /// Sample indices every active pixel has had (the spp of an image without adaptive sampling).
    std::uint32_t samplesDone() const { return done_; }
    /// Samples taken over all pixels (with adaptive sampling, the decision stream's included).
    std::uint64_t samplesTaken() const { return taken_; }
    /// Pixels still receiving samples (all of them unless adaptive sampling is on).
    std::uint32_t activePixels() const { return active_; }
    bool adaptive() const { return adaptiveThreshold_ > 0.0; }
    /// Adaptive sampling: one byte per pixel, 1 = still receiving samples.
    const std::vector<std::uint8_t>& activeMask() const { return activeMask_; }
    /// Adaptive decisions happen at adaptiveMinSpp spp and then every kAdaptiveStep spp.
    static constexpr std::uint32_t kAdaptiveStep = 16;
    /// Samples per pixel that the next dispatch adds.
    std::uint32_t samplesPerDispatch() const { return spd_; }
    /// Most loop passes one invocation made in the last addSamples (lavapipe stops loops at 65,535).
    std::uint32_t maxPassesLastBatch() const { return maxPasses_; }

    PixelSums readSums();
    Image image() { return readSums().mean(); }
    RenderCounters counters();
    const Features& features() const { return features_; }
    /// Bytes of the scene's device buffers: BVH nodes, primitives, materials, lights, environment,
    /// vertex attributes and textures (not the per-pixel accumulation buffers).
    std::uint64_t sceneBufferBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    VulkanDevice* dev_;
    Features features_;
    std::uint32_t width_, height_, spd_;
    bool autoSpd_;
    std::uint32_t done_ = 0;
    std::uint32_t maxPasses_ = 0;
    std::uint64_t taken_ = 0;
    std::uint32_t active_ = 0;
    double adaptiveThreshold_ = 0.0;
    std::uint32_t adaptiveMinSpp_ = 0;
    std::vector<std::uint8_t> activeMask_;
    void submitSamples(std::uint32_t count);
    void updateAdaptive();
};

}  // namespace vkp
