#include "chi2.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace vkp::test {

// ---- Incomplete gamma (Numerical Recipes 3rd ed., sec. 6.2, re-derived)
// --------------------------

namespace {

constexpr double kEps = 1e-15;
constexpr double kTiny = 1e-300;
constexpr int kMaxIter = 100000;

/// log of the prefactor x^a e^-x / Gamma(a).
double logPrefactor(double a, double x) { return a * std::log(x) - x - std::lgamma(a); }

/// P(a, x) by its power series, sum_n x^n / (a (a+1) ... (a+n)), good for x < a + 1.
double gammaPSeries(double a, double x) {
    double ap = a;
    double term = 1.0 / a;
    double sum = term;
    for (int n = 0; n < kMaxIter; ++n) {
        ap += 1.0;
        term *= x / ap;
        sum += term;
        if (std::fabs(term) < std::fabs(sum) * kEps) break;
    }
    return sum * std::exp(logPrefactor(a, x));
}

/// Q(a, x) by its continued fraction (modified Lentz), good for x >= a + 1.
double gammaQContinuedFraction(double a, double x) {
    double b = x + 1.0 - a;
    double c = 1.0 / kTiny;
    double d = 1.0 / b;
    double h = d;
    for (int i = 1; i < kMaxIter; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < kTiny) d = kTiny;
        c = b + an / c;
        if (std::fabs(c) < kTiny) c = kTiny;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (std::fabs(del - 1.0) < kEps) break;
    }
    return std::exp(logPrefactor(a, x)) * h;
}

}  // namespace

double gammaP(double a, double x) {
    if (!(a > 0.0) || !(x >= 0.0)) return std::numeric_limits<double>::quiet_NaN();
    if (x == 0.0) return 0.0;
    if (x < a + 1.0) return gammaPSeries(a, x);
    return 1.0 - gammaQContinuedFraction(a, x);
}

double gammaQ(double a, double x) {
    if (!(a > 0.0) || !(x >= 0.0)) return std::numeric_limits<double>::quiet_NaN();
    if (x == 0.0) return 1.0;
    if (x < a + 1.0) return 1.0 - gammaPSeries(a, x);
    return gammaQContinuedFraction(a, x);
}

double chi2PValue(double statistic, int dof) {
    if (dof <= 0) return 1.0;
    if (!(statistic >= 0.0)) return 0.0;  // NaN or negative: not a valid statistic
    if (std::isinf(statistic)) return 0.0;
    return gammaQ(0.5 * dof, 0.5 * statistic);
}

double chi2LowerTail(double statistic, int dof) {
    if (dof <= 0) return 0.0;
    if (!(statistic >= 0.0)) return 1.0;
    if (std::isinf(statistic)) return 1.0;
    return gammaP(0.5 * dof, 0.5 * statistic);
}

double sidakAlpha(double alpha, int numTests) {
    return 1.0 - std::pow(1.0 - alpha, 1.0 / static_cast<double>(numTests));
}

// ---- Pearson's test with pooling
// -----------------------------------------------------------------

Chi2Result chi2Test(const std::vector<double>& observed, const std::vector<double>& expected,
                    double minExpected, double zeroExpected) {
    Chi2Result r;
    if (observed.size() != expected.size()) {
        r.pValue = 0.0;
        r.message = "observed/expected size mismatch";
        return r;
    }
    double total = std::accumulate(observed.begin(), observed.end(), 0.0);
    double strayLimit = std::max(1.0, 1e-5 * total);
    std::vector<size_t> order(expected.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return expected[a] < expected[b]; });

    struct Cell {
        double obs;
        double exp;
    };
    std::vector<Cell> cells;
    double poolObs = 0.0, poolExp = 0.0;
    int pooledCount = 0;
    for (size_t i : order) {
        double o = observed[i], e = expected[i];
        if (e <= zeroExpected) {
            if (o > strayLimit) {
                char buf[160];
                std::snprintf(buf, sizeof buf,
                              "cell %zu has %.0f samples but expected count %.3g (pdf ~ 0 there)",
                              i, o, e);
                r.pValue = 0.0;
                r.statistic = std::numeric_limits<double>::infinity();
                r.message = buf;
                return r;
            }
            if (o == 0.0) continue;  // empty and impossible: no information, no degree of freedom
        }
        if (e < minExpected) {
            poolObs += o;
            poolExp += e;
            ++pooledCount;
            if (poolExp >= minExpected) {
                cells.push_back({poolObs, poolExp});
                poolObs = poolExp = 0.0;
            }
        } else {
            cells.push_back({o, e});
        }
    }
    if (poolExp > 0.0 || poolObs > 0.0) {
        if (cells.empty()) {
            cells.push_back({poolObs, poolExp});
        } else {
            auto smallest =
                std::min_element(cells.begin(), cells.end(),
                                 [](const Cell& a, const Cell& b) { return a.exp < b.exp; });
            smallest->obs += poolObs;
            smallest->exp += poolExp;
        }
    }
    for (const Cell& c : cells) r.statistic += (c.obs - c.exp) * (c.obs - c.exp) / c.exp;
    r.cells = static_cast<int>(cells.size());
    r.dof = r.cells - 1;
    r.pValue = chi2PValue(r.statistic, r.dof);
    char buf[200];
    std::snprintf(buf, sizeof buf, "chi2 = %.2f, dof = %d, p = %.3g (%d cells pooled)", r.statistic,
                  r.dof, r.pValue, pooledCount);
    r.message = buf;
    return r;
}

// ---- Adaptive Simpson quadrature over rectangles
// ----------------------------------------------------

int Grid2D::cell(double x, double y) const {
    double fx = (x - x0) / (x1 - x0) * nx;
    double fy = (y - y0) / (y1 - y0) * ny;
    if (!(fx >= 0.0 && fx <= nx && fy >= 0.0 && fy <= ny)) return -1;
    int ix = std::min(static_cast<int>(fx), nx - 1);
    int iy = std::min(static_cast<int>(fy), ny - 1);
    return iy * nx + ix;
}

namespace {

/// Simpson's rule on a 3x3 grid g[i][j] (i along x, j along y) over a rectangle of area `area`.
double simpson9(const double g[3][3], double area) {
    const double w[3] = {1.0, 4.0, 1.0};
    double s = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s += w[i] * w[j] * g[i][j];
    return s * area / 36.0;
}

/// Adaptive Simpson over [x0,x1] x [y0,y1], given the pdf on its 3x3 grid: the 5x5 grid of the
/// four quarters is completed, and the quarters are refined where the two estimates disagree.
double adaptiveRect(const Pdf2D& f, double x0, double x1, double y0, double y1,
                    const double coarse[3][3], double tol, int depth, int forced) {
    double g[5][5];
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 5; ++j) {
            if (i % 2 == 0 && j % 2 == 0) {
                g[i][j] = coarse[i / 2][j / 2];
            } else {
                g[i][j] = f(x0 + (x1 - x0) * 0.25 * i, y0 + (y1 - y0) * 0.25 * j);
            }
        }
    }
    double area = (x1 - x0) * (y1 - y0);
    double whole = simpson9(coarse, area);
    double sub[2][2][3][3];
    double sum = 0.0;
    for (int ci = 0; ci < 2; ++ci) {
        for (int cj = 0; cj < 2; ++cj) {
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) sub[ci][cj][i][j] = g[2 * ci + i][2 * cj + j];
            sum += simpson9(sub[ci][cj], 0.25 * area);
        }
    }
    bool converged = forced <= 0 && std::fabs(sum - whole) <= 15.0 * tol;
    if (depth <= 0 || converged) return sum + (sum - whole) / 15.0;
    double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
    double total = 0.0;
    for (int ci = 0; ci < 2; ++ci) {
        for (int cj = 0; cj < 2; ++cj) {
            total += adaptiveRect(f, ci ? xm : x0, ci ? x1 : xm, cj ? ym : y0, cj ? y1 : ym,
                                  sub[ci][cj], 0.5 * tol, depth - 1, forced - 1);
        }
    }
    return total;
}

double integrateRect(const Pdf2D& f, double x0, double x1, double y0, double y1, double tol,
                     int maxDepth, int minDepth) {
    double coarse[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            coarse[i][j] = f(x0 + (x1 - x0) * 0.5 * i, y0 + (y1 - y0) * 0.5 * j);
    return adaptiveRect(f, x0, x1, y0, y1, coarse, tol, std::max(maxDepth, minDepth), minDepth);
}

}  // namespace

std::vector<double> integrateCells(const Grid2D& g, const Pdf2D& pdf, double relTol, int maxDepth,
                                   int minDepth) {
    std::vector<double> p(static_cast<size_t>(g.cellCount()));
    double hx = (g.x1 - g.x0) / g.nx, hy = (g.y1 - g.y0) / g.ny;
    double tol = relTol / g.cellCount();
    for (int iy = 0; iy < g.ny; ++iy) {
        for (int ix = 0; ix < g.nx; ++ix) {
            double x0 = g.x0 + ix * hx, y0 = g.y0 + iy * hy;
            p[static_cast<size_t>(iy * g.nx + ix)] =
                integrateRect(pdf, x0, x0 + hx, y0, y0 + hy, tol, maxDepth, minDepth);
        }
    }
    // A cell that came out empty next to one that did not may hold a sliver of the pdf's support
    // that fell between its quadrature points: integrate it again on a 4x finer starting grid.
    std::vector<double> first = p;
    auto nonzero = [&](int ix, int iy) {
        return ix >= 0 && iy >= 0 && ix < g.nx && iy < g.ny &&
               first[static_cast<size_t>(iy * g.nx + ix)] != 0.0;
    };
    for (int iy = 0; iy < g.ny; ++iy) {
        for (int ix = 0; ix < g.nx; ++ix) {
            if (first[static_cast<size_t>(iy * g.nx + ix)] != 0.0) continue;
            bool edge = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) edge = edge || nonzero(ix + dx, iy + dy);
            if (!edge) continue;
            double x0 = g.x0 + ix * hx, y0 = g.y0 + iy * hy;
            p[static_cast<size_t>(iy * g.nx + ix)] =
                integrateRect(pdf, x0, x0 + hx, y0, y0 + hy, tol, maxDepth + 2, minDepth + 2);
        }
    }
    return p;
}

Chi2Result chi2Test2D(const std::vector<glm::dvec2>& samples, const Grid2D& g, const Pdf2D& pdf) {
    std::vector<double> observed(static_cast<size_t>(g.cellCount()), 0.0);
    size_t outside = 0;
    for (const glm::dvec2& s : samples) {
        int c = g.cell(s.x, s.y);
        if (c < 0) {
            ++outside;
        } else {
            observed[static_cast<size_t>(c)] += 1.0;
        }
    }
    if (outside > 0) {
        Chi2Result r;
        r.pValue = 0.0;
        r.message = std::to_string(outside) + " samples outside the domain";
        return r;
    }
    std::vector<double> expected = integrateCells(g, pdf);
    for (double& e : expected) e *= static_cast<double>(samples.size());
    return chi2Test(observed, expected);
}

// ---- Directions
// -------------------------------------------------------------------------------------

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Duff et al. 2017 frame around a unit axis.
void frameAround(const glm::dvec3& axis, SphereBinning& b) {
    glm::dvec3 n = glm::normalize(axis);
    double sgn = n.z >= 0.0 ? 1.0 : -1.0;
    double a = -1.0 / (sgn + n.z);
    double c = n.x * n.y * a;
    b.s = {1.0 + sgn * n.x * n.x * a, sgn * c, -sgn * n.x};
    b.t = {c, sgn + n.y * n.y * a, -n.y};
    b.n = n;
}

/// The rectangles in (phi, z) that cover the sphere outside the patch (each one histogram cell).
std::vector<Grid2D> restOfSphere(const SphereBinning& b) {
    std::vector<Grid2D> rest;
    if (b.zMin > -1.0) rest.push_back(Grid2D{-kPi, kPi, -1.0, b.zMin, 16, 16});
    if (b.zMax < 1.0) rest.push_back(Grid2D{-kPi, kPi, b.zMax, 1.0, 16, 16});
    if (b.phiMin > -kPi) rest.push_back(Grid2D{-kPi, b.phiMin, b.zMin, b.zMax, 16, 16});
    if (b.phiMax < kPi) rest.push_back(Grid2D{b.phiMax, kPi, b.zMin, b.zMax, 16, 16});
    return rest;
}

Grid2D patchGrid(const SphereBinning& b) {
    return Grid2D{b.phiMin, b.phiMax, b.zMin, b.zMax, b.nPhi, b.nZ};
}

/// The pdf as a density over (phi, z): d(omega) = dz dphi, so the same values.
Pdf2D inZPhi(const SphereBinning& b, const PdfDir& pdf) {
    return [&b, &pdf](double phi, double z) {
        double r = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
        glm::dvec3 d = r * std::cos(phi) * b.s + r * std::sin(phi) * b.t + z * b.n;
        return pdf(d);
    };
}

}  // namespace

SphereBinning SphereBinning::around(const glm::dvec3& axis, double zMin, int nZ, int nPhi) {
    SphereBinning b;
    frameAround(axis, b);
    b.zMin = zMin;
    b.nZ = nZ;
    b.nPhi = nPhi;
    return b;
}

SphereBinning SphereBinning::patch(const glm::dvec3& axis, double zMin, double zMax, double phiMin,
                                   double phiMax, int nZ, int nPhi) {
    SphereBinning b = around(axis, zMin, nZ, nPhi);
    b.zMax = zMax;
    b.phiMin = phiMin;
    b.phiMax = phiMax;
    return b;
}

int SphereBinning::cellCount() const {
    return nZ * nPhi + static_cast<int>(restOfSphere(*this).size());
}

glm::dvec2 SphereBinning::zPhi(const glm::dvec3& dir) const {
    glm::dvec3 d = glm::normalize(dir);
    return {std::clamp(glm::dot(d, n), -1.0, 1.0), std::atan2(glm::dot(d, t), glm::dot(d, s))};
}

std::vector<double> integrateDirectionCells(const SphereBinning& b, const PdfDir& pdf,
                                            double relTol, int maxDepth, int minDepth) {
    Pdf2D f = inZPhi(b, pdf);
    std::vector<double> cells = integrateCells(patchGrid(b), f, relTol, maxDepth, minDepth);
    for (const Grid2D& g : restOfSphere(b)) {
        std::vector<double> sub = integrateCells(g, f, relTol, maxDepth, minDepth);
        cells.push_back(std::accumulate(sub.begin(), sub.end(), 0.0));
    }
    return cells;
}

int directionCell(const SphereBinning& b, const glm::dvec3& dir) {
    if (!(glm::length(dir) > 0.0)) return -1;
    glm::dvec2 zp = b.zPhi(dir);
    int c = patchGrid(b).cell(zp.y, zp.x);
    if (c >= 0) return c;
    std::vector<Grid2D> rest = restOfSphere(b);
    for (size_t i = 0; i < rest.size(); ++i) {
        if (rest[i].cell(zp.y, zp.x) >= 0) return b.nZ * b.nPhi + static_cast<int>(i);
    }
    return -1;  // NaN
}

double integrateOverSphere(const SphereBinning& b, const PdfDir& pdf, double relTol, int maxDepth,
                           int minDepth) {
    std::vector<double> cells = integrateDirectionCells(b, pdf, relTol, maxDepth, minDepth);
    return std::accumulate(cells.begin(), cells.end(), 0.0);
}

Chi2Result chi2TestDirections(const std::vector<glm::dvec3>& dirs, const SphereBinning& b,
                              const PdfDir& pdf) {
    return chi2TestDirections(dirs, b, integrateDirectionCells(b, pdf));
}

Chi2Result chi2TestDirections(const std::vector<glm::dvec3>& dirs, const SphereBinning& b,
                              const std::vector<double>& cellProbabilities) {
    size_t cellCount = static_cast<size_t>(b.cellCount());
    if (cellProbabilities.size() != cellCount) {
        Chi2Result r;
        r.pValue = 0.0;
        r.message = "cell probabilities do not match the binning";
        return r;
    }
    std::vector<double> observed(cellCount, 0.0);
    for (const glm::dvec3& d : dirs) {
        int c = directionCell(b, d);
        if (c < 0) {
            Chi2Result r;
            r.pValue = 0.0;
            r.message = "a sampled direction is zero or NaN";
            return r;
        }
        observed[static_cast<size_t>(c)] += 1.0;
    }
    std::vector<double> expected = cellProbabilities;
    for (double& e : expected) e *= static_cast<double>(dirs.size());
    return chi2Test(observed, expected);
}

}  // namespace vkp::test
