// Fuzz target: the image decoders on arbitrary bytes, chosen by the bytes' signature as vkpath
// chooses by file: PFM ("PF"/"Pf"), OpenEXR (magic 76 2f 31 01), Radiance HDR ("#?"), else the
// PNG/JPEG header reader (core/image_header.h) and, where it finds a plausible image, stb_image as
// the glTF loader calls it. Bad input may only end in InputError.
#include <stb/stb_image.h>

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/errors.h"
#include "core/image_header.h"
#include "core/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> bytes(data, size);
    auto starts = [&](std::initializer_list<std::uint8_t> sig) {
        if (size < sig.size()) return false;
        std::size_t i = 0;
        for (std::uint8_t b : sig)
            if (data[i++] != b) return false;
        return true;
    };
    try {
        if (starts({'P', 'F'}) || starts({'P', 'f'})) (void)vkp::decodeImage(bytes, vkp::ImageFormat::Pfm, "fuzz.pfm");
        else if (starts({0x76, 0x2f, 0x31, 0x01})) (void)vkp::decodeImage(bytes, vkp::ImageFormat::Exr, "fuzz.exr");
        else if (starts({'#', '?'})) (void)vkp::decodeImage(bytes, vkp::ImageFormat::Hdr, "fuzz.hdr");
        else {
            const vkp::ImageHeader h = vkp::readImageHeader(bytes);
            // The glTF loader's limits (gltf_document.cpp): a header without a problem, each side <= 16384.
            if (!h.format.empty() && h.problem.empty() && h.width > 0 && h.height > 0 && h.width <= 4096 && h.height <= 4096) {
                int w = 0, hh = 0, comp = 0;
                if (stbi_info_from_memory(data, int(size), &w, &hh, &comp) && w > 0 && hh > 0 && w <= 4096 && hh <= 4096) {
                    unsigned char* pixels = stbi_load_from_memory(data, int(size), &w, &hh, &comp, 4);
                    stbi_image_free(pixels);
                }
            }
        }
    } catch (const vkp::InputError&) {
    }
    return 0;
}
