// Reading and writing images: the format is chosen by the file extension (case-insensitive).
//   .png  8-bit sRGB, tone mapped (exposure, clamp, sRGB OETF)       write only
//   .exr  OpenEXR, 32-bit float R,G,B, linear, ZIP compressed         write + read
//   .pfm  Portable Float Map "PF", little endian, linear              write + read
//   .hdr  Radiance RGBE, linear (~1% precision, no negatives)         write + read
// Every file is written atomically (core/atomic_file.h). Row 0 of an Image is the top row in
// every format.
#pragma once
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "core/image.h"

namespace vkp {

enum class ImageFormat { Png, Exr, Pfm, Hdr };

/// Options for writing an image.
struct WriteOptions {
    /// Exposure in stops: display-referred (PNG) output is multiplied by 2^exposure before
    /// clamping and sRGB encoding. Linear formats (EXR, PFM, HDR) store radiance unscaled.
    double exposure = 0.0;
    /// Text metadata, (name, value), e.g. ("vkpath.spp", "64"): EXR string attributes, PNG tEXt
    /// chunks (name: 1-79 Latin-1 characters), Radiance HDR header lines "name=value" (no newline
    /// in either). PFM has no place for it.
    std::vector<std::pair<std::string, std::string>> metadata;
    /// Feature layers (render/aov.h) written with the image: EXR keeps them as channels
    /// "<layer>.<channel>" of the same file; every other format writes each to layerFilePath (a
    /// one-channel layer replicated into R, G and B), all or none with the image.
    std::vector<ImageLayer> layers;
};

/// Where a layer of `image` goes in a format without layers: "<stem>.<layer><ext>" beside it
/// (out.pfm -> out.albedo.pfm), in PFM for a PNG image (out.png -> out.albedo.pfm: the values are
/// data, not display colours).
std::filesystem::path layerFilePath(const std::filesystem::path& image, const std::string& layer);

/// Reads layer `layer` of an EXR file written with it (e.g. "albedo": channels albedo.R,G,B;
/// "depth": its one channel, replicated into R, G and B). Throws InputError "<path>: ..." when the
/// file or the layer is missing or malformed.
Image readImageLayer(const std::filesystem::path& path, const std::string& layer);

/// The format for `path`'s extension (case-insensitive). Throws InputError
/// "<path>: unknown image extension '<ext>' (supported: .png .exr .pfm .hdr)" otherwise.
ImageFormat imageFormatFromPath(const std::filesystem::path& path);

/// The extension of a format, lower case with the dot (".png").
const char* imageFormatExtension(ImageFormat format);

/// Encodes `image` in `format` into `out` (no file involved). Throws std::invalid_argument for an
/// empty or inconsistent image or one too large for the format's library (a programming error);
/// `name` only labels error messages.
/// EXR/PFM store the floats exactly (NaN and inf included); HDR maps NaN and negatives to 0 and
/// values above 1e38 (+inf included) to 1e38; PNG: see WriteOptions::exposure and linearToSrgb8.
void encodeImage(const Image& image, ImageFormat format, const WriteOptions& options, std::ostream& out,
                 const std::string& name = "image");

/// Writes `image` to `path` in the format of its extension, atomically: on failure the previous
/// file (if any) is untouched and no temporary file is left. Throws InputError "<path>: ..." for an
/// unknown extension or an I/O failure.
void writeImage(const Image& image, const std::filesystem::path& path, const WriteOptions& options = {});

/// Writes `image` to every path of `paths` (format by extension) and the files of `more`, all or
/// none (core/atomic_file.h writeFilesAtomic): when one fails, none is replaced and no temporary
/// file is left. Throws InputError "<path>: ..." naming the first that failed.
void writeImages(const Image& image, const std::vector<std::filesystem::path>& paths, const WriteOptions& options,
                 std::vector<AtomicWrite> more = {});

/// Validates an output path before a long render: known extension, existing writable directory,
/// not a directory itself. Throws InputError "<path>: ..." (exit code 1) otherwise. Leaves no file.
void checkOutputPath(const std::filesystem::path& path);

/// Decodes an image file's bytes of the given format (.pfm, .exr or .hdr). Throws InputError
/// "<name>: <what is wrong>" for malformed, truncated or unsupported data, or for PNG (not
/// readable: it is display-encoded).
Image decodeImage(std::span<const uint8_t> bytes, ImageFormat format, const std::string& name);

/// Reads a .pfm, .exr or .hdr file into a linear Image (row 0 = top). Throws InputError
/// "<path>: <what is wrong>" if the file cannot be read or is malformed.
Image readImage(const std::filesystem::path& path);

}  // namespace vkp
