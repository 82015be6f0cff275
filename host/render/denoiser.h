// The built-in denoiser (issue 17): a compute-shader filter that turns a noisy render and its
// feature images into a clean, BIASED estimate of the image. It never replaces the raw image,
// which stays unbiased. Algorithm, parameters and costs: docs/design.md "Denoiser"; the kernel is
// shaders/denoise.comp.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/image.h"

namespace vkp {

class VulkanDevice;

/// What the denoiser reads. All images are width x height, row 0 = the top (core/image.h). The
/// feature images describe the first non-specular hit of each pixel's samples (averaged over them).
struct DenoiseInput {
    const Image* color = nullptr;     ///< mean radiance per pixel (linear)
    const Image* variance = nullptr;  ///< variance of each pixel's MEAN, per channel (sample variance / n)
    const Image* albedo = nullptr;    ///< mean albedo (RGB, mostly in [0,1]); for a miss or a pure
                                      ///< emitter the seen radiance clamped to [0,1]
    const Image* normal = nullptr;    ///< mean world-space shading normal, RGB = XYZ, length <= 1;
                                      ///< (0,0,0) where nothing was hit
    const std::vector<float>* depth = nullptr;  ///< per pixel (row-major), distance along the camera's
                                                ///< view axis of the first hit (scene units); +inf
                                                ///< (or any non-finite value) where no sample hit
    /// Optional, per pixel: the samples the mean normal averages (FeatureImages::samples). With
    /// it the normal's edge-stopping allows for the mean normal's own noise (normalNoise); without
    /// it every normal is taken as exact.
    const std::vector<float>* samples = nullptr;
};

/// Which filter the denoiser runs (docs/design.md "Denoiser").
enum class DenoiseFilter : std::uint32_t {
    /// A first level of non-local means (Rousselle, Knaus and Zwicker 2012): every pixel of a
    /// (2 nlmRadius + 1)^2 window weighted by how alike the 3x3 patches around it and the centre
    /// are, times the normal and depth weights below, as a local linear fit; then a-trous levels of
    /// step 2, 4, ... (below).
    NonLocalMeans,
    /// SVGF's edge-avoiding a-trous wavelets (Schied et al. 2017) alone: levels of step 1, 2, 4, ...
    ATrous,
};

/// The filter's parameters, each measured on the benchmark suite's scenes (docs/design.md
/// "Denoiser", docs/performance.md "Denoiser").
struct DenoiseOptions {
    /// Non-local means first by default: measured on the suite's scenes it leaves 7-20 % less error
    /// than the a-trous filter alone on all but env-sky, where both leave at most 3.2 % of the raw
    /// error (docs/performance.md "Non-local means as the first level").
    DenoiseFilter filter = DenoiseFilter::NonLocalMeans;
    /// NonLocalMeans: the window reaches this many pixels from the centre (1..15).
    std::uint32_t nlmRadius = 4;
    /// NonLocalMeans: a patch pair's distance is in units of nlmPatchK^2 x the sum of the two
    /// pixels' variances (Rousselle et al. 2012's k); larger blurs more.
    float nlmPatchK = 0.6f;
    /// NonLocalMeans: a tap brighter than the centre also weighs exp(-excess / (nlmBrighterSigma x
    /// the centre's median-limited standard deviation)): without it a dark pixel beside a few very
    /// bright, very noisy ones (the sun seen through glass) finds their patches alike within their
    /// variance and takes their light in, a halo.
    float nlmBrighterSigma = 16.0f;
    /// Levels (1..10; 0: the filter's measured default, levels(options)): level 0 is the
    /// non-local means pass (NonLocalMeans) or an a-trous level of step 1, level i > 0 an a-trous
    /// level whose taps are 2^i pixels apart. Defaults: the a-trous filter alone 4, not SVGF's 5
    /// (the fifth level, taps 16 pixels apart, added more bias than it removed noise on the
    /// suite's scenes: docs/performance.md "sigmaNormal and the number of levels"); after non-local
    /// means 1 more (docs/performance.md "Non-local means as the first level").
    std::uint32_t iterations = 0;
    /// A-trous levels: luminance edge-stopping: a tap whose demodulated luminance differs from the centre's by
    /// sigmaLuminance standard deviations (of the centre's mean, blurred 3x3) weighs 1/e. Larger
    /// blurs more; as the variance goes to 0 every differing tap goes to weight 0.
    float sigmaLuminance = 4.0f;
    /// Normal edge-stopping: the weight is max(0, cos(angle between the normals))^sigmaNormal.
    /// 16, not SVGF's 128: a 90-degree edge still weighs 0 and 45 degrees 0.004, while normals a
    /// few degrees apart (a tessellated or small curved surface, the mean normals of mixed
    /// pixels) mix (docs/performance.md "sigmaNormal and the number of levels").
    float sigmaNormal = 16.0f;
    /// A mean normal shorter than this has no direction to trust: its pixel's samples found
    /// surfaces facing many ways or mostly none (the inside of a glass sphere full of fog, seen
    /// through its refraction), so the unit vector made from it is noise, and at SVGF's
    /// sigmaNormal 128 any two such pixels would never mix. Such a pixel is filtered as one without a normal
    /// (alike with others of its kind, never mixed with pixels that have one).
    float minNormalLength = 0.5f;
    /// A mean normal of n samples that disagree (an edge, a corner, depth of field, fog) is itself
    /// noisy: its direction's variance is about theta^2 = (1 - |mean|^2) / (n |mean|^2) (rad^2;
    /// samples of unit normals or none). Between two pixels the cosine's exponent is
    /// min(sigmaNormal, normalNoise / (theta_p^2 + theta_q^2)), so two normals that differ by
    /// about their noise weigh exp(-normalNoise / 2) instead of nothing. 0: every normal exact
    /// (SVGF's rule). Needs DenoiseInput::samples.
    float normalNoise = 1.0f;
    /// Before filtering, a pixel whose demodulated luminance exceeds every one of its 8 neighbours'
    /// by more than fireflyBound of that neighbour's standard deviations (of its mean) is scaled
    /// down to the largest such bound: an isolated firefly (a rare bright path in a pixel, a
    /// caustic seen at low spp) that the edge-stopping would otherwise keep. Biased (energy of
    /// such paths is dropped from the denoised image, never from the raw one); 0: off. Only
    /// where the excess is within fireflyBound of the pixel's own standard deviations, so a pixel
    /// that is sure of its value (a small converged highlight) is kept. Measured choice:
    /// docs/performance.md "Fireflies among their neighbours".
    float fireflyBound = 2.0f;
    /// Depth edge-stopping: a tap whose depth differs from the centre's by sigmaDepth times the
    /// change the centre's depth gradient predicts weighs 1/e (plus 0.1% of the depth, so a flat
    /// face facing the camera never stops the filter).
    float sigmaDepth = 1.0f;
    /// Demodulation divides by max(albedo, albedoEpsilon) per channel and multiplies the filtered
    /// result by the same number, so where nothing is blurred the image comes back unchanged
    /// (to rounding), whatever the albedo. A black pixel (albedo 0) is filtered as radiance / eps
    /// and multiplied back by eps: what it gathers from brighter neighbours is scaled down by eps.
    float albedoEpsilon = 1e-3f;
    /// Each level fits a plane to its taps (local linear regression) and keeps the plane's value at
    /// the centre, instead of their weighted mean: no bias from a gradient where an edge cuts the
    /// window on one side. The ridge (in units of the taps' total weight, taps 1 apart) keeps the
    /// fit solvable when the taps lie on one line; < 0: the weighted mean (SVGF's level).
    /// Measured choice: docs/design.md "Denoiser".
    float localLinearRidge = 0.01f;
    /// Tests only: the most rows one band may hold (0: as many as the device's limits allow), to
    /// force bands on a small image.
    std::uint32_t maxBandRows = 0;
};

/// Rows of one band of a large image: the output rows [y0, y1) and the rows loaded for them,
/// [loadY0, loadY1), a halo of the filter's radius on each side where the image has rows.
struct DenoiseBand {
    std::uint32_t y0 = 0, y1 = 0;
    std::uint32_t loadY0 = 0, loadY1 = 0;
};

/// Radius in pixels of everything one output pixel depends on, for `iterations` a-trous levels:
/// sum over levels of 2 x 2^level (the 3x3 variance blur and the depth gradient reach 1 pixel,
/// within that), plus 1 for the firefly bound's 3x3 neighbours.
std::uint32_t filterRadius(std::uint32_t iterations);

/// The levels `options` ask for: DenoiseOptions::iterations, or the filter's default where that is 0.
std::uint32_t levels(const DenoiseOptions& options);

/// The same for the filter `options` choose: for non-local means the window's radius, plus 1 for
/// the tap's 3x3 patch and 1 for the firefly bound, plus 2 x 2^i for each a-trous level i > 0.
std::uint32_t filterRadius(const DenoiseOptions& options);

/// The bands of a height-row image when one band may load at most maxRows rows: one band if the
/// image fits, else bands of maxRows - 2 halo output rows (the last shorter). Throws
/// std::invalid_argument when maxRows <= 2 halo (no band could produce a row).
std::vector<DenoiseBand> planDenoiseBands(std::uint32_t height, std::uint32_t maxRows, std::uint32_t halo);

/// The denoiser on one device: its pipelines are built once; each run uploads the inputs, filters
/// them on the device and reads the result back. Reusable for images of any size (its buffers grow
/// to the largest band seen). Not thread-safe: one run at a time.
class Denoiser {
public:
    explicit Denoiser(VulkanDevice& device, const DenoiseOptions& options = {});
    ~Denoiser();
    Denoiser(const Denoiser&) = delete;
    Denoiser& operator=(const Denoiser&) = delete;

    /// The denoised image (linear radiance, same size as the input). Throws std::invalid_argument
    /// when an image is missing, the sizes differ, or options are out of range; DeviceError when
    /// the image is too wide for the device (one band of 2 x filterRadius + 1 rows does not fit
    /// its limits); VulkanError on a device failure or a validation message.
    Image run(const DenoiseInput& input);

    const DenoiseOptions& options() const { return options_; }
    /// Bands of the last run (1 when the image fitted one pass).
    std::size_t lastBandCount() const { return lastBands_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    VulkanDevice* dev_;
    DenoiseOptions options_;
    std::size_t lastBands_ = 0;
};

}  // namespace vkp
