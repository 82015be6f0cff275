// A linear-radiance RGB float image: what the renderer produces and what references are read into.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vkp {

/// A width x height RGB image of linear radiance (scene-referred, not tone mapped), 3 floats per
/// pixel, interleaved R,G,B. Row 0 is the TOP of the image, x grows to the right; pixel (x, y)
/// starts at rgb[3 * (y * width + x)]. Every reader and writer keeps this orientation.
struct Image {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgb;  ///< 3 * width * height values

    Image() = default;
    /// A black (all zero) image of the given size in pixels.
    Image(uint32_t w, uint32_t h);

    /// Number of pixels (width * height).
    size_t pixelCount() const { return size_t(width) * height; }
    /// True when the image has no pixels.
    bool empty() const { return pixelCount() == 0; }
    /// Index in `rgb` of the red value of pixel (x, y); y = 0 is the top row.
    size_t offset(uint32_t x, uint32_t y) const { return 3 * (size_t(y) * width + x); }

    /// The three values (R, G, B) of pixel (x, y); y = 0 is the top row. No bounds check.
    std::span<float, 3> pixel(uint32_t x, uint32_t y) { return std::span<float, 3>(rgb.data() + offset(x, y), 3); }
    std::span<const float, 3> pixel(uint32_t x, uint32_t y) const {
        return std::span<const float, 3>(rgb.data() + offset(x, y), 3);
    }
    /// Channel c (0 = R, 1 = G, 2 = B) of pixel (x, y). No bounds check.
    float& at(uint32_t x, uint32_t y, int c) { return rgb[offset(x, y) + size_t(c)]; }
    float at(uint32_t x, uint32_t y, int c) const { return rgb[offset(x, y) + size_t(c)]; }
    /// Sets pixel (x, y) to (r, g, b). No bounds check.
    void set(uint32_t x, uint32_t y, float r, float g, float b);

    /// Throws std::invalid_argument when rgb.size() != 3 * width * height (a programming error).
    void checkConsistent() const;
};

/// A named group of 1 to 3 channels written with an image (a feature image, render/aov.h): in EXR
/// as channels "<name>.<channel>" of the same file, in the other formats as a file of its own
/// (core/image_io.h layerFilePath).
struct ImageLayer {
    std::string name;                   ///< e.g. "albedo"; letters, digits, '_' and '-'
    std::vector<std::string> channels;  ///< e.g. {"R", "G", "B"}, {"X", "Y", "Z"}, {"Z"}
    Image values;                       ///< channel k of pixel i in values.rgb[3 * i + k]; the image's size
};

}  // namespace vkp
