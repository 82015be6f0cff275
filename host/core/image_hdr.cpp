// Radiance RGBE (.hdr, Greg Ward, "Real Pixels", Graphics Gems II, 1991). Written with
// stb_image_write; read here instead of with stb_image, whose RLE decoder (2022-09 release) loops
// forever on a zero run count, which every file truncated inside a run-length scanline produces.
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/image_formats.h"

namespace vkp::detail {
namespace {

void writeToStream(void* context, void* data, int size) {
    static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

class HdrReader {
public:
    HdrReader(std::span<const uint8_t> bytes, const std::string& name) : b_(bytes), name_(name) {}

    [[noreturn]] void fail(const std::string& what) const { throw InputError(name_ + ": " + what); }

    /// The next header line without its '\n'; fails at the end of the data.
    std::string_view line() {
        const size_t begin = pos_;
        while (pos_ < b_.size() && b_[pos_] != '\n') ++pos_;
        if (pos_ >= b_.size()) fail("truncated Radiance HDR header");
        return {reinterpret_cast<const char*>(b_.data()) + begin, pos_++ - begin};
    }
    size_t remaining() const { return b_.size() - pos_; }
    uint8_t byte() {
        if (pos_ >= b_.size()) fail("truncated Radiance HDR pixel data");
        return b_[pos_++];
    }

private:
    std::span<const uint8_t> b_;
    const std::string& name_;
    size_t pos_ = 0;
};

/// One scanline of `width` RGBE pixels into rgbe[4 * width]: flat, or the "new" run-length form
/// (2, 2, width >> 8, width & 255, then each component run-length coded separately).
void readScanline(HdrReader& in, uint32_t width, std::vector<uint8_t>& rgbe) {
    uint8_t head[4];
    for (uint8_t& h : head) h = in.byte();
    const bool rle = width >= 8 && width <= 0x7fff && head[0] == 2 && head[1] == 2 && (head[2] & 0x80) == 0;
    if (!rle) {
        std::copy(head, head + 4, rgbe.begin());
        for (size_t i = 4; i < 4 * size_t(width); ++i) rgbe[i] = in.byte();
        return;
    }
    if ((uint32_t(head[2]) << 8 | head[3]) != width) in.fail("bad Radiance HDR scanline: length mismatch");
    for (size_t c = 0; c < 4; ++c) {
        for (uint32_t x = 0; x < width;) {
            uint32_t count = in.byte();
            const bool run = count > 128;
            if (run) count -= 128;
            if (count == 0 || count > width - x) in.fail("bad Radiance HDR run-length data");
            const uint8_t value = run ? in.byte() : 0;
            for (uint32_t k = 0; k < count; ++k, ++x) rgbe[4 * size_t(x) + c] = run ? value : in.byte();
        }
    }
}

}  // namespace

void encodeHdr(const Image& image, std::ostream& out, const std::string& name) {
    // RGBE stores no sign, NaN or inf, and its exponent byte overflows at 2^127.
    constexpr float kMaxRgbe = 1.0e38f;
    std::vector<float> data(image.rgb.size());
    std::transform(image.rgb.begin(), image.rgb.end(), data.begin(), [&](float v) {
        return v > 0.0f ? std::min(v, kMaxRgbe) : 0.0f;  // NaN fails v > 0
    });
    if (!stbi_write_hdr_to_func(writeToStream, &out, int(image.width), int(image.height), 3, data.data())) {
        throw InputError(name + ": cannot encode Radiance HDR");
    }
}

Image decodeHdr(std::span<const uint8_t> bytes, const std::string& name) {
    if (bytes.size() < 2 || bytes[0] != '#' || bytes[1] != '?') {
        throw InputError(name + ": not a Radiance HDR file (no \"#?RADIANCE\" or \"#?RGBE\" signature)");
    }
    HdrReader in(bytes, name);
    (void)in.line();  // the signature line
    double exposure = 1.0;  // product of EXPOSURE= lines: stored value = radiance * exposure
    for (std::string_view l = in.line(); !l.empty(); l = in.line()) {
        if (l.starts_with("FORMAT=") && l != "FORMAT=32-bit_rle_rgbe") {
            in.fail("unsupported Radiance HDR format '" + std::string(l.substr(7)) + "' (only 32-bit_rle_rgbe)");
        }
        if (l.starts_with("EXPOSURE=")) {
            const double e = std::strtod(std::string(l.substr(9)).c_str(), nullptr);
            if (!(e > 0.0) || !std::isfinite(e)) in.fail("bad Radiance HDR EXPOSURE value");
            exposure *= e;
        }
    }
    // Resolution: "-Y <height> +X <width>" (rows top to bottom) or "+Y <height> +X <width>" (bottom up).
    const std::string res(in.line());
    char ySign = 0;
    unsigned long h = 0, w = 0;
    int consumed = 0;
    if (std::sscanf(res.c_str(), "%cY %lu +X %lu%n", &ySign, &h, &w, &consumed) != 3 ||
        size_t(consumed) != res.size() || (ySign != '-' && ySign != '+')) {
        in.fail("unsupported Radiance HDR resolution line '" + res + "' (expected \"-Y <height> +X <width>\")");
    }
    if (w == 0 || h == 0 || w > 0xffffffffUL || h > 0xffffffffUL) in.fail("bad Radiance HDR image size");
    // Each scanline takes at least 4 bytes, and 4 + 8 * ceil(w / 127) when run-length coded: reject
    // sizes the file cannot hold before allocating.
    const bool rleWidth = w >= 8 && w <= 0x7fff;
    const size_t minLine = rleWidth ? 4 + 8 * ((w + 126) / 127) : 4 * size_t(w);
    if (h > in.remaining() / minLine) in.fail("truncated Radiance HDR pixel data");

    Image image{uint32_t(w), uint32_t(h)};
    std::vector<uint8_t> rgbe(4 * size_t(w));
    const float invExposure = float(1.0 / exposure);
    for (uint32_t row = 0; row < h; ++row) {
        readScanline(in, uint32_t(w), rgbe);
        const uint32_t y = ySign == '-' ? row : uint32_t(h) - 1 - row;
        float* dst = image.rgb.data() + image.offset(0, y);
        for (size_t x = 0; x < w; ++x) {
            const uint8_t* p = &rgbe[4 * x];
            // Same convention as stb_image: value = mantissa * 2^(exponent - 136), exponent 0 -> 0.
            const float f = p[3] == 0 ? 0.0f : std::ldexp(1.0f, int(p[3]) - (128 + 8)) * invExposure;
            for (size_t c = 0; c < 3; ++c) dst[3 * x + c] = float(p[c]) * f;
        }
    }
    return image;
}

}  // namespace vkp::detail
