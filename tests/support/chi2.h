// Chi-square goodness-of-fit tests for sampling routines (the method of pbrt-v4's
// src/pbrt/util/sampling_test.cpp and Mitsuba 3's mitsuba.chi2): draw N samples, histogram them
// into cells, integrate the claimed pdf numerically over every cell to get the expected counts,
// pool cells whose expected count is below 5, and compute Pearson's statistic and its p-value.
// A cell that receives samples but has (numerically) zero expected count fails the test outright.
#pragma once
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace vkp::test {

// ---- Distributions
// -------------------------------------------------------------------------------

/// Regularised lower incomplete gamma function P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0
/// (series for x < a + 1, Lentz continued fraction otherwise; Numerical Recipes 3rd ed. sec. 6.2).
double gammaP(double a, double x);
/// Regularised upper incomplete gamma function Q(a, x) = 1 - P(a, x), accurate in the tail.
double gammaQ(double a, double x);
/// p-value of a chi-square statistic with dof degrees of freedom: Q(dof/2, statistic/2).
double chi2PValue(double statistic, int dof);
/// Lower tail P(X <= statistic) = P(dof/2, statistic/2), accurate where chi2PValue is near 1
/// (a fit "too good to be true", the sign of a non-random generator).
double chi2LowerTail(double statistic, int dof);
/// Per-test significance for a family of numTests independent tests to have family-wise
/// significance alpha (Sidak 1967): 1 - (1 - alpha)^(1/numTests).
double sidakAlpha(double alpha, int numTests);

// ---- The test
// ------------------------------------------------------------------------------------

struct Chi2Result {
    double statistic = 0.0;
    int dof = 0;          ///< pooled cells - 1
    double pValue = 1.0;  ///< 0 when samples fell into a cell of zero expected count
    int cells = 0;        ///< cells after pooling
    std::string message;  ///< summary, or why the test failed outright
};

/// Pearson's chi-square test of observed against expected counts (same length, same total up to
/// integration error). Cells with expected < minExpected are pooled: sorted by expected count and
/// merged in ascending order until each pool reaches minExpected; a final small pool is merged into
/// the smallest cell. A cell with expected <= zeroExpected that holds more than
/// max(1, 1e-5 * total) samples gives pValue = 0 (the rule of pbrt's and Mitsuba's chi2 tests: a
/// single stray sample may sit in a sliver of the pdf's support that the quadrature missed;
/// such cells are pooled like the other small ones).
Chi2Result chi2Test(const std::vector<double>& observed, const std::vector<double>& expected,
                    double minExpected = 5.0, double zeroExpected = 1e-8);

// ---- Histograms on rectangles and on the sphere
// ----------------------------------------------------

/// [x0, x1) x [y0, y1) cut into nx x ny equal cells, cell index = iy * nx + ix.
struct Grid2D {
    double x0 = 0.0, x1 = 1.0, y0 = 0.0, y1 = 1.0;
    int nx = 1, ny = 1;
    int cellCount() const { return nx * ny; }
    /// Cell of (x, y), or -1 outside (and for NaN).
    int cell(double x, double y) const;
};

using Pdf2D = std::function<double(double, double)>;

/// Integral of pdf over every cell of g (probability per cell), by adaptive 2D Simpson
/// quadrature: each cell is quadrisected recursively (error estimate |S_fine - S_coarse| / 15
/// against relTol / cellCount, halved per level) for at least minDepth and at most maxDepth
/// levels, so pdfs with jumps (lights' silhouettes) are refined along the jump only. Features
/// smaller than a cell / 2^(minDepth+1) can be missed entirely; cells that integrate to 0 next
/// to cells that do not are therefore integrated again from a 4x finer start. Raise minDepth
/// for pdfs with corners and thin slivers.
std::vector<double> integrateCells(const Grid2D& g, const Pdf2D& pdf, double relTol = 1e-4,
                                   int maxDepth = 8, int minDepth = 0);

/// Chi-square test of 2D samples against pdf over the grid (expected = N * integrateCells).
/// Samples outside the grid fail the test (they have no expected count).
Chi2Result chi2Test2D(const std::vector<glm::dvec2>& samples, const Grid2D& g, const Pdf2D& pdf);

/// Binning of unit directions in a frame (s, t, n): z = cos(theta) = dir . n and azimuth
/// phi = atan2(dir . t, dir . s) in (-pi, pi]. The patch [zMin, zMax] x [phiMin, phiMax] is cut
/// into nZ x nPhi cells of equal solid angle (equal steps in z and phi, since d(omega) = dz dphi).
/// The rest of the sphere is covered by up to four more cells (z below / above the patch, phi
/// before / after it), so every direction has a cell and an expected count.
/// Choose the frame and the patch so that its cells resolve the pdf: a cap around the direction
/// of a light (around()), or a box around a light seen near the frame's horizon (patch()).
struct SphereBinning {
    glm::dvec3 s{1.0, 0.0, 0.0}, t{0.0, 1.0, 0.0}, n{0.0, 0.0, 1.0};
    double zMin = -1.0, zMax = 1.0;
    double phiMin = -3.14159265358979323846, phiMax = 3.14159265358979323846;
    int nZ = 40;
    int nPhi = 80;
    /// Cap z >= zMin around axis (unit not required), frame tangents of Duff et al. 2017.
    static SphereBinning around(const glm::dvec3& axis, double zMin, int nZ, int nPhi);
    /// Box [zMin, zMax] x [phiMin, phiMax] in the frame around axis.
    static SphereBinning patch(const glm::dvec3& axis, double zMin, double zMax, double phiMin,
                               double phiMax, int nZ, int nPhi);
    /// Patch cells + the rest-of-sphere cells.
    int cellCount() const;
    /// (z, phi) of a direction in this frame (normalised first).
    glm::dvec2 zPhi(const glm::dvec3& dir) const;
};

using PdfDir = std::function<double(const glm::dvec3&)>;  ///< solid-angle density (sr^-1)

/// Probability of every cell of the binning (patch cells first, iz * nPhi + iphi, then the
/// rest-of-sphere cells) under the solid-angle pdf (see integrateCells for the parameters).
std::vector<double> integrateDirectionCells(const SphereBinning& b, const PdfDir& pdf,
                                            double relTol = 1e-4, int maxDepth = 8,
                                            int minDepth = 0);
/// Cell of a direction (normalised first), or -1 for a zero/NaN vector.
int directionCell(const SphereBinning& b, const glm::dvec3& dir);
/// Integral of the solid-angle pdf over the whole sphere of directions (should be 1), using the
/// binning's cells as the quadrature's starting grid.
double integrateOverSphere(const SphereBinning& b, const PdfDir& pdf, double relTol = 1e-5,
                           int maxDepth = 8, int minDepth = 0);
/// Chi-square test of sampled directions against the solid-angle pdf.
Chi2Result chi2TestDirections(const std::vector<glm::dvec3>& dirs, const SphereBinning& b,
                              const PdfDir& pdf);
/// The same with the cell probabilities already computed by integrateDirectionCells (so a test
/// can also check that they sum to 1 without integrating twice).
Chi2Result chi2TestDirections(const std::vector<glm::dvec3>& dirs, const SphereBinning& b,
                              const std::vector<double>& cellProbabilities);

}  // namespace vkp::test
