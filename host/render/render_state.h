// What a Renderer holds that decides its future images, as plain host arrays: enough to continue a
// render bit for bit in another process (checkpoints, `--resume`), or to add up the samples of
// several renders (sample ranges, `vkpath merge`, several devices). Written to and read from files
// by render/accum_file.h.
#pragma once
#include <cstdint>
#include <vector>

#include "render/aov.h"
#include "render/renderer.h"
#include "shared/aov.h"

namespace vkp {

/// Floats per pixel of each accumulation array: two vec4 as on the device, (hi.rgba, lo.rgba), the
/// compensated pair of shared/compensated_sum.h.
inline constexpr std::uint32_t kStateFloatsPerPixel = 8;
/// Floats per pixel of the feature images' sums (`--aov`): shared/aov.h's layout.
inline constexpr std::uint32_t kAovFloatsPerPixel = 4 * gpu::AOV_VEC4_PER_PIXEL;

struct RenderState {
    std::uint32_t width = 0, height = 0;
    /// Samples [firstSample, nextSample) of every pixel are in the sums (adaptive sampling: of every
    /// pixel that was active when each was taken).
    std::uint32_t firstSample = 0, nextSample = 0;
    std::uint64_t samplesTaken = 0;  ///< over all pixels (Renderer::samplesTaken)
    RenderCounters counters;         ///< rays, non-finite samples, loop-guard cuts so far
    /// Per pixel (kStateFloatsPerPixel floats each, row by row from the top): sum = (RGB sum, count
    /// of finite samples; then their compensation terms); sumSq = (RGB sum of squares, 0; then
    /// compensation terms). Exactly the device's bits.
    std::vector<float> sum, sumSq;
    /// Adaptive sampling only (else empty): the decision stream's sums (RGB, count, then RGB sums
    /// of squares, 0) and one byte per pixel, 1 = still receiving samples.
    std::vector<float> decision;
    std::vector<std::uint8_t> active;
    /// Feature images only (`--aov`, else empty): kAovFloatsPerPixel floats per pixel, the device's
    /// sums (shared/aov.h).
    std::vector<float> aov;
    /// Feature images only: where their positions are (GpuArrays::aovFrame), so that a file alone
    /// (`vkpath merge`) can make the position and depth images.
    AovFrame aovFrame;

    std::uint64_t pixels() const { return std::uint64_t(width) * height; }
    bool adaptive() const { return !active.empty(); }
    /// The per-pixel sums combined in double (as Renderer::readSums).
    PixelSums pixelSums() const;
};

}  // namespace vkp
