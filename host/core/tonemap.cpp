#include "core/tonemap.h"

#include <cmath>

namespace vkp {

double srgbEncode(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

double exposureScale(double exposureStops) { return std::exp2(exposureStops); }

uint8_t linearToSrgb8(float linear, double scale) {
    double v = double(linear) * scale;
    if (!(v > 0.0)) return 0;  // NaN, zero and negatives
    if (v >= 1.0) return 255;  // includes +inf
    return uint8_t(std::lround(srgbEncode(v) * 255.0));
}

std::vector<uint8_t> toSrgb8(const Image& image, double exposureStops) {
    image.checkConsistent();
    const double scale = exposureScale(exposureStops);
    std::vector<uint8_t> out(image.rgb.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = linearToSrgb8(image.rgb[i], scale);
    return out;
}

}  // namespace vkp
