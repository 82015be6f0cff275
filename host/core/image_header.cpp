#include "core/image_header.h"

#include <algorithm>

namespace vkp {

namespace {

std::uint32_t be32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | std::uint32_t(p[3]);
}

/// A chunk type as text, bytes outside letters shown as '?'.
std::string chunkType(const std::uint8_t* p) {
    std::string t;
    for (int i = 0; i < 4; ++i) {
        const char c = static_cast<char>(p[i]);
        t += ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z')) ? c : '?';
    }
    return t;
}

ImageHeader readPng(std::span<const std::uint8_t> b) {
    ImageHeader h;
    h.format = "PNG";
    const std::size_t n = b.size();
    if (n < 33 || chunkType(b.data() + 12) != "IHDR") {
        h.problem = n < 33 ? "truncated: " + std::to_string(n) + " bytes, the signature and IHDR chunk need 33"
                           : "the first chunk is not IHDR";
        return h;
    }
    h.width = be32(b.data() + 16);
    h.height = be32(b.data() + 20);
    // The chunk list: length (4), type (4), data, CRC (4), until IEND.
    std::size_t at = 8;
    for (std::size_t index = 0;; ++index) {
        if (at + 8 > n) {
            h.problem = "truncated: the data ends at byte " + std::to_string(n) + " before the IEND chunk (after " +
                        std::to_string(index) + " chunks)";
            return h;
        }
        const std::uint64_t length = be32(b.data() + at);
        const std::string type = chunkType(b.data() + at + 4);
        if (length > 0x7fffffffu) {
            h.problem = "chunk " + std::to_string(index) + " (" + type + ") at byte " + std::to_string(at) +
                        " has a length of " + std::to_string(length) + " (at most 2^31 - 1)";
            return h;
        }
        if (at + 12 + length > n) {
            h.problem = "truncated: chunk " + std::to_string(index) + " (" + type + ") at byte " + std::to_string(at) +
                        " needs " + std::to_string(12 + length) + " bytes, the data ends at byte " + std::to_string(n);
            return h;
        }
        if (type == "IEND") return h;
        at += 12 + static_cast<std::size_t>(length);
    }
}

/// SOF0-SOF15 but DHT (C4), JPG (C8) and DAC (CC).
bool isFrameHeader(std::uint8_t marker) { return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC; }

ImageHeader readJpeg(std::span<const std::uint8_t> b) {
    ImageHeader h;
    h.format = "JPEG";
    const std::size_t n = b.size();
    std::size_t at = 2;
    for (;;) {
        while (at < n && b[at] == 0xFF && at + 1 < n && b[at + 1] == 0xFF) ++at;  // fill bytes
        if (at + 4 > n) {
            h.problem = "truncated: the data ends at byte " + std::to_string(n) + " before the frame header (SOF)";
            return h;
        }
        if (b[at] != 0xFF) {
            h.problem = "no marker at byte " + std::to_string(at) + " before the frame header (SOF)";
            return h;
        }
        const std::uint8_t marker = b[at + 1];
        const std::size_t length = std::size_t(b[at + 2]) << 8 | b[at + 3];
        if (length < 2 || at + 2 + length > n) {
            h.problem = "truncated: the segment at byte " + std::to_string(at) + " needs " + std::to_string(2 + length) +
                        " bytes, the data ends at byte " + std::to_string(n);
            return h;
        }
        if (isFrameHeader(marker)) {
            if (length < 7) {
                h.problem = "the frame header at byte " + std::to_string(at) + " is too short";
                return h;
            }
            h.height = std::uint32_t(b[at + 5]) << 8 | b[at + 6];
            h.width = std::uint32_t(b[at + 7]) << 8 | b[at + 8];
            at += 2 + length;
            break;
        }
        at += 2 + length;
    }
    // The segments and scans after the frame header, up to the end-of-image marker (FF D9). A second
    // frame header is refused: baseline and progressive JPEGs have one (several make a
    // hierarchical JPEG, which stb_image does not decode), and Debian's stb_image (2.27, git
    // 2022-09-08) reads out of bounds on a progressive file with two (found by tools/fuzz.sh).
    for (;;) {
        if (at + 2 > n) {
            h.problem = "truncated: no end-of-image marker (FF D9) after the frame header";
            return h;
        }
        if (b[at] != 0xFF) {  // extraneous bytes before a marker: skipped, as libjpeg and stb_image do
            ++at;
            continue;
        }
        const std::uint8_t marker = b[at + 1];
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0xD9) return h;  // end of image
        if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {  // restart markers, TEM: no length
            at += 2;
            continue;
        }
        if (isFrameHeader(marker)) {
            h.problem = "a second frame header (SOF) at byte " + std::to_string(at) + " (hierarchical JPEG is not supported)";
            return h;
        }
        if (at + 4 > n) {
            h.problem = "truncated: the data ends at byte " + std::to_string(n) + " inside the marker at byte " + std::to_string(at);
            return h;
        }
        const std::size_t length = std::size_t(b[at + 2]) << 8 | b[at + 3];
        if (length < 2 || at + 2 + length > n) {
            h.problem = "truncated: the segment at byte " + std::to_string(at) + " needs " + std::to_string(2 + length) +
                        " bytes, the data ends at byte " + std::to_string(n);
            return h;
        }
        at += 2 + length;
        if (marker == 0xDA) {  // start of scan: entropy-coded data up to the next marker
            while (at < n && !(b[at] == 0xFF && at + 1 < n && b[at + 1] != 0x00 && !(b[at + 1] >= 0xD0 && b[at + 1] <= 0xD7))) {
                at += (b[at] == 0xFF) ? 2 : 1;  // FF 00 is a stuffed FF, FF D0-D7 a restart marker
            }
        }
    }
}

}  // namespace

ImageHeader readImageHeader(std::span<const std::uint8_t> bytes) {
    static const std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() >= 8 && std::equal(kPng, kPng + 8, bytes.begin())) return readPng(bytes);
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return readJpeg(bytes);
    return {};
}

}  // namespace vkp
