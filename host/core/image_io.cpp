#include "core/image_io.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/image_formats.h"
#include "core/input_file.h"
#include "core/tonemap.h"

namespace vkp {
namespace fs = std::filesystem;

namespace {

constexpr const char* kSupported = "supported: .png .exr .pfm .hdr";

void writeToStream(void* context, void* data, int size) {
    static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

/// stb and tinyexr index pixels and bytes with int.
void checkIntSized(const Image& image, const std::string& name, const char* format) {
    if (image.pixelCount() > size_t(INT_MAX) / 16) {
        throw InputError(name + ": image " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " is too large for " + format);
    }
}

void encodePng(const Image& image, const WriteOptions& options, std::ostream& out, const std::string& name) {
    const std::vector<uint8_t> srgb = toSrgb8(image, options.exposure);
    const int w = int(image.width), h = int(image.height);
    if (!stbi_write_png_to_func(writeToStream, &out, w, h, 3, srgb.data(), 3 * w)) {
        throw InputError(name + ": cannot encode PNG");
    }
}

/// CRC-32 of PNG chunks (ISO 3309 / ITU-T V.42, the PNG specification's Annex D).
std::uint32_t pngCrc(const std::string& bytes) {
    std::uint32_t c = 0xffffffffu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xffffffffu;
}

void putBigEndian(std::string& s, std::uint32_t v) {
    for (int k = 3; k >= 0; --k) s.push_back(char((v >> (8 * k)) & 0xffu));
}

/// `png` with one tEXt chunk per metadata entry after IHDR (8-byte signature + 25-byte IHDR).
std::string withPngText(std::string png, const std::vector<std::pair<std::string, std::string>>& metadata) {
    std::string chunks;
    for (const auto& [key, value] : metadata) {
        const std::string body = "tEXt" + key + std::string(1, '\0') + value;
        putBigEndian(chunks, std::uint32_t(body.size() - 4));
        chunks += body;
        putBigEndian(chunks, pngCrc(body));
    }
    png.insert(33, chunks);
    return png;
}

/// Radiance HDR with "name=value" header lines after the signature line.
std::string withHdrLines(std::string hdr, const std::vector<std::pair<std::string, std::string>>& metadata) {
    std::string lines;
    for (const auto& [key, value] : metadata) lines += key + "=" + value + "\n";
    hdr.insert(hdr.find('\n') + 1, lines);
    return hdr;
}

}  // namespace

ImageFormat imageFormatFromPath(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".png") return ImageFormat::Png;
    if (ext == ".exr") return ImageFormat::Exr;
    if (ext == ".pfm") return ImageFormat::Pfm;
    if (ext == ".hdr") return ImageFormat::Hdr;
    if (ext.empty()) throw InputError(path.string() + ": no image file extension (" + kSupported + ")");
    throw InputError(path.string() + ": unknown image extension '" + path.extension().string() + "' (" +
                     kSupported + ")");
}

const char* imageFormatExtension(ImageFormat format) {
    switch (format) {
        case ImageFormat::Png: return ".png";
        case ImageFormat::Exr: return ".exr";
        case ImageFormat::Pfm: return ".pfm";
        case ImageFormat::Hdr: return ".hdr";
    }
    return "";
}

void encodeImage(const Image& image, ImageFormat format, const WriteOptions& options, std::ostream& out,
                 const std::string& name) {
    image.checkConsistent();
    if (image.empty()) throw std::invalid_argument(name + ": cannot write an empty image");
    if (!options.metadata.empty() && (format == ImageFormat::Png || format == ImageFormat::Hdr)) {
        std::ostringstream plain;
        WriteOptions without = options;
        without.metadata.clear();
        encodeImage(image, format, without, plain, name);
        out << (format == ImageFormat::Png ? withPngText(plain.str(), options.metadata) : withHdrLines(plain.str(), options.metadata));
        return;
    }
    switch (format) {
        case ImageFormat::Png:
            checkIntSized(image, name, "PNG");
            encodePng(image, options, out, name);
            return;
        case ImageFormat::Exr:
            checkIntSized(image, name, "EXR");
            detail::encodeExr(image, out, name, options.metadata, options.layers);
            return;
        case ImageFormat::Pfm: detail::encodePfm(image, out); return;
        case ImageFormat::Hdr:
            checkIntSized(image, name, "Radiance HDR");
            detail::encodeHdr(image, out, name);
            return;
    }
}

fs::path layerFilePath(const fs::path& image, const std::string& layer) {
    const ImageFormat format = imageFormatFromPath(image);
    fs::path p = image;
    p.replace_filename(image.stem().string() + "." + layer +
                       (format == ImageFormat::Png ? std::string(".pfm") : image.extension().string()));
    return p;
}

void writeImages(const Image& image, const std::vector<fs::path>& paths, const WriteOptions& options,
                 std::vector<AtomicWrite> more) {
    std::vector<AtomicWrite> files;
    // Layers of the formats without them, as images of their own (a one-channel layer replicated).
    auto layerImage = [](const ImageLayer& layer) {
        Image img = layer.values;
        if (layer.channels.size() == 1)
            for (std::size_t i = 0; i < img.pixelCount(); ++i) img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = img.rgb[3 * i];
        return img;
    };
    WriteOptions plain = options;
    plain.layers.clear();
    for (const fs::path& p : paths) {
        const ImageFormat format = imageFormatFromPath(p);
        const bool own = format == ImageFormat::Exr;
        files.push_back({p, [&image, &options, &plain, own, format, p](std::ostream& out) {
                             encodeImage(image, format, own ? options : plain, out, p.string());
                         }});
        if (own) continue;
        for (const ImageLayer& layer : options.layers) {
            const fs::path lp = layerFilePath(p, layer.name);
            const ImageFormat lf = imageFormatFromPath(lp);
            files.push_back({lp, [&layer, &plain, &layerImage, lf, lp](std::ostream& out) {
                                 WriteOptions linear = plain;
                                 linear.exposure = 0.0;
                                 encodeImage(layerImage(layer), lf, linear, out, lp.string());
                             }});
        }
    }
    for (AtomicWrite& m : more) files.push_back(std::move(m));
    writeFilesAtomic(files);
}

void writeImage(const Image& image, const fs::path& path, const WriteOptions& options) {
    writeImages(image, {path}, options);
}

Image readImageLayer(const fs::path& path, const std::string& layer) {
    if (imageFormatFromPath(path) != ImageFormat::Exr)
        throw InputError(path.string() + ": layers are read from EXR files only (layer " + layer + ")");
    const std::vector<uint8_t> bytes = readInputBytes(path);
    std::uint32_t w = 0, h = 0;
    const auto channels = detail::decodeExrChannels(bytes, path.string(), layer + ".", w, h);
    if (channels.empty()) throw InputError(path.string() + ": no layer " + layer + " (no channel " + layer + ".*)");
    // R,G,B or X,Y,Z in that order; one channel replicated.
    std::vector<const std::vector<float>*> planes;
    for (const char* order : {"RGB", "XYZ"})
        if (planes.empty()) {
            std::vector<const std::vector<float>*> found;
            for (int k = 0; k < 3; ++k)
                for (const auto& [name, values] : channels)
                    if (name == std::string(1, order[k])) found.push_back(&values);
            if (found.size() == 3) planes = found;
        }
    if (planes.empty() && channels.size() == 1) planes = {&channels[0].second, &channels[0].second, &channels[0].second};
    if (planes.empty()) throw InputError(path.string() + ": layer " + layer + " is neither R,G,B nor X,Y,Z nor one channel");
    Image img(w, h);
    for (std::size_t i = 0; i < img.pixelCount(); ++i)
        for (int k = 0; k < 3; ++k) img.rgb[3 * i + std::size_t(k)] = (*planes[std::size_t(k)])[i];
    return img;
}

void checkOutputPath(const fs::path& path) {
    (void)imageFormatFromPath(path);
    checkCanCreateFile(path);
}

Image decodeImage(std::span<const uint8_t> bytes, ImageFormat format, const std::string& name) {
    switch (format) {
        case ImageFormat::Pfm: return detail::decodePfm(bytes, name);
        case ImageFormat::Exr: return detail::decodeExr(bytes, name);
        case ImageFormat::Hdr: return detail::decodeHdr(bytes, name);
        case ImageFormat::Png: break;
    }
    throw InputError(name + ": reading PNG is not supported (it is display-encoded; use .exr, .pfm or .hdr)");
}

Image readImage(const fs::path& path) {
    const ImageFormat format = imageFormatFromPath(path);
    if (format == ImageFormat::Png) return decodeImage({}, format, path.string());  // throws
    const std::vector<uint8_t> bytes = readInputBytes(path);
    return decodeImage(bytes, format, path.string());
}

}  // namespace vkp
