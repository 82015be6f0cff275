// A glTF image that cannot be used is one line "<file>: image <i>: <what is wrong>" that says what
// is wrong: a size beyond the limits (which stb_image reports as "unknown image type" beyond its
// own), a truncated PNG or JPEG (for which stb_image gives a terse or empty reason), corrupt data.
// The images are made here by stb_image_write, then changed.
#include <gtest/gtest.h>

#include <stb/stb_image_write.h>

#include <fstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/image_header.h"
#include "scene/gltf.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;
using namespace vkp;

void append(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

/// A w x h RGB gradient encoded as PNG or JPEG.
std::string encoded(bool png, int w = 16, int h = 16) {
    std::vector<unsigned char> rgb(std::size_t(w * h * 3));
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<unsigned char>(i * 7);
    std::string out;
    const int ok = png ? stbi_write_png_to_func(append, &out, w, h, 3, rgb.data(), w * 3)
                       : stbi_write_jpg_to_func(append, &out, w, h, 3, rgb.data(), 90);
    EXPECT_NE(ok, 0);
    return out;
}

void putBe(std::string& s, std::size_t at, std::uint32_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) s[at + std::size_t(i)] = char((v >> (8 * (bytes - 1 - i))) & 0xff);
}

/// A glTF file with one image (uri "<name>") whose bytes are `image`; returns the glTF file.
fs::path withImage(const std::string& name, const std::string& image) {
    const fs::path dir = test::scratchDir("gltf_image_errors");
    std::ofstream(dir / name, std::ios::binary) << image;
    const fs::path file = dir / (name + ".gltf");
    std::ofstream(file) << R"({"asset": {"version": "2.0"}, "images": [{"uri": ")" + name + R"("}]})";
    return file;
}

/// The message of loading file, which must fail.
std::string errorOf(const fs::path& file) {
    try {
        (void)loadSceneGltf(file);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << file << ": accepted";
    return {};
}

TEST(GltfImageErrors, TheImagesLoadUnchanged) {
    EXPECT_NO_THROW((void)loadSceneGltf(withImage("ok.png", encoded(true))));
    EXPECT_NO_THROW((void)loadSceneGltf(withImage("ok.jpg", encoded(false))));
    const std::string png = encoded(true, 7, 5);
    const ImageHeader h = readImageHeader({reinterpret_cast<const std::uint8_t*>(png.data()), png.size()});
    EXPECT_EQ(h.format, "PNG");
    EXPECT_EQ(h.width, 7u);
    EXPECT_EQ(h.height, 5u);
    EXPECT_EQ(h.problem, "");
    const std::string jpg = encoded(false, 7, 5);
    const ImageHeader j = readImageHeader({reinterpret_cast<const std::uint8_t*>(jpg.data()), jpg.size()});
    EXPECT_EQ(j.format, "JPEG");
    EXPECT_EQ(j.width, 7u);
    EXPECT_EQ(j.height, 5u);
    EXPECT_EQ(j.problem, "");
}

TEST(GltfImageErrors, SizesBeyondTheLimitsAreSaidAsSizes) {
    // 2^25 is beyond stb_image's own limit (2^24), 20000 beyond vkpath's (16384).
    for (const std::uint32_t width : {20000u, 1u << 25}) {
        std::string png = encoded(true);
        putBe(png, 16, width, 4);  // IHDR width
        const fs::path file = withImage("wide-" + std::to_string(width) + ".png", png);
        EXPECT_EQ(errorOf(file), file.string() + ": image 0: PNG of " + std::to_string(width) +
                                     "x16 pixels: each side must be in [1, 16384]");
    }
    std::string jpg = encoded(false);
    const std::size_t sof = jpg.find("\xff\xc0");
    ASSERT_NE(sof, std::string::npos);
    putBe(jpg, sof + 5, 20000, 2);  // frame height
    const fs::path file = withImage("tall.jpg", jpg);
    EXPECT_EQ(errorOf(file), file.string() + ": image 0: JPEG of 16x20000 pixels: each side must be in [1, 16384]");
}

TEST(GltfImageErrors, TruncatedImagesSayTruncated) {
    for (const bool png : {true, false}) {
        const std::string whole = encoded(png);
        const std::string format = png ? "PNG" : "JPEG";
        // Every length from the signature to one byte short (JPEG: up to the end-of-image marker).
        for (std::size_t n = png ? 8 : 3; n + (png ? 1 : 2) <= whole.size(); ++n) {
            const fs::path file = withImage(std::string("cut.") + (png ? "png" : "jpg"), whole.substr(0, n));
            const std::string e = errorOf(file);
            EXPECT_EQ(e.rfind(file.string() + ": image 0: cannot decode the " + format + ": truncated", 0), 0u) << n << ": " << e;
        }
    }
}

TEST(GltfImageErrors, CorruptDataHasAReason) {
    std::string png = encoded(true);
    const std::size_t idat = png.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    for (std::size_t i = idat + 4; i < idat + 12; ++i) png[i] = char(0xff);  // the zlib stream
    const fs::path file = withImage("corrupt.png", png);
    const std::string e = errorOf(file);
    EXPECT_EQ(e.rfind(file.string() + ": image 0: cannot decode the PNG: corrupt data (stb_image: \"", 0), 0u) << e;
    const fs::path text = withImage("text.png", "not an image at all");
    EXPECT_EQ(errorOf(text).rfind(text.string() + ": image 0: cannot decode the image (PNG or JPEG expected): ", 0), 0u);
}

}  // namespace
