#include "scene/ldr_image.h"

#include <algorithm>

#include <stb/stb_image.h>

#include "core/image_header.h"

namespace vkp {

namespace {
/// stb_image's reason, printable ASCII only (it may quote bytes of the file, e.g. a PNG chunk type).
std::string stbReason() {
    const char* r = stbi_failure_reason();
    std::string out = r && *r ? "corrupt data (stb_image: \"" + std::string(r) + "\")" : "corrupt data (stb_image gives no reason)";
    for (char& c : out) {
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    }
    return out;
}
}  // namespace

std::string decodeLdrImage(std::span<const unsigned char> bytes, std::uint32_t maxSide, Rgba8Image& out) {
    if (bytes.empty()) return "no image data";
    if (bytes.size() > 0x7fffffffu) return "too large for the image decoder (more than 2 GiB)";
    const int size = static_cast<int>(bytes.size());
    auto sizeProblem = [&](std::uint64_t w, std::uint64_t h, const std::string& format) {
        return format + " of " + std::to_string(w) + "x" + std::to_string(h) + " pixels: each side must be in [1, " +
               std::to_string(maxSide) + "]";
    };
    // The header first: stb_image says "unknown image type" for a size beyond its own limits and
    // little or nothing for a truncated file.
    const ImageHeader header = readImageHeader(bytes);
    if (!header.format.empty()) {
        if (!header.problem.empty()) return "cannot decode the " + header.format + ": " + header.problem;
        if (header.width == 0 || header.height == 0 || header.width > maxSide || header.height > maxSide)
            return sizeProblem(header.width, header.height, header.format);
    }
    const std::string format = header.format.empty() ? std::string("image") : header.format;
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes.data(), size, &w, &h, &comp))
        return "cannot decode the " + format + " (PNG or JPEG expected): " + stbReason();
    if (w <= 0 || h <= 0 || std::uint32_t(w) > maxSide || std::uint32_t(h) > maxSide)
        return sizeProblem(std::uint64_t(std::max(w, 0)), std::uint64_t(std::max(h, 0)), format);
    unsigned char* pixels = stbi_load_from_memory(bytes.data(), size, &w, &h, &comp, 4);
    if (!pixels) return "cannot decode the " + format + ": " + stbReason();
    out.width = std::uint32_t(w);
    out.height = std::uint32_t(h);
    out.rgba.assign(pixels, pixels + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    stbi_image_free(pixels);
    return "";
}

}  // namespace vkp
