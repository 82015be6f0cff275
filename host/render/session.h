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
#include "render/aov.h"
#include "render/render_key.h"
#include "render/renderer.h"

namespace vkp {

/// A moment of the render at which the session hands the current image out (see SessionOptions).
struct Checkpoint {
    std::uint32_t spp = 0;  ///< samples per pixel in `image`
    double seconds = 0.0;   ///< wall time since process start when `image` was read back (s)
    const Image& image;     ///< the mean image so far (linear radiance)
    /// The denoised image (SessionOptions::denoiseCheckpoints), else null; made after `seconds`,
    /// in denoiseSeconds (so a denoised image is ready at seconds + denoiseSeconds).
    const Image* denoised = nullptr;
    double denoiseSeconds = 0.0;
};

/// What the denoiser gets (render/denoiser.h): the mean image, the variance of each pixel's mean,
/// and the feature images.
struct DenoiseRequest {
    const Image& color;
    const Image& variance;
    const FeatureImages& features;
};

struct SessionOptions {
    /// Stop at this sample index: after samples [renderer.firstSample(), spp) of every pixel (the
    /// samples per pixel of a render from sample 0; the end B of `--sample-range A:B`).
    std::uint32_t spp = 64;
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
    /// `--checkpoint FILE`: the render's state (render/accum_file.h) every checkpointEvery seconds
    /// of wall time, at a signal and at the end, atomically; the last one stays if the render fails.
    std::filesystem::path checkpoint;
    double checkpointEvery = 60.0;
    /// `--partial FILE.exr`: the state at the end (also after a signal), for `vkpath merge`.
    std::filesystem::path partial;
    /// The render's key, written into the checkpoint and the partial (render/render_key.h). Needed
    /// only where writesState() (or a resume compares it); hashing every array costs about 0.15 s
    /// per 100 MB, so the CLI computes it only then.
    RenderKey key;
    /// A state file is written: `--checkpoint` or `--partial`.
    bool writesState() const { return !checkpoint.empty() || !partial.empty(); }
    /// `--aov`: feature layers of the final images and of EXR dumps (render/aov.h). The kernel's
    /// ones need RenderOptions::aov; aovFrame places their positions (GpuArrays::aovFrame).
    std::vector<Aov> aovs;
    AovFrame aovFrame;
    /// `--denoise`: the denoiser (null: none). Needs RenderOptions::aov (its guides).
    std::function<Image(const DenoiseRequest&)> denoiser;
    /// Where the denoised final image goes: `--denoise-output FILE`, else beside every output
    /// (denoisedPath). Never over the raw image.
    std::filesystem::path denoiseOutput;
    /// `--denoise-dumps`: every dump gets frame-<spp>.denoised.<ext> too.
    bool denoiseDumps = false;
    /// Denoise at every checkpoint too, for onCheckpoint (an error log of the denoised image).
    bool denoiseCheckpoints = false;
};

/// The denoised image's file beside output `path`: "<stem>.denoised<ext>" (out.png -> out.denoised.png).
std::filesystem::path denoisedPath(const std::filesystem::path& path);
/// Where the denoised final image goes: `--denoise-output`, else denoisedPath of every output.
std::vector<std::filesystem::path> denoisedOutputs(const SessionOptions& o);
/// Appends to `writes` the files of denoisedOutputs(o) holding `denoised` (which must outlive
/// them), with `options` (its layers left out) and the metadata vkpath.denoised.
void addDenoisedWrites(const Image& denoised, const SessionOptions& o, WriteOptions options, std::vector<AtomicWrite>& writes);

struct SessionResult {
    std::uint32_t spp = 0;
    double seconds = 0.0;        ///< wall time since process start
    double renderSeconds = 0.0;  ///< time spent in batches of samples
    double firstBatchSeconds = 0.0;  ///< the first batch (1 spp), shader JIT included
    double firstSampleAt = 0.0;      ///< wall time since process start when the first batch ended (s)
    std::uint64_t firstBatchRays = 0;  ///< rays traced by the first batch
    double longestDispatchSeconds = 0.0;  ///< Renderer::longestDispatchSeconds at the end
    std::uint32_t pixelsPerInvocation = 1;  ///< Renderer::maxPixelsPerInvocation at the end
    double checkpointSeconds = 0.0;  ///< time spent in checkpoints: image read-back + onCheckpoint (s)
    std::uint32_t checkpoints = 0;   ///< number of onCheckpoint calls
    double outputSeconds = 0.0;      ///< time spent writing dumps and the final images (s)
    RenderCounters counters;
    std::uint64_t pixels = 0;
    std::uint64_t samplesTaken = 0;  ///< over all pixels (Renderer::samplesTaken)
    std::uint32_t activePixels = 0;  ///< still active at the end (all unless adaptive sampling is on)
    std::uint32_t firstSample = 0;   ///< the render held samples [firstSample, spp) at the end
    std::uint64_t nonfinitePixels = 0;  ///< pixels of the final image that are NaN or Inf (0 unless something is wrong)
    int signal = 0;                  ///< SIGINT or SIGTERM that ended the render early (core/interrupt.h), else 0
    std::uint32_t stateWrites = 0;   ///< checkpoint files written (periodic ones and the final one)
    double denoiseSeconds = 0.0;     ///< the final image's denoising (0 without --denoise)
};

/// The text metadata of an output image of the render that holds samples [first, next):
/// vkpath.version, vkpath.spp (= next - first; the most any pixel had, with adaptive sampling),
/// vkpath.samples ("first:next") and, after a signal, vkpath.interrupted ("SIGINT" / "SIGTERM").
std::vector<std::pair<std::string, std::string>> imageMetadata(std::uint32_t first, std::uint32_t next, int signal);

/// Runs the render. `processStart` is when the process started (the time limit counts from it).
/// Ends early, after the batch in flight, when SIGINT or SIGTERM arrives (installInterruptHandlers,
/// core/interrupt.h): the outputs, the partial and the checkpoint are then written with the
/// samples reached, and SessionResult::signal says so. The outputs, the partial and the final
/// checkpoint are written all or none (writeImages).
SessionResult runSession(Renderer& renderer, const SessionOptions& options,
                         std::chrono::steady_clock::time_point processStart);

/// File name of a progressive dump: frame-<spp zero-padded to 6 digits>.<ext>.
std::string dumpFileName(std::uint32_t spp, ImageFormat format);

}  // namespace vkp
