// Tests of the statistics in tests/support/chi2.{h,cpp} that the other stats tests rely on:
// incomplete gamma / p-values against tabulated values, Sidak correction, Pearson's statistic
// with pooling and the zero-expected rule, the adaptive quadrature, direction binning, and the
// power of the test (a wrong pdf is rejected, the right one accepted).
// The one random test (uniform samples against the uniform pdf) runs at statsAlpha(): see
// stat_suite.h for the suite-wide false-failure probability (<= 1%, fixed seed).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stat_suite.h"

namespace {

using namespace vkp::test;

TEST(Chi2Support, PValuesMatchTables) {
    // Upper 5% points of chi-square (NIST/SEMATECH e-Handbook, table 1.3.6.7.4).
    EXPECT_NEAR(chi2PValue(3.841458820694124, 1), 0.05, 1e-9);
    EXPECT_NEAR(chi2PValue(18.307038053275146, 10), 0.05, 1e-9);
    EXPECT_NEAR(chi2PValue(124.34211340400407, 100), 0.05, 1e-8);
    EXPECT_NEAR(chi2PValue(1074.6794, 1000), 0.05, 1e-5);
    // Closed forms: dof 2 is exponential, Q(1, x) = e^-x; P(1/2, x) = erf(sqrt(x)).
    EXPECT_NEAR(chi2PValue(2.0, 2), std::exp(-1.0), 1e-14);
    EXPECT_NEAR(gammaP(0.5, 0.7), std::erf(std::sqrt(0.7)), 1e-13);
    EXPECT_NEAR(gammaP(3.5, 2.0) + gammaQ(3.5, 2.0), 1.0, 1e-14);
    EXPECT_NEAR(gammaP(50.0, 80.0) + gammaQ(50.0, 80.0), 1.0, 1e-14);
    EXPECT_EQ(chi2PValue(0.0, 5), 1.0);
    double tiny = chi2PValue(1e4, 100);
    EXPECT_TRUE(tiny >= 0.0 && tiny < 1e-300 + 1e-200);
    EXPECT_NEAR(chi2LowerTail(3.841458820694124, 1), 0.95, 1e-9);
    EXPECT_EQ(chi2PValue(std::nan(""), 3), 0.0);
}

TEST(Chi2Support, SidakCorrection) {
    EXPECT_NEAR(sidakAlpha(0.01, 1), 0.01, 1e-15);
    double a = sidakAlpha(0.01, kStatsChi2Budget);
    EXPECT_NEAR(1.0 - std::pow(1.0 - a, kStatsChi2Budget), 0.01, 1e-12);
    EXPECT_NEAR(statsAlpha(), a, 1e-15);
}

TEST(Chi2Support, PearsonStatisticAndPooling) {
    Chi2Result r = chi2Test({10, 20, 30}, {20, 20, 20});
    EXPECT_NEAR(r.statistic, 10.0, 1e-12);
    EXPECT_EQ(r.dof, 2);
    EXPECT_NEAR(r.pValue, std::exp(-5.0), 1e-12);
    // Cells with expected < 5 are pooled: {1,1,1,2} -> one cell of 5; the rest stand alone.
    Chi2Result p = chi2Test({0, 2, 1, 2, 10, 20}, {1, 1, 1, 2, 10, 20});
    EXPECT_EQ(p.cells, 3);
    EXPECT_NEAR(p.statistic, 0.0, 1e-12);
    // A small leftover pool is merged into the smallest cell, never left with expected < 5.
    Chi2Result q = chi2Test({1, 10, 20}, {1, 10, 20});
    EXPECT_EQ(q.cells, 2);
    // Samples where the pdf is zero: one stray sample is pooled, more reject outright.
    EXPECT_GT(chi2Test({1, 10, 10}, {0, 10.5, 10.5}).pValue, 0.0);
    EXPECT_EQ(chi2Test({3, 9, 9}, {0, 10.5, 10.5}).pValue, 0.0);
    // Empty impossible cells carry no degree of freedom.
    EXPECT_EQ(chi2Test({0, 10, 10}, {0, 10, 10}).dof, 1);
}

TEST(Chi2Support, QuadratureIsAccurate) {
    // Simpson is exact for x^3 y^2 on every cell.
    Grid2D g{0.0, 2.0, -1.0, 1.0, 4, 3};
    std::vector<double> cells =
        integrateCells(g, [](double x, double y) { return x * x * x * y * y; });
    double total = 0.0;
    for (double c : cells) total += c;
    EXPECT_NEAR(total, 4.0 * (2.0 / 3.0), 1e-12);  // (2^4/4) * (2/3)
    // A disc indicator (a jump along a curve): area pi/4 of the unit square's quarter disc.
    Grid2D h{0.0, 1.0, 0.0, 1.0, 8, 8};
    cells = integrateCells(h, [](double x, double y) { return x * x + y * y <= 1.0 ? 1.0 : 0.0; });
    total = 0.0;
    for (double c : cells) total += c;
    EXPECT_NEAR(total, 0.25 * 3.14159265358979323846, 2e-4);
    // Over the sphere: (3/(4 pi)) cos^2(theta) integrates to 1; so does a small cap's indicator.
    SphereBinning b = SphereBinning::around(glm::dvec3(1.0, 2.0, 2.0), -1.0, 10, 20);
    EXPECT_NEAR(integrateOverSphere(b,
                                    [](const glm::dvec3& d) {
                                        return 3.0 / (4.0 * 3.14159265358979323846) * d.z * d.z;
                                    }),
                1.0, 1e-6);
    double cosCap = std::cos(0.2);
    SphereBinning cap = SphereBinning::around(glm::dvec3(0.0, 0.0, 1.0), std::cos(0.25), 10, 20);
    double capPdf = 1.0 / (2.0 * 3.14159265358979323846 * (1.0 - cosCap));
    EXPECT_NEAR(
        integrateOverSphere(cap, [&](const glm::dvec3& d) { return d.z >= cosCap ? capPdf : 0.0; }),
        1.0, 1e-3);
}

TEST(Chi2Support, DirectionCellsCoverTheSphere) {
    SphereBinning b = SphereBinning::patch(glm::dvec3(0.0, 0.0, 1.0), 0.2, 0.6, -1.0, 0.5, 4, 5);
    EXPECT_EQ(b.cellCount(), 4 * 5 + 4);
    UniformSource rng(401);
    for (int i = 0; i < 10000; ++i) {
        glm::vec2 u = rng.next2();
        double z = 1.0 - 2.0 * u.x, phi = 2.0 * 3.14159265358979323846 * u.y;
        double r = std::sqrt(1.0 - z * z);
        glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
        int c = directionCell(b, d);
        ASSERT_GE(c, 0);
        ASSERT_LT(c, b.cellCount());
        glm::dvec2 zp = b.zPhi(d);
        bool inPatch = zp.x >= 0.2 && zp.x <= 0.6 && zp.y >= -1.0 && zp.y <= 0.5;
        ASSERT_EQ(inPatch, c < 20);
    }
    EXPECT_EQ(directionCell(b, glm::dvec3(0.0)), -1);
}

TEST(Chi2Support, AcceptsTheRightPdfAndRejectsAWrongOne) {
    UniformSource rng(402);
    std::vector<glm::dvec2> pts;
    for (int i = 0; i < 100000; ++i) pts.emplace_back(rng.next2());
    Grid2D g{0.0, 1.0, 0.0, 1.0, 20, 20};
    EXPECT_TRUE(passesChi2(chi2Test2D(pts, g, [](double, double) { return 1.0; })));
    // A density tilted by +-10% is rejected with 1e5 samples (noncentrality ~330).
    Chi2Result wrong = chi2Test2D(pts, g, [](double x, double) { return 0.9 + 0.2 * x; });
    EXPECT_LT(wrong.pValue, 1e-6) << wrong.message;
    std::vector<glm::dvec2> outside = {glm::dvec2(1.5, 0.5)};
    EXPECT_EQ(chi2Test2D(outside, g, [](double, double) { return 1.0; }).pValue, 0.0);
}

}  // namespace
