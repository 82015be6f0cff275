// Display encoding: linear radiance -> 8-bit sRGB (exposure, clamp, sRGB transfer function).
#pragma once
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace vkp {

/// The sRGB opto-electronic transfer function (IEC 61966-2-1): linear value in [0, 1] -> encoded
/// value in [0, 1]. 12.92 v for v <= 0.0031308, else 1.055 v^(1/2.4) - 0.055.
double srgbEncode(double linear);

/// The inverse of srgbEncode: encoded value in [0, 1] -> linear value in [0, 1].
double srgbDecode(double encoded);

/// 2^exposure: the factor that linear radiance is multiplied by before display encoding.
/// `exposureStops` is in photographic stops (+1 doubles the brightness).
double exposureScale(double exposureStops);

/// One linear value -> 8-bit sRGB code: multiply by `scale`, NaN -> 0, clamp to [0, 1] (so +inf
/// -> 255, negatives -> 0), srgbEncode, round to nearest.
uint8_t linearToSrgb8(float linear, double scale);

/// The whole image as 8-bit sRGB, 3 bytes per pixel (R, G, B), rows top to bottom like the image,
/// each value converted by linearToSrgb8 with scale = exposureScale(exposureStops).
std::vector<uint8_t> toSrgb8(const Image& image, double exposureStops);

}  // namespace vkp
