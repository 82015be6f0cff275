// Adaptive sampling: which pixels keep receiving samples (`--adaptive THRESHOLD`).
//
// Unbiased by construction. With adaptive sampling on, sample i of a pixel goes to one of two
// disjoint streams: i mod 4 == 3 to the *decision* stream, every other sample to the image. A
// pixel's convergence is judged from its decision stream alone (and its neighbours'), so the number
// of image samples a pixel receives is independent of the values of those samples, and their mean
// is an unbiased estimate of the pixel whatever the stopping rule. Judging a pixel by the samples
// that also form its image would bias it: a pixel whose rare bright paths (fireflies) have not
// shown up yet looks converged, stops, and stays too dark (tests/unit/test_adaptive.cpp measures
// both). The price is the quarter of the samples that only steer.
//
// Seams: a pixel stops only when it and every pixel of its 3x3 neighbourhood are converged, so the
// converged region grows inward from smooth areas and no pixel is left behind alone at the edge of
// an active one. Once stopped, a pixel never restarts, so every active pixel has had every sample
// index so far, and the kernel's per-sample random numbers stay (pixel, sample index, seed).
#pragma once
#include <cstdint>
#include <vector>

namespace vkp {

/// The sample stream of sample index i under adaptive sampling: true = decision stream.
inline bool isDecisionSample(std::uint32_t i) { return (i & 3u) == 3u; }
/// Image-stream samples among sample indices [0, n).
inline std::uint32_t imageSamplesBefore(std::uint32_t n) { return n - n / 4u; }

/// The relative standard error expected of a pixel's image mean after `imageSamples` samples,
/// estimated from its decision stream: sqrt(mean over RGB of var_c / imageSamples / (m_c^2 + 0.01)),
/// with m_c and var_c the decision stream's mean and sample variance of channel c. The 0.01 is the
/// one of the benchmark's relMSE, (x - y)^2 / (y^2 + 0.01), so THRESHOLD^2 is the relMSE a converged
/// pixel aims at. `sum` and `sumSq` hold RGB sums and the sample count in sum[3]; fewer than 4
/// decision samples give +infinity (not judged yet).
double estimatedRelativeError(const float sum[4], const float sumSq[4], std::uint32_t imageSamples);

/// One adaptive step. `decision` holds, per pixel, 8 floats: RGB sums and count, then RGB sums of
/// squares (the kernel's decision buffer). `active` (one byte per pixel, 1 = active) is updated:
/// an active pixel stops when its estimated error and that of every pixel in its 3x3 neighbourhood
/// is <= threshold (pixels already stopped count as converged). `samplesDone` is the number of
/// sample indices every active pixel has had. Returns the number of pixels still active.
std::uint32_t updateActivePixels(std::vector<std::uint8_t>& active, const std::vector<float>& decision,
                                 std::uint32_t width, std::uint32_t height, double threshold,
                                 std::uint32_t samplesDone);

/// The active pixels' indices (y * width + x) among rows [firstRow, firstRow + rows) (default: the
/// whole image), 8x8 tile by tile (tiles in row order from firstRow, pixels row by row inside a
/// tile), so that the 64 lanes of a workgroup shade neighbouring pixels. With firstRow a multiple of
/// 8 a band's list is the run of the whole image's list that falls in it.
std::vector<std::uint32_t> activePixelList(const std::vector<std::uint8_t>& active, std::uint32_t width,
                                           std::uint32_t height, std::uint32_t firstRow = 0, std::uint32_t rows = ~0u);

}  // namespace vkp
