// Image accessors and the display encoding (exposure, clamp, sRGB OETF, rounding).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/image.h"
#include "core/tonemap.h"

namespace vkp {
namespace {

TEST(Image, LayoutIsRowMajorTopRowFirst) {
    Image img(3, 2);
    ASSERT_EQ(img.rgb.size(), 18u);
    EXPECT_EQ(img.pixelCount(), 6u);
    img.set(2, 1, 1.0f, 2.0f, 3.0f);
    EXPECT_EQ(img.offset(2, 1), 15u);
    EXPECT_EQ(img.rgb[15], 1.0f);
    EXPECT_EQ(img.rgb[17], 3.0f);
    EXPECT_EQ(img.at(2, 1, 1), 2.0f);
    img.pixel(0, 1)[2] = 7.0f;
    EXPECT_EQ(img.rgb[3 * 3 + 2], 7.0f);
    EXPECT_NO_THROW(img.checkConsistent());
    img.rgb.pop_back();
    EXPECT_THROW(img.checkConsistent(), std::invalid_argument);
    EXPECT_TRUE(Image().empty());
}

TEST(Tonemap, SrgbKnownValues) {
    // Expected codes computed independently: round(255 * (1.055 v^(1/2.4) - 0.055)) or 12.92 v.
    EXPECT_EQ(linearToSrgb8(0.0f, 1.0), 0);
    EXPECT_EQ(linearToSrgb8(0.001f, 1.0), 3);       // linear segment: 3.29
    EXPECT_EQ(linearToSrgb8(0.0031308f, 1.0), 10);  // the knee: 10.31
    EXPECT_EQ(linearToSrgb8(0.01f, 1.0), 25);       // 25.46
    EXPECT_EQ(linearToSrgb8(0.18f, 1.0), 118);      // 117.65
    EXPECT_EQ(linearToSrgb8(0.5f, 1.0), 188);       // 187.52
    EXPECT_EQ(linearToSrgb8(0.9f, 1.0), 243);       // 243.45
    EXPECT_EQ(linearToSrgb8(1.0f, 1.0), 255);
    EXPECT_NEAR(srgbEncode(0.5), 0.735356983, 1e-8);
    EXPECT_NEAR(srgbDecode(srgbEncode(0.25)), 0.25, 1e-12);
}

TEST(Tonemap, ClampsAndNaN) {
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(linearToSrgb8(std::numeric_limits<float>::quiet_NaN(), 1.0), 0);
    EXPECT_EQ(linearToSrgb8(-0.5f, 1.0), 0);
    EXPECT_EQ(linearToSrgb8(-inf, 1.0), 0);
    EXPECT_EQ(linearToSrgb8(2.0f, 1.0), 255);
    EXPECT_EQ(linearToSrgb8(inf, 1.0), 255);
}

TEST(Tonemap, EveryCodeRoundTrips) {
    for (int k = 0; k < 256; ++k) {
        EXPECT_EQ(linearToSrgb8(float(srgbDecode(k / 255.0)), 1.0), k) << "code " << k;
    }
}

TEST(Tonemap, ExposureIsPowerOfTwo) {
    EXPECT_DOUBLE_EQ(exposureScale(0.0), 1.0);
    EXPECT_DOUBLE_EQ(exposureScale(1.0), 2.0);
    EXPECT_DOUBLE_EQ(exposureScale(-2.0), 0.25);
    Image img(2, 1);
    img.set(0, 0, 0.25f, 0.125f, 1.0f);
    img.set(1, 0, 0.5f, 0.0f, 4.0f);
    const auto plus1 = toSrgb8(img, 1.0);
    ASSERT_EQ(plus1.size(), 6u);
    EXPECT_EQ(plus1[0], 188);  // 0.25 * 2 = 0.5
    EXPECT_EQ(plus1[1], linearToSrgb8(0.25f, 1.0));
    EXPECT_EQ(plus1[2], 255);
    EXPECT_EQ(plus1[3], 255);  // 0.5 * 2 = 1
    const auto minus2 = toSrgb8(img, -2.0);
    EXPECT_EQ(minus2[2], linearToSrgb8(0.25f, 1.0));
    EXPECT_EQ(minus2[5], 255);  // 4 / 4 = 1
    EXPECT_EQ(toSrgb8(img, 0.0)[3], 188);
}

}  // namespace
}  // namespace vkp
