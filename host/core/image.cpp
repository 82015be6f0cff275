#include "core/image.h"

#include <stdexcept>
#include <string>

namespace vkp {

Image::Image(uint32_t w, uint32_t h) : width(w), height(h), rgb(3 * size_t(w) * h, 0.0f) {}

void Image::set(uint32_t x, uint32_t y, float r, float g, float b) {
    float* p = rgb.data() + offset(x, y);
    p[0] = r;
    p[1] = g;
    p[2] = b;
}

void Image::checkConsistent() const {
    if (rgb.size() != 3 * pixelCount()) {
        throw std::invalid_argument("Image: " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                                    std::to_string(3 * pixelCount()) + " floats, has " +
                                    std::to_string(rgb.size()));
    }
}

}  // namespace vkp
