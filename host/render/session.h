// A render from start to finish: batches of samples until --spp or --time, progressive frame
// dumps, progress on stderr, and the final images.
#pragma once
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "render/renderer.h"

namespace vkp {

/// A moment of the render at which the session hands the current image out (see SessionOptions).
struct Checkpoint {
    std::uint32_t spp = 0;  ///< samples per pixel in `image`
    double seconds = 0.0;   ///< wall time since process start when `image` was read back (s)
    const Image& image;     ///< the mean image so far (linear radiance)
};

struct SessionOptions {
    std::uint32_t spp = 64;                        ///< stop after this many samples per pixel
    double timeLimit = 0.0;                        ///< seconds since process start; 0 = none
    std::vector<std::filesystem::path> outputs;    ///< final images (format by extension)
    double exposure = 0.0;                         ///< stops, for PNG output
    std::uint32_t dumpEvery = 0;                   ///< dump every N spp (0 = never)
    std::filesystem::path dumpDir = "frames";
    std::vector<ImageFormat> dumpFormats{ImageFormat::Png};  ///< formats of each dump
    bool quiet = false;
    /// Called with the image at every dump (when dumpEvery > 0), at every power of two spp (1, 2,
    /// 4, ...; when checkpointPowersOfTwo and dumpEvery == 0) and once at the end (never twice at the
    /// same spp). Batches are cut so that they end exactly at these spp. Time spent here counts in
    /// the wall time (and towards timeLimit) but not in renderSeconds.
    std::function<void(const Checkpoint&)> onCheckpoint;
    bool checkpointPowersOfTwo = false;
};

struct SessionResult {
    std::uint32_t spp = 0;
    double seconds = 0.0;        ///< wall time since process start
    double renderSeconds = 0.0;  ///< time spent in batches of samples
    double firstBatchSeconds = 0.0;  ///< the first batch (1 spp), shader JIT included
    double firstSampleAt = 0.0;      ///< wall time since process start when the first batch ended (s)
    std::uint64_t firstBatchRays = 0;  ///< rays traced by the first batch
    double checkpointSeconds = 0.0;  ///< time spent in checkpoints: image read-back + onCheckpoint (s)
    std::uint32_t checkpoints = 0;   ///< number of onCheckpoint calls
    double outputSeconds = 0.0;      ///< time spent writing dumps and the final images (s)
    RenderCounters counters;
    std::uint64_t pixels = 0;
    std::uint64_t samplesTaken = 0;  ///< over all pixels (Renderer::samplesTaken)
    std::uint32_t activePixels = 0;  ///< still active at the end (all unless adaptive sampling is on)
};

/// Runs the render. `processStart` is when the process started (the time limit counts from it).
SessionResult runSession(Renderer& renderer, const SessionOptions& options,
                         std::chrono::steady_clock::time_point processStart);

/// File name of a progressive dump: frame-<spp zero-padded to 6 digits>.<ext>.
std::string dumpFileName(std::uint32_t spp, ImageFormat format);

}  // namespace vkp
