// OpenEXR through tinyexr (Debian's libtinyexr; the implementation lives in the shared library).
// EXR stores channels sorted by name (B, G, R) and scanlines top to bottom (y grows downwards).
#include <tinyexr.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "core/errors.h"
#include "core/exr_guards.h"
#include "core/image_formats.h"

namespace vkp::detail {
namespace {

using exr::ExrError;
using exr::HeaderGuard;
using exr::ImageGuard;

[[noreturn]] void fail(const std::string& name, const std::string& what) { throw InputError(name + ": " + what); }

}  // namespace

void encodeExr(const Image& image, std::ostream& out, const std::string& name,
               const std::vector<std::pair<std::string, std::string>>& metadata, const std::vector<ImageLayer>& layers) {
    const size_t n = image.pixelCount();
    // Every channel as a plane: R, G, B of the image, then each layer's; written sorted by name
    // (OpenEXR's order: B, G, R, albedo.B, ...).
    struct Plane {
        std::string name;
        std::vector<float> values;
    };
    std::vector<Plane> planes;
    auto addPlane = [&](std::string channel, const Image& from, size_t k) {
        Plane p{std::move(channel), std::vector<float>(n)};
        for (size_t i = 0; i < n; ++i) p.values[i] = from.rgb[3 * i + k];
        planes.push_back(std::move(p));
    };
    const char* rgb[3] = {"R", "G", "B"};
    for (size_t c = 0; c < 3; ++c) addPlane(rgb[c], image, c);
    for (const ImageLayer& layer : layers) {
        if (layer.values.width != image.width || layer.values.height != image.height || layer.channels.empty() ||
            layer.channels.size() > 3)
            throw std::invalid_argument(name + ": layer " + layer.name + " does not match the image");
        for (size_t c = 0; c < layer.channels.size(); ++c) addPlane(layer.name + "." + layer.channels[c], layer.values, c);
    }
    std::sort(planes.begin(), planes.end(), [](const Plane& a, const Plane& b) { return a.name < b.name; });
    const size_t count = planes.size();
    std::vector<unsigned char*> planePtrs(count);
    std::vector<EXRChannelInfo> channels(count);
    for (size_t c = 0; c < count; ++c) {
        if (planes[c].name.size() >= sizeof(channels[c].name))
            throw std::invalid_argument(name + ": EXR channel name too long: " + planes[c].name);
        std::memset(&channels[c], 0, sizeof(EXRChannelInfo));
        std::strcpy(channels[c].name, planes[c].name.c_str());
        planePtrs[c] = reinterpret_cast<unsigned char*>(planes[c].values.data());
    }
    std::vector<int> pixelTypes(count, TINYEXR_PIXELTYPE_FLOAT);
    std::vector<int> requestedTypes = pixelTypes;  // stored as 32-bit float, no conversion to half

    // Not HeaderGuard/ImageGuard: the arrays belong to us, FreeEXR* must not free them.
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = int(count);
    header.channels = channels.data();
    header.pixel_types = pixelTypes.data();
    header.requested_pixel_types = requestedTypes.data();
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;  // lossless
    std::vector<std::string> values;  // tinyexr wants mutable bytes
    for (const auto& m : metadata) values.push_back(m.second);
    std::vector<EXRAttribute> attributes(metadata.size());
    for (std::size_t k = 0; k < metadata.size(); ++k) {
        std::memset(&attributes[k], 0, sizeof(EXRAttribute));
        std::strncpy(attributes[k].name, metadata[k].first.c_str(), sizeof(attributes[k].name) - 1);
        std::strcpy(attributes[k].type, "string");
        attributes[k].value = reinterpret_cast<unsigned char*>(values[k].data());
        attributes[k].size = int(values[k].size());
    }
    header.num_custom_attributes = int(attributes.size());
    header.custom_attributes = attributes.empty() ? nullptr : attributes.data();

    EXRImage exr;
    InitEXRImage(&exr);
    exr.num_channels = int(count);
    exr.images = planePtrs.data();
    exr.width = int(image.width);
    exr.height = int(image.height);

    unsigned char* memory = nullptr;
    ExrError err;
    const size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &err.msg);
    if (size == 0 || memory == nullptr) {
        std::free(memory);
        throw InputError(name + ": cannot encode EXR: " + err.text(0));
    }
    out.write(reinterpret_cast<const char*>(memory), std::streamsize(size));
    std::free(memory);  // tinyexr allocates with malloc
}

std::vector<std::pair<std::string, std::vector<float>>> decodeExrChannels(std::span<const uint8_t> bytes, const std::string& name,
                                                                          const std::string& prefix, std::uint32_t& width,
                                                                          std::uint32_t& height) {
    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS)
        fail(name, "not an OpenEXR file (bad or missing magic number/version)");
    if (version.multipart || version.non_image || version.tiled) fail(name, "multi-part, deep and tiled EXR files are not supported");
    HeaderGuard header;
    ExrError err;
    int ret = ParseEXRHeaderFromMemory(&header.h, &version, bytes.data(), bytes.size(), &err.msg);
    if (ret != TINYEXR_SUCCESS) fail(name, "invalid or truncated EXR header: " + err.text(ret));
    for (int c = 0; c < header.h.num_channels; ++c) {
        const int type = header.h.pixel_types[c];
        if (type != TINYEXR_PIXELTYPE_HALF && type != TINYEXR_PIXELTYPE_FLOAT)
            fail(name, std::string("EXR channel '") + header.h.channels[c].name + "' is not of type half or float");
        header.h.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    }
    ImageGuard exr;
    exr.i.num_channels = header.h.num_channels;  // see decodeExr
    ret = LoadEXRImageFromMemory(&exr.i, &header.h, bytes.data(), bytes.size(), &err.msg);
    if (ret != TINYEXR_SUCCESS) {
        InitEXRImage(&exr.i);
        fail(name, "invalid or truncated EXR pixel data: " + err.text(ret));
    }
    if (exr.i.width <= 0 || exr.i.height <= 0 || exr.i.images == nullptr) fail(name, "EXR file has no pixels");
    width = uint32_t(exr.i.width);
    height = uint32_t(exr.i.height);
    const size_t n = size_t(width) * height;
    std::vector<std::pair<std::string, std::vector<float>>> out;
    for (int c = 0; c < header.h.num_channels; ++c) {
        const std::string channel = header.h.channels[c].name;
        if (channel.rfind(prefix, 0) != 0) continue;
        const float* plane = reinterpret_cast<const float*>(exr.i.images[c]);
        if (plane == nullptr) fail(name, "EXR file has no pixels");
        out.emplace_back(channel.substr(prefix.size()), std::vector<float>(plane, plane + n));
    }
    return out;
}

Image decodeExr(std::span<const uint8_t> bytes, const std::string& name) {
    EXRVersion version;
    int ret = ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size());
    if (ret != TINYEXR_SUCCESS) fail(name, "not an OpenEXR file (bad or missing magic number/version)");
    if (version.multipart || version.non_image) fail(name, "multi-part and deep EXR files are not supported");
    if (version.tiled) fail(name, "tiled EXR files are not supported");

    HeaderGuard header;
    ExrError err;
    ret = ParseEXRHeaderFromMemory(&header.h, &version, bytes.data(), bytes.size(), &err.msg);
    if (ret != TINYEXR_SUCCESS) fail(name, "invalid or truncated EXR header: " + err.text(ret));

    // Channel index for R, G, B; a single channel (e.g. Y) is read as gray.
    std::array<int, 3> index{-1, -1, -1};
    for (int c = 0; c < header.h.num_channels; ++c) {
        const std::string channel = header.h.channels[c].name;
        if (channel == "R") index[0] = c;
        if (channel == "G") index[1] = c;
        if (channel == "B") index[2] = c;
    }
    if (header.h.num_channels == 1) index = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
        if (index[size_t(k)] < 0) fail(name, std::string("EXR file has no '") + "RGB"[k] + "' channel");
        const int type = header.h.pixel_types[index[size_t(k)]];
        if (type != TINYEXR_PIXELTYPE_HALF && type != TINYEXR_PIXELTYPE_FLOAT) {
            fail(name, std::string("EXR channel '") + header.h.channels[index[size_t(k)]].name +
                 "' is not of type half or float");
        }
    }
    for (int c = 0; c < header.h.num_channels; ++c) {
        if (header.h.pixel_types[c] == TINYEXR_PIXELTYPE_HALF) {
            header.h.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
        }
    }

    ImageGuard exr;
    // tinyexr 1.0.1 frees the image itself when decoding fails, but sets num_channels only on
    // success and leaves the pointers dangling: preset num_channels so it frees every channel
    // array, and forget the pointers afterwards so ~ImageGuard does not free them twice.
    exr.i.num_channels = header.h.num_channels;
    ret = LoadEXRImageFromMemory(&exr.i, &header.h, bytes.data(), bytes.size(), &err.msg);
    if (ret != TINYEXR_SUCCESS) {
        InitEXRImage(&exr.i);
        fail(name, "invalid or truncated EXR pixel data: " + err.text(ret));
    }
    if (exr.i.width <= 0 || exr.i.height <= 0 || exr.i.images == nullptr) fail(name, "EXR file has no pixels");

    Image image{uint32_t(exr.i.width), uint32_t(exr.i.height)};
    const size_t n = image.pixelCount();
    for (size_t k = 0; k < 3; ++k) {
        const float* plane = reinterpret_cast<const float*>(exr.i.images[index[k]]);
        if (plane == nullptr) fail(name, "EXR file has no pixels");
        for (size_t i = 0; i < n; ++i) image.rgb[3 * i + k] = plane[i];
    }
    return image;
}

}  // namespace vkp::detail
