// The numbers of one render, written by `vkpath render --stats-json FILE` for scripts (the
// benchmark suite, tools/bench). The keys are documented in docs/performance.md "Measuring one render".
#pragma once
#include <glm/glm.hpp>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "render/error_metrics.h"

namespace vkp {

struct RunStats {
    std::string version;   ///< VKPATH_VERSION
    std::string scene;     ///< the scene file as given on the command line
    /// Camera-relative space: the point of the file's coordinates the renderer's origin is at
    /// (Scene::origin, the camera's position; world units).
    glm::dvec3 frameOrigin{0.0};
    std::string sampler;   ///< bsdf | light | mixture
    std::string sequence;  ///< random | sobol (--sequence)
    std::string lightPick = "power";             ///< power | uniform (--light-pick)
    std::string lightSampling = "auto";          ///< auto | solid-angle | area (--light-sampling)
    float solidAngleMinSize = 0.0f;              ///< auto's switch (sr; --solid-angle-min), else 0
    std::string workgroup = "8x8";               ///< the one the kernel ran with (--workgroup, else the device's)
    std::string tileOrder = "scrambled";         ///< scrambled | linear (--tile-order)
    std::string variant;   ///< Features::name() of the pipeline
    bool fullVariant = false;
    std::uint32_t width = 0, height = 0, maxDepth = 0, seed = 0, samplesPerDispatch = 1;
    std::uint32_t spp = 0;          ///< samples per pixel reached
    std::uint32_t sppRequested = 0;
    double timeLimit = 0.0;         ///< --time (s), 0 if none
    std::uint64_t rays = 0;         ///< rays traced (counted on the device)
    std::uint64_t firstBatchRays = 0;
    std::uint64_t nonfinite = 0, loopGuard = 0;
    std::uint64_t nonfinitePixels = 0;  ///< pixels of the final image that are NaN or Inf
    // Wall times in seconds.
    double secondsTotal = 0.0;        ///< process start to the end of the last output
    double secondsSceneLoad = 0.0;    ///< reading and validating the scene file
    double secondsBvh = 0.0;          ///< BVH build + flattening
    double secondsSetup = 0.0;        ///< Vulkan instance + device
    double secondsUpload = 0.0;       ///< Renderer construction: buffers, upload, pipeline creation
    double secondsFirstBatch = 0.0;   ///< the first batch (1 spp): includes the shader JIT
    double secondsRender = 0.0;       ///< every batch, the first included
    std::uint32_t pixelsPerInvocation = 1;  ///< the most pixels one invocation took (Renderer::maxPixelsPerInvocation)
    double secondsLongestDispatch = 0.0;  ///< the longest dispatch after the first submission (Renderer::longestDispatchSeconds)
    double secondsToFirstSample = 0.0;  ///< process start to the end of the first batch
    double secondsCheckpoints = 0.0;  ///< image read-backs + error rows
    double secondsOutput = 0.0;       ///< writing dumps and final images
    std::uint32_t checkpoints = 0;
    // Memory.
    std::uint64_t peakRssBytes = 0;      ///< the process's peak resident set (getrusage; lavapipe's buffers included)
    bool hugePages = false;              ///< malloc asks for transparent huge pages (core/huge_pages.h)
    // The BVH.
    bool spatialSplits = false;          ///< built with spatial splits (--spatial-splits, host/bvh/sbvh.h)
    std::uint64_t bvhPrimitives = 0;     ///< primitives on the device: one per reference (instances included)
    std::uint64_t sceneBufferBytes = 0;  ///< the scene's device buffers (Renderer::sceneBufferBytes)
    std::uint64_t stagingCopies = 0;     ///< transfers through staging buffers (VulkanDevice::stagingCopies)
    /// The kernel cache (core/disk_cache.h), if the render used one: its folder and what it did.
    struct KernelCache {
        std::string dir;
        std::uint64_t hits = 0, misses = 0, stores = 0, failedStores = 0;
        std::uint64_t pipelineCacheBytesLoaded = 0;  ///< VulkanDevice::pipelineCacheBytesLoaded
    };
    std::optional<KernelCache> kernelCache;
    // The device.
    std::string deviceName, deviceType, driverName, driverInfo, vulkanVersion;
    std::uint32_t subgroupSize = 0;  ///< the device's subgroup lanes (0: not reported)
    /// LP_NUM_THREADS and MESA_SHADER_CACHE_DIR as set in the environment (empty if unset).
    std::string lpNumThreads, mesaShaderCacheDir;
    /// The final errors, when rendered with --reference.
    std::optional<ErrorMetrics> error;
    std::string reference;

    /// Adaptive sampling: the threshold (0 = off) and the pixels still active at the end.
    double adaptiveThreshold = 0.0;
    std::uint32_t activePixels = 0;
    /// Samples taken over all pixels (counted by the renderer; spp x pixels without adaptive sampling).
    std::uint64_t samplesTaken = 0;

    std::uint64_t pixels() const { return std::uint64_t(width) * height; }
    std::uint64_t samples() const { return samplesTaken ? samplesTaken : pixels() * spp; }
};

struct Features;
struct RenderJob;
class DiskCache;

/// RunStats::kernelCache of `cache`.
RunStats::KernelCache kernelCacheStats(const DiskCache& cache);
struct SessionResult;

/// The stats of a finished render: what `job` asked for and what the session did (`kernel`: the
/// pipeline's Features, Renderer::features, for the variant and the workgroup it ran with). The
/// times of the steps before the session, the device, the memory and the error are the caller's.
RunStats runStats(const RenderJob& job, const Features& kernel, const SessionResult& result);

/// The stats as a JSON object (pretty-printed, keys in a fixed order, non-finite numbers as null).
/// Top-level keys scripts may rely on: spp, samples, rays, seconds_total, seconds_render,
/// samples_per_second, rays_per_second, nonfinite_samples, device (an object: name, type, driver,
/// driver_info, vulkan). Rates are per second of rendering (seconds_render); the *_steady rates leave
/// out the first batch (shader JIT).
std::string runStatsJson(const RunStats& stats);

/// Writes runStatsJson(stats) to `path` atomically (core/atomic_file.h). Throws InputError.
void writeRunStatsJson(const RunStats& stats, const std::filesystem::path& path);

/// `s` as a JSON string literal, quotes included (control characters escaped as \u00XX).
std::string jsonString(const std::string& s);

}  // namespace vkp
