// Portable Float Map (http://www.pauldebevec.com/Research/HDR/PFM/): a text header, then raw
// 32-bit floats, rows from the BOTTOM of the image to the top; a negative scale means little endian.
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <ostream>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/image_formats.h"

namespace vkp::detail {
namespace {

uint32_t loadU32(const uint8_t* p, bool littleEndian) {
    if (littleEndian) return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    return uint32_t(p[3]) | uint32_t(p[2]) << 8 | uint32_t(p[1]) << 16 | uint32_t(p[0]) << 24;
}

bool isSpace(uint8_t c) { return std::isspace(c) != 0; }

/// Header tokenizer: every token must be preceded by at least one white-space character.
class HeaderReader {
public:
    HeaderReader(std::span<const uint8_t> bytes, const std::string& name) : b_(bytes), name_(name) {}

    [[noreturn]] void fail(const std::string& what) const { throw InputError(name_ + ": " + what); }

    std::string_view token(const char* what) {
        const size_t start = pos_;
        while (pos_ < b_.size() && isSpace(b_[pos_])) ++pos_;
        if (pos_ >= b_.size()) fail(std::string("truncated PFM header: missing ") + what);
        if (pos_ == start) fail(std::string("malformed PFM header: no white space before ") + what);
        const size_t begin = pos_;
        while (pos_ < b_.size() && !isSpace(b_[pos_]) && pos_ - begin < 64) ++pos_;
        return {reinterpret_cast<const char*>(b_.data()) + begin, pos_ - begin};
    }

    uint32_t dimension(const char* what) {
        const std::string_view t = token(what);
        uint32_t v = 0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (ec != std::errc() || end != t.data() + t.size() || v == 0) {
            fail("malformed PFM header: " + std::string(what) + " '" + std::string(t) + "' is not a positive integer");
        }
        return v;
    }

    double scale() {
        const std::string_view t = token("scale");
        double v = 0.0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v) || v == 0.0) {
            fail("malformed PFM header: scale '" + std::string(t) + "' is not a non-zero number");
        }
        return v;
    }

    /// The single white-space character that ends the header; returns the offset of the pixels.
    size_t endOfHeader() {
        if (pos_ >= b_.size()) fail("truncated PFM file: no pixel data");
        if (!isSpace(b_[pos_])) fail("malformed PFM header: no white space after the scale");
        return pos_ + 1;
    }

private:
    std::span<const uint8_t> b_;
    const std::string& name_;
    size_t pos_ = 2;  // after the magic
};

}  // namespace

void encodePfm(const Image& image, std::ostream& out) {
    out << "PF\n" << image.width << ' ' << image.height << "\n-1.0\n";
    std::vector<char> row(size_t(image.width) * 12);
    for (uint32_t fileRow = 0; fileRow < image.height; ++fileRow) {
        const uint32_t y = image.height - 1 - fileRow;  // bottom row first
        const float* src = image.rgb.data() + image.offset(0, y);
        for (size_t i = 0; i < size_t(image.width) * 3; ++i) {
            const uint32_t u = std::bit_cast<uint32_t>(src[i]);
            for (int k = 0; k < 4; ++k) row[4 * i + size_t(k)] = char(uint8_t(u >> (8 * k)));
        }
        out.write(row.data(), std::streamsize(row.size()));
    }
}

Image decodePfm(std::span<const uint8_t> bytes, const std::string& name) {
    if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f')) {
        throw InputError(name + ": not a PFM file (it does not start with \"PF\" or \"Pf\")");
    }
    const size_t channels = bytes[1] == 'F' ? 3 : 1;
    HeaderReader header(bytes, name);
    const uint32_t width = header.dimension("width");
    const uint32_t height = header.dimension("height");
    const bool littleEndian = header.scale() < 0.0;
    const size_t dataBegin = header.endOfHeader();

    const size_t available = bytes.size() - dataBegin;
    const uint64_t pixels = uint64_t(width) * height;  // < 2^64: both factors < 2^32
    const size_t bytesPerPixel = 4 * channels;
    if (pixels > available / bytesPerPixel) {
        header.fail("truncated PFM file: " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                    std::to_string(pixels * bytesPerPixel) + " bytes of pixels, found " + std::to_string(available));
    }
    if (available != pixels * bytesPerPixel) {
        header.fail("malformed PFM file: " + std::to_string(available - pixels * bytesPerPixel) +
                    " unexpected bytes after the pixel data");
    }

    Image image(width, height);
    const uint8_t* p = bytes.data() + dataBegin;
    for (uint32_t fileRow = 0; fileRow < height; ++fileRow) {
        float* dst = image.rgb.data() + image.offset(0, height - 1 - fileRow);
        for (uint32_t x = 0; x < width; ++x) {
            for (size_t c = 0; c < 3; ++c) {
                const size_t src = channels == 3 ? c : 0;
                dst[3 * x + c] = std::bit_cast<float>(loadU32(p + 4 * src, littleEndian));
            }
            p += bytesPerPixel;
        }
    }
    return image;
}

}  // namespace vkp::detail
