// Synthetic inputs of the denoiser's tests (test_gpu_denoise.cpp): feature images with a closed
// form (albedo, normal, depth, clean radiance = albedo x irradiance) and their noisy renders at n
// spp, drawn from a fixed seed. The noise is Gaussian, per sample of standard deviation
// kNoisePerSample x the clean radiance, correlated between channels (as a path's channels are);
// the variance image is what a renderer estimates from n samples (a scaled chi-square draw), not
// the true value, so the denoiser sees variance estimates as noisy as a real render's.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/image.h"

namespace vkp::test {

/// Relative standard deviation of one sample's radiance (1: a sample's noise is as large as the
/// signal; at 16 spp the raw image's relative error is 25%).
inline constexpr double kNoisePerSample = 1.0;
/// Correlation of the noise between the three channels.
inline constexpr double kChannelCorrelation = 0.7;

/// A clean scene: what a converged render and its feature images would be.
struct CleanScene {
    Image radiance;             ///< the reference (linear)
    Image albedo;               ///< per pixel, RGB
    Image normal;               ///< unit normals, (0,0,0) where nothing was hit
    std::vector<float> depth;   ///< view-axis distance, +inf where nothing was hit
    std::vector<std::uint8_t> noiseFree;  ///< 1: the pixel's samples are all equal (the sky)
};

/// A noisy render of a clean scene: the mean of n samples and the variance of that mean.
struct NoisyRender {
    Image color;
    Image variance;
};

/// Gaussian numbers from a fixed-seed mt19937 (fully specified by the standard) by Box-Muller, so
/// the draws are identical on every platform.
class GaussianSource {
public:
    explicit GaussianSource(std::uint32_t seed) : gen_(seed) {}
    double uniform() { return (double(gen_() >> 5) + 0.5) * (1.0 / 134217728.0); }
    double next() {
        if (haveSpare_) {
            haveSpare_ = false;
            return spare_;
        }
        const double r = std::sqrt(-2.0 * std::log(uniform())), phi = 6.283185307179586 * uniform();
        spare_ = r * std::sin(phi);
        haveSpare_ = true;
        return r * std::cos(phi);
    }

private:
    std::mt19937 gen_;
    double spare_ = 0.0;
    bool haveSpare_ = false;
};

/// The noisy mean of n samples per pixel (n >= 2) and its estimated variance.
inline NoisyRender renderNoisy(const CleanScene& s, std::uint32_t n, std::uint32_t seed) {
    GaussianSource g(seed);
    NoisyRender r{Image(s.radiance.width, s.radiance.height), Image(s.radiance.width, s.radiance.height)};
    const double dof = double(n - 1);
    for (std::size_t i = 0; i < s.radiance.pixelCount(); ++i) {
        const double common = g.next();
        // Wilson-Hilferty: chi-square with dof degrees of freedom, divided by dof.
        const double z = g.next(), k = 2.0 / (9.0 * dof);
        const double chi2OverDof = std::max(0.0, std::pow(1.0 - k + z * std::sqrt(k), 3.0));
        for (int c = 0; c < 3; ++c) {
            const double ref = s.radiance.rgb[3 * i + c];
            const double sigmaMean = s.noiseFree[i] ? 0.0 : kNoisePerSample * ref / std::sqrt(double(n));
            const double e = std::sqrt(kChannelCorrelation) * common + std::sqrt(1.0 - kChannelCorrelation) * g.next();
            r.color.rgb[3 * i + c] = float(ref + sigmaMean * e);
            r.variance.rgb[3 * i + c] = float(sigmaMean * sigmaMean * chi2OverDof);
        }
    }
    return r;
}

/// A scene of two halves split at column w/2 (the left half is x < w/2): each side its albedo,
/// irradiance, normal and depth. Used for the edge tests: one feature differs at a time.
struct HalfSide {
    float albedo[3];
    float irradiance;
    float normal[3];
    float depth;
};
inline CleanScene twoHalves(std::uint32_t w, std::uint32_t h, const HalfSide& left, const HalfSide& right) {
    CleanScene s{Image(w, h), Image(w, h), Image(w, h), std::vector<float>(std::size_t(w) * h),
                 std::vector<std::uint8_t>(std::size_t(w) * h, 0)};
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            const HalfSide& side = x < w / 2 ? left : right;
            for (int c = 0; c < 3; ++c) {
                s.albedo.at(x, y, c) = side.albedo[c];
                s.radiance.at(x, y, c) = side.albedo[c] * side.irradiance;
                s.normal.at(x, y, c) = side.normal[c];
            }
            s.depth[std::size_t(y) * w + x] = side.depth;
        }
    return s;
}

/// Albedo of the piecewise-smooth scene's checker texture: squares of kCheckerSize pixels.
inline constexpr std::uint32_t kCheckerSize = 8;
inline constexpr float kCheckerLight[3] = {0.75f, 0.7f, 0.6f};
inline constexpr float kCheckerDark[3] = {0.12f, 0.2f, 0.3f};

/// Where the piecewise-smooth scene's regions lie, in pixels.
struct PiecewiseLayout {
    std::uint32_t skyEnd;     ///< rows [0, skyEnd): sky (a miss)
    std::uint32_t floorBegin; ///< rows [floorBegin, h): the checker floor
    std::uint32_t fold;       ///< between: a folded wall, its crease at this column
    std::uint32_t boxX0, boxX1, boxY0, boxY1;  ///< a box face in front of the wall's right part
};
inline PiecewiseLayout piecewiseLayout(std::uint32_t w, std::uint32_t h) {
    return {h * 3 / 20, h * 11 / 20, w / 2, w * 6 / 10, w * 17 / 20, h * 5 / 20, h * 9 / 20};
}

/// A piecewise-smooth scene: a sky (a miss, noise free), a wall folded at a vertical crease (two
/// normals, irradiance 1.0 and 0.35 times a smooth gradient, depth continuous at the crease), a
/// box face in front of the right part (same normal and albedo as the wall behind it, 2.5 units
/// nearer, brighter: a depth edge alone), and a receding floor (depth grows upwards) with an
/// albedo checker of kCheckerSize pixels under a smooth irradiance gradient and a shadow (a disc
/// of irradiance x 0.3 with a 3-pixel penumbra, which only the radiance shows).
inline CleanScene piecewiseScene(std::uint32_t w, std::uint32_t h) {
    const PiecewiseLayout L = piecewiseLayout(w, h);
    CleanScene s{Image(w, h), Image(w, h), Image(w, h), std::vector<float>(std::size_t(w) * h),
                 std::vector<std::uint8_t>(std::size_t(w) * h, 0)};
    const float inv = 1.0f / std::sqrt(2.0f);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
            const std::size_t i = std::size_t(y) * w + x;
            float a[3] = {0.6f, 0.6f, 0.6f}, n[3] = {0.0f, 0.0f, 0.0f}, e = 0.0f, z = 0.0f;
            if (y < L.skyEnd) {
                const float sky[3] = {0.5f, 0.65f, 0.9f};
                for (int c = 0; c < 3; ++c) s.radiance.at(x, y, c) = s.albedo.at(x, y, c) = sky[c];
                s.depth[i] = std::numeric_limits<float>::infinity();
                s.noiseFree[i] = 1;
                continue;
            }
            if (y >= L.floorBegin) {
                const bool light = ((x / kCheckerSize) + (y / kCheckerSize)) % 2 == 0;
                for (int c = 0; c < 3; ++c) a[c] = light ? kCheckerLight[c] : kCheckerDark[c];
                n[1] = 1.0f;
                z = 2.0f + 8.0f * (1.0f - v);
                e = 0.9f + 0.5f * std::sin(3.0f * u + 1.0f) * v;
                // A shadow with a soft edge (no feature marks it): a disc, irradiance x 0.3.
                const float du = (u - 0.3f) * float(w), dv = (v - 0.8f) * float(h), rad = 0.1f * float(h);
                const float t = std::clamp((std::sqrt(du * du + dv * dv) - rad) / 3.0f + 0.5f, 0.0f, 1.0f);
                e *= 0.3f + 0.7f * t;
            } else if (x >= L.boxX0 && x < L.boxX1 && y >= L.boxY0 && y < L.boxY1) {
                n[0] = -inv;
                n[2] = inv;
                z = 6.0f + 4.0f * (u - 0.5f) - 2.5f;
                e = 1.1f - 0.3f * v;
            } else {
                const bool left = x < L.fold;
                n[0] = left ? inv : -inv;
                n[2] = inv;
                z = 6.0f + 4.0f * std::abs(u - 0.5f);
                e = (left ? 1.0f : 0.35f) * (0.7f + 0.6f * u * (1.0f - v));
            }
            for (int c = 0; c < 3; ++c) {
                s.albedo.at(x, y, c) = a[c];
                s.normal.at(x, y, c) = n[c];
                s.radiance.at(x, y, c) = a[c] * e;
            }
            s.depth[i] = z;
        }
    return s;
}

/// relMSE: mean over pixels and channels of (x - ref)^2 / (ref^2 + 1e-2).
inline double relMse(const Image& x, const Image& ref) {
    double sum = 0.0;
    for (std::size_t i = 0; i < ref.rgb.size(); ++i) {
        const double d = double(x.rgb[i]) - ref.rgb[i];
        sum += d * d / (double(ref.rgb[i]) * ref.rgb[i] + 1e-2);
    }
    return sum / double(ref.rgb.size());
}

}  // namespace vkp::test
