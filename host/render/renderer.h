// The progressive renderer: uploads the packed arrays of a render (render/gpu_arrays.h), owns the
// accumulation buffers, and adds samples per pixel batch after batch. It knows nothing of files,
// progress bars or time limits (render/session.h), nor of device-side sizes (render/gpu_arrays.h).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/features.h"
#include "render/render_options.h"

namespace vkp {

class VulkanDevice;
class ComputePipeline;
struct GpuArrays;
struct RenderState;
struct DeviceLimits;

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
    /// Uploads `arrays` (packGpuArrays of the scene and `options`) and builds the pipeline variant
    /// they name. Refuses a render that does not fit the device before allocating anything: throws
    /// DeviceError with fitProblem's one line. An image whose accumulation buffers exceed one
    /// storage-buffer binding is rendered in bands of rows (planBands), each with buffers of its
    /// own; the sums do not depend on the split. `limits` (tests only): pretend the device has
    /// these limits instead of its own (to force bands on a small image).
    Renderer(VulkanDevice& device, const GpuArrays& arrays, const RenderOptions& options,
             const DeviceLimits* limits = nullptr);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Adds samples [samplesDone(), samplesDone() + count) to every active pixel (every pixel unless
    /// adaptive sampling is on), in one submission, and waits for it; then, with adaptive sampling,
    /// stops the pixels that have converged. Throws VulkanError on a device failure or a validation
    /// message.
    void addSamples(std::uint32_t count);
    /// The next sample index: every active pixel has had samples [firstSample(), samplesDone())
    /// (the spp of an image without adaptive sampling when firstSample() is 0).
    std::uint32_t samplesDone() const { return done_; }
    /// The first sample index of this render: 0, or where startAt or restore put it.
    std::uint32_t firstSample() const { return first_; }
    /// Before any sample: the render takes samples from index `first` on (`--sample-range`).
    /// Throws std::logic_error after samples were added or with adaptive sampling (whose decisions
    /// need every earlier sample).
    void startAt(std::uint32_t first);
    /// Several devices sharing a render (cli/multi_device.cpp): the next addSamples takes samples
    /// from index `next` on, wherever the last one ended. The sums then hold a set of sample
    /// chunks that only the caller knows (firstSample()/samplesDone() no longer describe it).
    /// Throws std::logic_error with adaptive sampling.
    void jumpTo(std::uint32_t next);
    /// Everything that decides the next images (sums, counts, adaptive state, counters), read back.
    RenderState state();
    /// Continues from `state` (read from a checkpoint of a render with the same key): the next
    /// samples are added to exactly these sums, so the images equal those of a render that was
    /// never interrupted, bit for bit. Throws InputError "<what>: ..." when its size or adaptive
    /// sampling does not match this renderer's.
    void restore(const RenderState& state, const std::string& what);
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
    /// The most that automatic samples per dispatch reach: 32 on a CPU device, where a dispatch is
    /// bounded by the session's submission anyway and longer ones waste fewer SIMD lanes at their
    /// end (docs/performance.md "Dispatch size"); 8 on a GPU.
    std::uint32_t maxAutoSamplesPerDispatch() const { return cpuDevice_ ? 32u : 8u; }
    /// Most loop passes one invocation made in the last addSamples (lavapipe stops loops at 65,535).
    std::uint32_t maxPassesLastBatch() const { return maxPasses_; }
    /// The longest dispatch so far, in seconds, the first submission's (shader JIT) left out: from
    /// device timestamps around each dispatch where the compute queue has them (lavapipe does),
    /// else each submission's wall time over the dispatches it held. What a GPU's watchdog would see.
    double longestDispatchSeconds() const { return longestDispatch_; }
    /// On a GPU, automatic samples per dispatch (RenderOptions::samplesPerDispatch 0) aim the
    /// slowest dispatch at this many seconds: tens of milliseconds, far from any watchdog.
    static constexpr double kTargetDispatchSeconds = 0.1;
    /// On a CPU device, an image where a dispatch of samplesPerDispatch() samples per pixel would
    /// take longer than this (seconds, from the last submission) has dispatches that add fewer
    /// samples per pixel take several pixels per invocation (RenderOptions::pixelsPerInvocation).
    static constexpr double kSlotSeconds = 0.5;
    /// ... and an invocation gets about this many samples in all (fewer if samplesPerDispatch() is).
    static constexpr std::uint32_t kSlotSamples = 8;
    /// Pixels per invocation of a submission that adds `count` samples per pixel (1 unless the rule
    /// above or RenderOptions::pixelsPerInvocation says otherwise).
    std::uint32_t pixelsPerInvocation(std::uint32_t count) const;
    /// The most pixels one invocation took in any submission so far.
    std::uint32_t maxPixelsPerInvocation() const { return maxSlots_; }
    /// Bands of rows the image is rendered in (1 unless it exceeds the device's binding range).
    std::uint32_t bandCount() const;

    PixelSums readSums();
    /// The feature images' sums (`--aov`; render/aov.h makes the images), kAovFloatsPerPixel floats
    /// per pixel, row by row from the top; empty without RenderOptions::aov.
    std::vector<float> readAovSums();
    Image image() { return readSums().mean(); }
    RenderCounters counters();
    const Features& features() const { return features_; }
    /// Bytes of the scene's device buffers: every read-only buffer (GpuArrays::sceneBytes; not the
    /// per-pixel accumulation buffers).
    std::uint64_t sceneBufferBytes() const { return sceneBytes_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    VulkanDevice* dev_;
    Features features_;
    std::uint32_t width_, height_, spd_;
    std::uint32_t pixelsPerInvocation_;  // RenderOptions::pixelsPerInvocation
    bool cpuDevice_;
    bool autoSpd_;
    double secondsPerSample_ = 0.0;  // the last submission's seconds per sample per pixel (not the first's)
    double targetDispatch_;  ///< seconds; 0: no time limit (RenderOptions::targetDispatchSeconds)
    bool linearTiles_;
    std::uint64_t sceneBytes_ = 0;
    std::uint32_t done_ = 0;
    std::uint32_t first_ = 0;
    std::uint32_t maxPasses_ = 0;
    double longestDispatch_ = 0.0;
    std::uint64_t taken_ = 0;
    std::uint32_t active_ = 0;
    double adaptiveThreshold_ = 0.0;
    std::uint32_t adaptiveMinSpp_ = 0;
    std::vector<std::uint8_t> activeMask_;
    void submitSamples(std::uint32_t count);
    std::uint32_t maxSlots_ = 1;
    /// The kernel's pipeline with PIXEL_SLOTS as given, its descriptor sets bound to every buffer.
    std::unique_ptr<ComputePipeline> makePipeline(bool pixelSlots);
    /// The PIXEL_SLOTS pipeline, made when first needed (a second JIT: only for images that use it).
    ComputePipeline& slotPipeline();
    /// Fault injection for tests (docs/farm.md "Faults"): with VKPATH_INJECT_DEVICE_LOST=N in the
    /// environment, the Nth submission of samples fails as a lost device makes it fail.
    std::uint32_t injectDeviceLostAt_ = 0, submissions_ = 0;
    void updateAdaptive();
    /// Adaptive sampling: each band's list of active pixels from activeMask_, uploaded.
    void uploadActiveLists();
};

}  // namespace vkp
