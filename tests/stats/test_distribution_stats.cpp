// Statistical and numerical tests of shaders/shared/distribution.h (compiled as C++) with the
// tables of host/render/distribution_table.cpp: for tables with zeros, a single bright cell, whole
// zero rows and columns, 1 x N and N x 1 shapes, (a) chi-square of sampleDistribution2D against
// pdfDistribution2D on a grid twice as fine as the table (so non-uniformity inside a cell shows),
// (b) the densities integrate to 1, (c) the pdf returned with a sample equals pdfDistribution2D at
// that point, (d) invertDistribution2D(sampleDistribution2D(u)) = u, (e) no sample in a cell of
// zero weight.
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: Sidak-corrected so the
// whole stats suite falsely fails with probability <= 1% for correct code; seeds are fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "render/distribution_table.h"
#include "shared/distribution.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;

constexpr int kSamples = 200000;

struct Table {
    std::string name;
    std::uint32_t nu, nv;
    std::vector<double> w;
};

std::vector<Table> tables() {
    std::vector<Table> t;
    {
        Table a{"random 8x6 with zeros", 8, 6, {}};
        UniformSource src(11);
        for (std::uint32_t i = 0; i < a.nu * a.nv; ++i) {
            const float r = src.next();
            a.w.push_back(r < 0.25f ? 0.0 : double(src.next()) * 10.0);
        }
        t.push_back(a);
    }
    {
        Table a{"single bright cell 16x8", 16, 8, std::vector<double>(16 * 8, 1e-3)};
        a.w[3 * 16 + 11] = 1e4;
        t.push_back(a);
    }
    {
        Table a{"only one non-zero cell 5x4", 5, 4, std::vector<double>(5 * 4, 0.0)};
        a.w[2 * 5 + 4] = 2.0;
        t.push_back(a);
    }
    {
        Table a{"zero row and column 6x5", 6, 5, {}};
        for (std::uint32_t r = 0; r < 5; ++r)
            for (std::uint32_t c = 0; c < 6; ++c) a.w.push_back((r == 2 || c == 0) ? 0.0 : 1.0 + r + 2.0 * c);
        t.push_back(a);
    }
    t.push_back({"1x7 (one column)", 1, 7, {1, 0, 3, 0.5, 7, 0, 2}});
    t.push_back({"9x1 (one row)", 9, 1, {0, 1, 2, 3, 0, 5, 6, 0, 0.25}});
    t.push_back({"all zero 3x3 (uniform)", 3, 3, std::vector<double>(9, 0.0)});
    return t;
}

class DistributionTest : public ::testing::TestWithParam<int> {};

TEST_P(DistributionTest, Chi2PdfConsistencyRoundTrip) {
    const Table tab = tables()[GetParam()];
    SCOPED_TRACE(tab.name);
    const std::vector<float> data = vkp::buildDistribution2D(tab.w, tab.nu, tab.nv);
    ASSERT_EQ(data.size(), gpu::distSize2D(tab.nu, tab.nv));
    const float* table = data.data();

    // (b) densities integrate to 1 (sum over cells of density x cell area).
    double integral = 0.0;
    for (std::uint32_t r = 0; r < tab.nv; ++r)
        for (std::uint32_t c = 0; c < tab.nu; ++c)
            integral += gpu::pdfDistribution2D(table, 0u, tab.nu, tab.nv,
                                               glm::vec2((c + 0.5f) / tab.nu, (r + 0.5f) / tab.nv)) /
                        (double(tab.nu) * tab.nv);
    EXPECT_NEAR(integral, 1.0, 1e-5);

    UniformSource src(1234 + GetParam());
    std::vector<glm::dvec2> samples;
    samples.reserve(kSamples);
    int pdfMismatch = 0, zeroCell = 0, roundTripBad = 0;
    double worstRoundTrip = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const glm::vec2 u = src.next2();
        float pdf = -1.0f;
        const glm::vec2 p = gpu::sampleDistribution2D(table, 0u, tab.nu, tab.nv, u, pdf);
        samples.emplace_back(p.x, p.y);
        // (c) the same density as evaluated alone, bit for bit.
        if (pdf != gpu::pdfDistribution2D(table, 0u, tab.nu, tab.nv, p)) ++pdfMismatch;
        // (e) never a cell of zero weight (unless every weight is zero: uniform).
        const std::uint32_t c = gpu::distCellOf(p.x, tab.nu), r = gpu::distCellOf(p.y, tab.nv);
        double rowSum = 0.0, all = 0.0;
        for (std::uint32_t k = 0; k < tab.nu; ++k) rowSum += tab.w[r * tab.nu + k];
        for (double w : tab.w) all += w;
        if (all > 0.0 && (tab.w[r * tab.nu + c] == 0.0 || !(pdf > 0.0f))) ++zeroCell;
        // (d) round trip; u moves by at most a few ulps of the CDF (float) times the cell's
        // remapping, so 2e-5 absolute is ~100 ulps of 1.
        const glm::vec2 back = gpu::invertDistribution2D(table, 0u, tab.nu, tab.nv, p);
        const double err = std::max(std::abs(back.x - u.x), std::abs(back.y - u.y));
        worstRoundTrip = std::max(worstRoundTrip, err);
        if (err > 2e-5) ++roundTripBad;
        (void)rowSum;
    }
    EXPECT_EQ(pdfMismatch, 0);
    EXPECT_EQ(zeroCell, 0);
    EXPECT_EQ(roundTripBad, 0) << "worst round-trip error " << worstRoundTrip;

    // (a) chi-square on a grid twice as fine as the table. The pdf is constant on each grid cell,
    // so a cell's probability is its density at the centre times its area (exact; quadrature
    // points on the cell edges would read the neighbour's density).
    Grid2D g;
    g.nx = int(2 * tab.nu);
    g.ny = int(2 * tab.nv);
    std::vector<double> observed(g.cellCount(), 0.0), expected(g.cellCount(), 0.0);
    for (const glm::dvec2& p : samples) {
        const int cell = g.cell(p.x, p.y);
        ASSERT_GE(cell, 0) << "sample outside [0,1)^2";
        observed[cell] += 1.0;
    }
    for (int iy = 0; iy < g.ny; ++iy)
        for (int ix = 0; ix < g.nx; ++ix) {
            const glm::vec2 centre(float((ix + 0.5) / g.nx), float((iy + 0.5) / g.ny));
            expected[iy * g.nx + ix] =
                kSamples * double(gpu::pdfDistribution2D(table, 0u, tab.nu, tab.nv, centre)) / g.cellCount();
        }
    EXPECT_TRUE(passesChi2(chi2Test(observed, expected)));
}

INSTANTIATE_TEST_SUITE_P(Tables, DistributionTest, ::testing::Range(0, int(tables().size())));

TEST(Distribution1D, EdgesOfU) {
    // u = 0 and the largest u < 1 stay inside [0,1) and in cells of non-zero weight, even when the
    // first and last cells have zero weight.
    std::vector<float> data;
    vkp::appendDistribution1D({0, 0, 1, 2, 0}, data);
    for (float u : {0.0f, 0x1p-24f, 0.5f, 0x1.fffffep-1f}) {
        float pdf;
        std::uint32_t cell;
        const float x = gpu::sampleDistribution1D(data.data(), 0u, 5u, u, pdf, cell);
        EXPECT_GE(x, 0.0f);
        EXPECT_LT(x, 1.0f);
        EXPECT_TRUE(cell == 2u || cell == 3u) << "u " << u << " cell " << cell;
        EXPECT_GT(pdf, 0.0f);
        EXPECT_EQ(gpu::distCellOf(x, 5u), cell);
    }
}

}  // namespace
