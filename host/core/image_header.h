// What a PNG or JPEG file's header says, read without decoding: the format, the size in pixels,
// and whether the file's structure is complete (PNG: every chunk inside the data, up to IEND;
// JPEG: the markers up to the frame header, and an end-of-image marker). For messages that name
// the real problem where stb_image would only say "unknown image type" (a size beyond its limits)
// or give a terse or empty reason (a truncated file).
#pragma once
#include <cstdint>
#include <span>
#include <string>

namespace vkp {

struct ImageHeader {
    std::string format;          ///< "PNG", "JPEG", or empty: neither signature
    std::uint32_t width = 0;     ///< pixels; 0 when the header does not give it
    std::uint32_t height = 0;
    std::string problem;         ///< empty, or one clause: what is truncated or malformed, and where
};

/// The header of a PNG (signature, IHDR, then the chunk list) or a JPEG (SOI, the segments up to a
/// start-of-frame marker, an EOI marker after it). Never throws; reads only inside bytes.
ImageHeader readImageHeader(std::span<const std::uint8_t> bytes);

}  // namespace vkp
