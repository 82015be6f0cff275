#include "render/adaptive.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vkp {

double estimatedRelativeError(const float sum[4], const float sumSq[4], std::uint32_t imageSamples) {
    const double n = sum[3];
    if (n < 4.0 || imageSamples == 0) return std::numeric_limits<double>::infinity();
    double e2 = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double m = sum[c] / n;
        const double var = std::max(0.0, (double(sumSq[c]) - n * m * m) / (n - 1.0));
        e2 += var / double(imageSamples) / (m * m + 0.01);
    }
    return std::sqrt(e2 / 3.0);
}

std::uint32_t updateActivePixels(std::vector<std::uint8_t>& active, const std::vector<float>& decision,
                                 std::uint32_t width, std::uint32_t height, double threshold,
                                 std::uint32_t samplesDone) {
    const std::size_t pixels = std::size_t(width) * height;
    const std::uint32_t imageSamples = imageSamplesBefore(samplesDone);
    std::vector<std::uint8_t> unconverged(pixels, 0);
    for (std::size_t i = 0; i < pixels; ++i)
        if (active[i]) {
            const float* d = decision.data() + 8 * i;
            unconverged[i] = !(estimatedRelativeError(d, d + 4, imageSamples) <= threshold);
        }
    std::uint32_t count = 0;
    std::vector<std::uint8_t> next(active);
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            if (!active[i]) continue;
            bool keep = false;
            for (std::uint32_t yy = y ? y - 1 : 0; yy <= std::min(y + 1, height - 1) && !keep; ++yy)
                for (std::uint32_t xx = x ? x - 1 : 0; xx <= std::min(x + 1, width - 1) && !keep; ++xx)
                    keep = unconverged[std::size_t(yy) * width + xx] != 0;
            next[i] = keep;
            count += keep;
        }
    active.swap(next);
    return count;
}

std::vector<std::uint32_t> activePixelList(const std::vector<std::uint8_t>& active, std::uint32_t width,
                                           std::uint32_t height, std::uint32_t firstRow, std::uint32_t rows) {
    std::vector<std::uint32_t> list;
    height = std::min(height, firstRow + std::min(rows, height));
    for (std::uint32_t ty = firstRow; ty < height; ty += 8)
        for (std::uint32_t tx = 0; tx < width; tx += 8)
            for (std::uint32_t y = ty; y < std::min(ty + 8, height); ++y)
                for (std::uint32_t x = tx; x < std::min(tx + 8, width); ++x)
                    if (active[std::size_t(y) * width + x]) list.push_back(y * width + x);
    return list;
}

}  // namespace vkp
