// Internal to image_io: one encoder/decoder pair per linear float format.
#pragma once
#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace vkp::detail {

/// PFM ("PF", 3 channels): header "PF\n<w> <h>\n-1.0\n", little-endian floats, rows bottom to top.
void encodePfm(const Image& image, std::ostream& out);
/// Reads "PF" (RGB) and "Pf" (gray, replicated to RGB), either byte order. Throws InputError.
Image decodePfm(std::span<const uint8_t> bytes, const std::string& name);

/// OpenEXR scanline image, FLOAT channels B,G,R, ZIP compression, via tinyexr.
/// `metadata`: (name, value) string attributes of the header.
/// `layers`: more channels, "<layer>.<channel>", every channel sorted by name as OpenEXR keeps them.
void encodeExr(const Image& image, std::ostream& out, const std::string& name,
               const std::vector<std::pair<std::string, std::string>>& metadata = {},
               const std::vector<ImageLayer>& layers = {});
/// The planes of the EXR channels whose names start with `prefix` ("albedo."), by the rest of the name.
std::vector<std::pair<std::string, std::vector<float>>> decodeExrChannels(std::span<const uint8_t> bytes, const std::string& name,
                                                                          const std::string& prefix, std::uint32_t& width,
                                                                          std::uint32_t& height);
/// Reads a single-part scanline EXR with R,G,B (or one Y) channels of HALF or FLOAT type.
Image decodeExr(std::span<const uint8_t> bytes, const std::string& name);

/// Radiance RGBE via stb_image_write: NaN and negatives -> 0, values above 1e38 clamped.
void encodeHdr(const Image& image, std::ostream& out, const std::string& name);
/// Reads "#?" Radiance files, FORMAT=32-bit_rle_rgbe, "-Y h +X w" or "+Y h +X w", flat or
/// run-length scanlines; divides by the header's EXPOSURE. Throws InputError.
Image decodeHdr(std::span<const uint8_t> bytes, const std::string& name);

}  // namespace vkp::detail
