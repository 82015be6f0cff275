// The error metrics of --reference / --error-log (render/error_metrics.h) on images whose errors are
// known by hand, the reference checks, and the CSV log.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"
#include "core/image_io.h"
#include "render/error_metrics.h"
#include "test_paths.h"

namespace vkp {
namespace {

Image constant(std::uint32_t w, std::uint32_t h, float r, float g, float b) {
    Image img(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) img.set(x, y, r, g, b);
    return img;
}

std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

TEST(ErrorMetrics, IdenticalImagesHaveNoError) {
    const Image a = constant(5, 3, 0.25f, 2.0f, 0.0f);
    const ErrorMetrics m = computeErrorMetrics(a, a);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.relmse, 0.0);
    EXPECT_DOUBLE_EQ(m.mean[0], 0.25);
    EXPECT_DOUBLE_EQ(m.mean[1], 2.0);
    EXPECT_DOUBLE_EQ(m.mean[2], 0.0);
}

TEST(ErrorMetrics, ConstantOffset) {
    // x = y + 0.5 everywhere: rmse = 0.5. Against y = 0: relmse = 0.25 / 0.01 = 25; against y = 1:
    // 0.25 / 1.01.
    const Image ref0 = constant(4, 4, 0, 0, 0), x0 = constant(4, 4, 0.5f, 0.5f, 0.5f);
    ErrorMetrics m = computeErrorMetrics(x0, ref0);
    EXPECT_NEAR(m.rmse, 0.5, 1e-12);
    EXPECT_NEAR(m.relmse, 25.0, 1e-9);
    const Image ref1 = constant(4, 4, 1, 1, 1), x1 = constant(4, 4, 1.5f, 1.5f, 1.5f);
    m = computeErrorMetrics(x1, ref1);
    EXPECT_NEAR(m.rmse, 0.5, 1e-12);
    EXPECT_NEAR(m.relmse, 0.25 / 1.01, 1e-12);
    EXPECT_DOUBLE_EQ(m.mean[1], 1.5);
}

TEST(ErrorMetrics, HandComputedTwoPixels) {
    // Pixel 0: x = (1, 0, 0), y = (0, 0, 0); pixel 1: x = (2, 2, 2), y = (2, 2, 4).
    // Squared errors: 1, 0, 0, 0, 0, 4 -> MSE 5/6. relMSE terms: 1/0.01, 0, 0, 0, 0, 4/16.01.
    Image x(2, 1), y(2, 1);
    x.set(0, 0, 1, 0, 0);
    x.set(1, 0, 2, 2, 2);
    y.set(0, 0, 0, 0, 0);
    y.set(1, 0, 2, 2, 4);
    const ErrorMetrics m = computeErrorMetrics(x, y);
    EXPECT_NEAR(m.rmse, std::sqrt(5.0 / 6.0), 1e-12);
    EXPECT_NEAR(m.relmse, (100.0 + 4.0 / 16.01) / 6.0, 1e-9);
    EXPECT_DOUBLE_EQ(m.mean[0], 1.5);
    EXPECT_DOUBLE_EQ(m.mean[1], 1.0);
    EXPECT_DOUBLE_EQ(m.mean[2], 1.0);
}

TEST(ErrorMetrics, NotSymmetricInTheReference) {
    // relMSE divides by the reference, so swapping the images changes it (rmse does not).
    Image a = constant(1, 1, 0, 0, 0), b = constant(1, 1, 1, 1, 1);
    EXPECT_NEAR(computeErrorMetrics(a, b).relmse, 1.0 / 1.01, 1e-12);
    EXPECT_NEAR(computeErrorMetrics(b, a).relmse, 100.0, 1e-9);
    EXPECT_EQ(computeErrorMetrics(a, b).rmse, computeErrorMetrics(b, a).rmse);
}

TEST(ErrorMetrics, SizeMismatchAndEmptyThrow) {
    EXPECT_THROW(computeErrorMetrics(Image(4, 4), Image(4, 5)), std::invalid_argument);
    EXPECT_THROW(computeErrorMetrics(Image(4, 4), Image(5, 4)), std::invalid_argument);
    EXPECT_THROW(computeErrorMetrics(Image(), Image()), std::invalid_argument);
}

struct ReferenceFile : ::testing::Test {
    std::filesystem::path dir = test::scratchDir("error_metrics");
};

TEST_F(ReferenceFile, AcceptsTheRightSizeRefusesOthers) {
    const Image ref = constant(6, 4, 0.1f, 0.2f, 0.3f);
    writeImage(ref, dir / "ref.pfm");
    EXPECT_EQ(readReferenceImage(dir / "ref.pfm", 6, 4).rgb, ref.rgb);
    try {
        readReferenceImage(dir / "ref.pfm", 4, 6);
        FAIL() << "no error for a size mismatch";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("ref.pfm"), std::string::npos) << msg;
        EXPECT_NE(msg.find("6x4"), std::string::npos) << msg;
        EXPECT_NE(msg.find("4x6"), std::string::npos) << msg;
    }
    EXPECT_THROW(readReferenceImage(dir / "missing.pfm", 6, 4), InputError);
}

TEST_F(ReferenceFile, RefusesNonFiniteValues) {
    Image ref = constant(3, 2, 0.5f, 0.5f, 0.5f);
    ref.at(2, 1, 1) = std::nanf("");
    writeImage(ref, dir / "nan.pfm");
    try {
        readReferenceImage(dir / "nan.pfm", 3, 2);
        FAIL() << "no error for a NaN pixel";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("(2, 1)"), std::string::npos) << e.what();
    }
    ref.at(2, 1, 1) = INFINITY;
    writeImage(ref, dir / "inf.pfm");
    EXPECT_THROW(readReferenceImage(dir / "inf.pfm", 3, 2), InputError);
}

TEST(ErrorLogRow, Format) {
    ErrorMetrics m;
    m.rmse = 0.125;
    m.relmse = 2.5e-3;
    m.mean[0] = 1;
    m.mean[1] = 0.5;
    m.mean[2] = 0.25;
    EXPECT_EQ(errorLogRow(16, 2.5, m), "16,2.500000,0.125,0.0025,1,0.5,0.25");
    EXPECT_STREQ(errorLogHeader(), "spp,seconds,rmse,relmse,mean_r,mean_g,mean_b");
}

TEST_F(ReferenceFile, ErrorLogRowsAreOnDiskAsSoonAsWritten) {
    const auto path = dir / "log.csv";
    std::filesystem::remove(path);
    ErrorMetrics m;
    m.rmse = 1;
    {
        ErrorLog log(path);
        EXPECT_EQ(slurp(path), "spp,seconds,rmse,relmse,mean_r,mean_g,mean_b\n");
        log.append(1, 0.5, m);
        // Still open: the row must already be in the file (a killed render keeps its rows).
        EXPECT_EQ(slurp(path), std::string(errorLogHeader()) + "\n" + errorLogRow(1, 0.5, m) + "\n");
        log.append(2, 0.75, m);
        EXPECT_EQ(log.rows(), 2u);
    }
    EXPECT_EQ(slurp(path), std::string(errorLogHeader()) + "\n" + errorLogRow(1, 0.5, m) + "\n" +
                               errorLogRow(2, 0.75, m) + "\n");
    // A new log replaces the old one.
    { ErrorLog again(path); }
    EXPECT_EQ(slurp(path), std::string(errorLogHeader()) + "\n");
}

TEST_F(ReferenceFile, ErrorLogInMissingFolderIsAnInputError) {
    EXPECT_THROW(ErrorLog(dir / "no-such-folder" / "log.csv"), InputError);
}

}  // namespace
}  // namespace vkp
