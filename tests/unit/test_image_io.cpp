// Image writers and readers: round trips, orientation (row 0 = top everywhere), PNG encoding,
// extension dispatch and malformed-file errors.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/image.h"
#include "core/image_header.h"
#include "core/image_io.h"
#include "test_paths.h"

namespace vkp {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) { return test::scratchDir("image_io") / name; }

std::vector<uint8_t> fileBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::vector<uint8_t>& bytes, size_t count) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(count));
}

void writeText(const fs::path& p, const std::string& s) { writeBytes(p, {s.begin(), s.end()}, s.size()); }

/// Non-square, every value distinct, the top row (y = 0) bright red-ish and unlike the others.
Image makeTestImage(uint32_t w = 5, uint32_t h = 3) {
    Image img(w, h);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            if (y == 0) {
                img.set(x, y, 50.0f + float(x), 0.001f * float(x + 1), 0.0f);
            } else {
                img.set(x, y, 0.01f * float(x + 1), 0.1f * float(y) + 0.003f * float(x), 0.5f + 2.0f * float(y));
            }
        }
    }
    return img;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no InputError thrown>";
}

void expectBitExact(const Image& a, const Image& b) {
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        EXPECT_EQ(std::bit_cast<uint32_t>(a.rgb[i]), std::bit_cast<uint32_t>(b.rgb[i]))
            << "value " << i << ": " << a.rgb[i] << " vs " << b.rgb[i];
    }
}

TEST(ImageIo, FormatFromExtensionIsCaseInsensitive) {
    EXPECT_EQ(imageFormatFromPath("a/b.png"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromPath("B.PNG"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromPath("c.Exr"), ImageFormat::Exr);
    EXPECT_EQ(imageFormatFromPath("d.pFm"), ImageFormat::Pfm);
    EXPECT_EQ(imageFormatFromPath("e.HDR"), ImageFormat::Hdr);
}

TEST(ImageIo, UnknownExtensionNamesFileAndSupportedList) {
    const fs::path p = scratch("picture.jpg");
    const std::string msg = errorOf([&] { writeImage(makeTestImage(), p); });
    EXPECT_NE(msg.find("picture.jpg"), std::string::npos) << msg;
    EXPECT_NE(msg.find(".png .exr .pfm .hdr"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(p));
    EXPECT_NE(errorOf([&] { checkOutputPath(scratch("noext")); }).find("noext"), std::string::npos);
    EXPECT_NE(errorOf([&] { (void)readImage(scratch("x.tiff")); }).find("x.tiff"), std::string::npos);
}

TEST(ImageIo, PfmRoundTripIsExactIncludingSpecialValues) {
    Image img = makeTestImage();
    img.set(1, 1, std::numeric_limits<float>::infinity(), -3.5f, std::numeric_limits<float>::denorm_min());
    img.set(2, 2, std::numeric_limits<float>::quiet_NaN(), -0.0f, 1e30f);
    const fs::path p = scratch("round.pfm");
    writeImage(img, p);
    expectBitExact(readImage(p), img);
}

TEST(ImageIo, PfmFileStoresRowsBottomToTopLittleEndian) {
    Image img(2, 2);
    img.set(0, 0, 1.0f, 2.0f, 3.0f);  // top row
    img.set(1, 0, 4.0f, 5.0f, 6.0f);
    img.set(0, 1, 7.0f, 8.0f, 9.0f);  // bottom row
    img.set(1, 1, 10.0f, 11.0f, 12.0f);
    const fs::path p = scratch("order.pfm");
    writeImage(img, p);
    const std::vector<uint8_t> bytes = fileBytes(p);
    const std::string header = "PF\n2 2\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 48);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(header.size())), header);
    const float expected[12] = {7, 8, 9, 10, 11, 12, 1, 2, 3, 4, 5, 6};  // bottom row first
    for (size_t i = 0; i < 12; ++i) {
        const uint8_t* q = bytes.data() + header.size() + 4 * i;
        const uint32_t u = uint32_t(q[0]) | uint32_t(q[1]) << 8 | uint32_t(q[2]) << 16 | uint32_t(q[3]) << 24;
        EXPECT_EQ(std::bit_cast<float>(u), expected[i]) << "float " << i;
    }
}

TEST(ImageIo, PfmReadsBigEndianAndGray) {
    // "Pf" (one channel), positive scale = big endian, 2x1, stored bottom row first (one row here).
    const fs::path p = scratch("gray_be.pfm");
    std::string s = "Pf 2\t1\n\n1.0\n";
    for (float v : {0.5f, -2.0f}) {
        const uint32_t u = std::bit_cast<uint32_t>(v);
        for (int k = 3; k >= 0; --k) s.push_back(char(uint8_t(u >> (8 * k))));
    }
    writeText(p, s);
    const Image img = readImage(p);
    ASSERT_EQ(img.width, 2u);
    ASSERT_EQ(img.height, 1u);
    EXPECT_EQ(img.pixel(0, 0)[0], 0.5f);
    EXPECT_EQ(img.pixel(0, 0)[2], 0.5f);
    EXPECT_EQ(img.pixel(1, 0)[1], -2.0f);
}

TEST(ImageIo, MalformedPfmIsAnInputErrorNamingTheFile) {
    const fs::path good = scratch("good.pfm");
    writeImage(makeTestImage(), good);
    const std::vector<uint8_t> bytes = fileBytes(good);
    const fs::path bad = scratch("bad.pfm");
    // Every truncation, header included, is detected.
    for (size_t n = 0; n < bytes.size(); ++n) {
        writeBytes(bad, bytes, n);
        const std::string msg = errorOf([&] { (void)readImage(bad); });
        EXPECT_EQ(msg.rfind(bad.string() + ": ", 0), 0u) << "prefix " << n << ": " << msg;
    }
    writeBytes(bad, bytes, bytes.size() - 1);
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("truncated"), std::string::npos);
    writeText(bad, "P6\n2 2\n255\n");
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("not a PFM"), std::string::npos);
    writeText(bad, "PF\n0 2\n-1.0\n");
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("width"), std::string::npos);
    writeText(bad, "PF\n1 1\nabc\n123456789012");
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("scale"), std::string::npos);
    writeText(bad, "PF\n1 1\n-1\n123456789012345");  // 3 bytes too many
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("unexpected bytes"), std::string::npos);
    writeText(bad, "PF\n4294967295 4294967295\n-1\n0000");  // huge size, tiny file: no allocation
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("truncated"), std::string::npos);
    EXPECT_NE(errorOf([&] { (void)readImage(scratch("missing.pfm")); }).find("no such file"), std::string::npos);
}

TEST(ImageIo, ExrRoundTripIsExactFloat) {
    Image img = makeTestImage(17, 9);  // more than one 16-line ZIP block
    img.set(3, 4, -1.25f, std::numeric_limits<float>::infinity(), 1e-40f);
    const fs::path p = scratch("round.exr");
    writeImage(img, p);
    expectBitExact(readImage(p), img);
}

TEST(ImageIo, ExrStoresFloatChannelsBGR) {
    const fs::path p = scratch("channels.exr");
    writeImage(makeTestImage(), p);
    const std::vector<uint8_t> b = fileBytes(p);
    const std::string s(b.begin(), b.end());
    // chlist entries: name\0, int32 pixel type (2 = FLOAT), ... in the order B, G, R.
    const size_t at = s.find(std::string("channels\0chlist\0", 16));
    ASSERT_NE(at, std::string::npos);
    const size_t list = at + 16 + 4;  // after the attribute size
    for (int c = 0; c < 3; ++c) {
        const size_t entry = list + size_t(c) * 18;  // "X\0" + 4 type + 4 pLinear/reserved + 8 sampling
        EXPECT_EQ(s[entry], "BGR"[c]);
        EXPECT_EQ(b[entry + 2], 2) << "channel " << "BGR"[c] << " is not FLOAT";
    }
}

TEST(ImageIo, TruncatedExrIsAnInputError) {
    const fs::path good = scratch("good.exr");
    writeImage(makeTestImage(20, 40), good);
    const std::vector<uint8_t> bytes = fileBytes(good);
    const fs::path bad = scratch("bad.exr");
    for (size_t n = 0; n < bytes.size(); ++n) {
        writeBytes(bad, bytes, n);
        const std::string msg = errorOf([&] { (void)readImage(bad); });
        EXPECT_EQ(msg.rfind(bad.string() + ": ", 0), 0u) << "prefix " << n << ": " << msg;
    }
    writeText(bad, "this is not an exr file at all");
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("not an OpenEXR"), std::string::npos);
}

TEST(ImageIo, HdrRoundTripWithinRgbePrecision) {
    Image img = makeTestImage(40, 6);  // wide enough for RGBE run-length rows
    img.set(7, 2, 12345.0f, 0.002f, 3.0f);
    const fs::path p = scratch("round.hdr");
    writeImage(img, p);
    const Image back = readImage(p);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    for (uint32_t y = 0; y < img.height; ++y) {
        for (uint32_t x = 0; x < img.width; ++x) {
            const auto a = img.pixel(x, y);
            const float maxc = std::max({a[0], a[1], a[2]});
            for (int c = 0; c < 3; ++c) {
                // RGBE: shared exponent, 8-bit truncated mantissas -> error < max component / 128.
                EXPECT_NEAR(back.pixel(x, y)[size_t(c)], a[size_t(c)], maxc / 128.0f) << x << "," << y << "," << c;
            }
        }
    }
}

TEST(ImageIo, HdrMapsUnrepresentableValues) {
    Image img(3, 1);
    img.set(0, 0, std::numeric_limits<float>::quiet_NaN(), -4.0f, 1.0f);
    img.set(1, 0, std::numeric_limits<float>::infinity(), 0.0f, 0.0f);
    img.set(2, 0, 0.5f, 0.5f, 0.5f);
    const fs::path p = scratch("special.hdr");
    writeImage(img, p);
    const Image back = readImage(p);
    EXPECT_EQ(back.pixel(0, 0)[0], 0.0f);
    EXPECT_EQ(back.pixel(0, 0)[1], 0.0f);
    EXPECT_NEAR(back.pixel(0, 0)[2], 1.0f, 1.0f / 128);
    EXPECT_GT(back.pixel(1, 0)[0], 1e37f);
    EXPECT_TRUE(std::isfinite(back.pixel(1, 0)[0]));
    EXPECT_NEAR(back.pixel(2, 0)[1], 0.5f, 0.5f / 128);
}

TEST(ImageIo, MalformedHdrIsAnInputError) {
    const fs::path bad = scratch("bad.hdr");
    writeText(bad, "P6 not radiance");
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("not a Radiance HDR"), std::string::npos);
    // Every truncation fails cleanly, both for run-length (width 40) and flat (width 5) scanlines.
    // (stb_image's reader loops forever on some of these.)
    for (uint32_t width : {40u, 5u}) {
        const fs::path good = scratch("good.hdr");
        writeImage(makeTestImage(width, 4), good);
        const std::vector<uint8_t> bytes = fileBytes(good);
        for (size_t n = 0; n < bytes.size(); ++n) {
            writeBytes(bad, bytes, n);
            const std::string msg = errorOf([&] { (void)readImage(bad); });
            EXPECT_EQ(msg.rfind(bad.string() + ": ", 0), 0u) << "width " << width << " prefix " << n << ": " << msg;
        }
    }
    std::string zeroRun = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
    zeroRun += std::string("\x02\x02\x00\x08", 4);  // run-length scanline of 8 pixels
    zeroRun += std::string(12, '\0');                  // whose first count is 0
    writeText(bad, zeroRun);
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("run-length"), std::string::npos);
    writeText(bad, "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\x80\x80\x80\x81");
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("xyze"), std::string::npos);
    writeText(bad, "#?RADIANCE\n\n+X 1 -Y 1\n\x80\x80\x80\x81");
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("resolution"), std::string::npos);
    writeText(bad, "#?RADIANCE\n\n-Y 100000 +X 100000\n\x80\x80\x80\x81");  // no huge allocation
    EXPECT_NE(errorOf([&] { (void)readImage(bad); }).find("truncated"), std::string::npos);
}

TEST(ImageIo, HdrReaderHandlesBottomUpFilesAndExposure) {
    // Flat scanlines, 1 x 2, stored bottom row first ("+Y"), EXPOSURE 2 then 2 (stored = 4 x radiance).
    const fs::path p = scratch("bottom_up.hdr");
    std::string s = "#?RGBE\nEXPOSURE=2\nEXPOSURE= 2.0\n\n+Y 2 +X 1\n";
    s += std::string("\x80\x40\x00\x81", 4);  // (128, 64, 0) * 2^(129-136) = (1, 0.5, 0): bottom
    s += std::string("\x80\x80\x80\x83", 4);  // (4, 4, 4): top
    writeText(p, s);
    const Image img = readImage(p);
    ASSERT_EQ(img.width, 1u);
    ASSERT_EQ(img.height, 2u);
    EXPECT_EQ(img.pixel(0, 0)[0], 1.0f);  // top: 4 / 4
    EXPECT_EQ(img.pixel(0, 1)[0], 0.25f);  // bottom: 1 / 4
    EXPECT_EQ(img.pixel(0, 1)[1], 0.125f);
    EXPECT_EQ(img.pixel(0, 1)[2], 0.0f);
}

TEST(ImageIo, PngIsSrgbEncodedWithExposure) {
    Image img(4, 1);
    img.set(0, 0, 0.0f, 0.5f, 1.0f);
    img.set(1, 0, 0.18f, 0.01f, 0.001f);
    img.set(2, 0, std::numeric_limits<float>::quiet_NaN(), -1.0f, 7.0f);
    img.set(3, 0, 0.25f, 0.125f, 0.0625f);
    const fs::path p = scratch("encode.png");
    writeImage(img, p);
    int w = 0, h = 0, comp = 0;
    unsigned char* px = stbi_load(p.c_str(), &w, &h, &comp, 0);
    ASSERT_NE(px, nullptr) << stbi_failure_reason();
    ASSERT_EQ(w, 4);
    ASSERT_EQ(h, 1);
    ASSERT_EQ(comp, 3);
    const std::vector<int> got(px, px + 12);
    stbi_image_free(px);
    // Independently computed: round(255 * sRGB_OETF(v)).
    EXPECT_EQ(got, (std::vector<int>{0, 188, 255, 118, 25, 3, 0, 0, 255, 137, 99, 71}));

    WriteOptions plus2;
    plus2.exposure = 2.0;  // x4: 0.25 -> 1, 0.125 -> 0.5, 0.0625 -> 0.25
    writeImage(img, p, plus2);
    px = stbi_load(p.c_str(), &w, &h, &comp, 3);
    ASSERT_NE(px, nullptr);
    EXPECT_EQ(px[9], 255);
    EXPECT_EQ(px[10], 188);
    EXPECT_EQ(px[11], 137);
    stbi_image_free(px);
}

TEST(ImageIo, RowZeroIsTheTopInEveryFormat) {
    const Image img = makeTestImage(6, 4);
    for (const char* ext : {".pfm", ".exr", ".hdr"}) {
        const fs::path p = scratch(std::string("orient") + ext);
        writeImage(img, p);
        const Image back = readImage(p);
        ASSERT_EQ(back.width, 6u) << ext;
        ASSERT_EQ(back.height, 4u) << ext;
        for (uint32_t x = 0; x < 6; ++x) {
            EXPECT_NEAR(back.pixel(x, 0)[0], 50.0f + float(x), 0.5f) << ext;  // top row
            EXPECT_NEAR(back.pixel(x, 3)[2], 6.5f, 0.06f) << ext;            // bottom row
        }
    }
    const fs::path p = scratch("orient.png");
    writeImage(img, p);
    int w = 0, h = 0, comp = 0;
    unsigned char* px = stbi_load(p.c_str(), &w, &h, &comp, 3);
    ASSERT_NE(px, nullptr);
    ASSERT_EQ(w, 6);
    ASSERT_EQ(h, 4);
    EXPECT_EQ(px[0], 255);  // top-left: R clamps to 255, B = 0
    EXPECT_EQ(px[2], 0);
    EXPECT_EQ(px[3 * 6 * 3 + 2], 255);  // bottom-left: B = 6.5 -> 255, R = 0.01 -> 25
    EXPECT_EQ(px[3 * 6 * 3 + 0], 25);
    stbi_image_free(px);
}

TEST(ImageIo, PngIsNotReadable) {
    const fs::path p = scratch("encode_only.png");
    writeImage(makeTestImage(), p);
    EXPECT_NE(errorOf([&] { (void)readImage(p); }).find("not supported"), std::string::npos);
}

TEST(ImageIo, CheckOutputPath) {
    EXPECT_NO_THROW(checkOutputPath(scratch("ok.exr")));
    EXPECT_FALSE(fs::exists(scratch("ok.exr")));
    EXPECT_NE(errorOf([&] { checkOutputPath(scratch("no_such_dir") / "x.png"); }).find("does not exist"),
              std::string::npos);
    fs::create_directories(scratch("a_dir.png"));
    EXPECT_NE(errorOf([&] { checkOutputPath(scratch("a_dir.png")); }).find("is a directory"), std::string::npos);
    EXPECT_NE(errorOf([&] { checkOutputPath(scratch("x.bmp")); }).find("unknown image extension"),
              std::string::npos);
}

TEST(ImageIo, EmptyImageIsAProgrammingError) {
    EXPECT_THROW(writeImage(Image(), scratch("empty.pfm")), std::invalid_argument);
    EXPECT_FALSE(fs::exists(scratch("empty.pfm")));
}

}  // namespace
}  // namespace vkp

namespace vkp {
namespace {
// Found by tools/fuzz.sh: a progressive JPEG with a second frame header makes Debian's stb_image
// read out of bounds (SEGV). The header reader refuses it before stb_image sees it, naming the
// marker; the file stays in the fuzz corpus, which the default run replays (fuzz.replay_image).
TEST(ImageHeaderFuzzFindings, ASecondJpegFrameHeaderIsRefused) {
    const std::filesystem::path f = std::filesystem::path(VKPATH_SOURCE_DIR) / "tests/fuzz/corpus/image/crash-stb-progressive-two-sof.jpg";
    std::ifstream in(f, std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(bytes.empty());
    const ImageHeader h = readImageHeader(bytes);
    EXPECT_EQ(h.format, "JPEG");
    EXPECT_NE(h.problem.find("a second frame header (SOF) at byte"), std::string::npos) << h.problem;
    // A well-formed progressive JPEG (one frame header) still passes.
    std::ifstream ok(std::filesystem::path(VKPATH_SOURCE_DIR) / "tests/fuzz/corpus/image/progressive.jpg", std::ios::binary);
    const std::vector<std::uint8_t> good((std::istreambuf_iterator<char>(ok)), std::istreambuf_iterator<char>());
    EXPECT_EQ(readImageHeader(good).problem, "");
}
}  // namespace
}  // namespace vkp
