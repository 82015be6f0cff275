// Decoding PNG and JPEG images (Debian's stb_image) to RGBA8, for glTF images and JSON image
// textures alike: the header is read first (core/image_header.h), so that sizes beyond the limits
// and truncated files get a message of their own instead of stb_image's "unknown image type".
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vkp {

/// A decoded image, RGBA8, rows top to bottom.
struct Rgba8Image {
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes
};

/// Decodes a PNG or JPEG held in `bytes` (each side in [1, maxSide]). Returns "" and fills `out`,
/// or one line saying what is wrong (no file name: the caller names the place).
std::string decodeLdrImage(std::span<const unsigned char> bytes, std::uint32_t maxSide, Rgba8Image& out);

}  // namespace vkp
