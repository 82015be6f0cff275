// Piecewise-constant 1D and 2D distributions sampled by inverting their CDF (binary search):
// pbrt-v4 sec. A.5.1-A.5.2 (PiecewiseConstant1D / PiecewiseConstant2D) and "Ray Tracing: The Rest
// of Your Life" sec. 3 ("inverting the CDF"). The general "sample any tabulated pdf" machinery;
// the environment light (lib/environment.glsl) uses the 2D form.
//
// Table layout: one flat array of floats (built on the host by host/render/distribution_table.cpp).
//   1D distribution of n cells at `base`:  cdf[0..n] (cdf[0] = 0, cdf[n] = 1) at base,
//                                          density[0..n-1] at base + n + 1 (density of cell i on
//                                          [0,1): n * P(cell i), so it integrates to 1).
//   2D distribution of nu x nv cells (nv rows of nu columns, row-major like an image) at `base`:
//                                          the marginal over rows, a 1D distribution of nv cells, at
//                                          base, then the conditional of row r, a 1D distribution of
//                                          nu cells, at base + distSize1D(nv) + r * distSize1D(nu).
// Data access differs between the languages, so the including side provides it:
//   C++:  every function takes `const float* table` first (VKP_DIST_PARAM / VKP_DIST_ARG);
//   GLSL: define `float distFetch(uint i)` (e.g. a texelFetch from a samplerBuffer) before
//         including this header; the functions then take no table argument.
// The density reported for a sample is the table's density (as pbrt), so sample and pdf agree bit
// for bit; cells of zero density are never sampled (binary search skips zero-width CDF steps).
// Limit: the CDF is stored in floats, so a cell whose probability is below ~6e-8 of its row (or
// of the marginal) may get a zero-width step and never be sampled although its density is > 0
// (the builder keeps such densities > 0, so MIS and the pdf stay right; only the `light` sampler,
// which relies on light sampling alone, would miss that sliver of radiance).
#ifndef VKP_DISTRIBUTION_H
#define VKP_DISTRIBUTION_H
#include "glsl_compat.h"

#ifdef __cplusplus
#define VKP_DIST_PARAM const float *table,
#define VKP_DIST_ARG table,
#define VKP_DIST_AT(i) table[i]
#else
#define VKP_DIST_PARAM
#define VKP_DIST_ARG
#define VKP_DIST_AT(i) distFetch(i)
#endif

VKP_BEGIN

/// Floats of a 1D distribution of n cells: n + 1 CDF values and n densities.
VKP_FN uint distSize1D(uint n) { return 2u * n + 1u; }
/// Floats of a 2D distribution of nu x nv cells.
VKP_FN uint distSize2D(uint nu, uint nv) { return distSize1D(nv) + nv * distSize1D(nu); }

/// The cell i of the 1D distribution at base with cdf[i] <= u < cdf[i+1] (u in [0,1)), found by
/// binary search (pbrt-v4's FindInterval); the last cell whose CDF step is > 0 when rounding puts
/// u at or past the end. O(log n) fetches.
VKP_FN uint distFindCell(VKP_DIST_PARAM uint base, uint n, float u) {
    // Largest i in [0, n-1] with cdf[i] <= u.
    uint first = 0u;
    uint size = n;  // candidates [first, first + size)
    while (size > 1u) {
        uint h = size / 2u;
        uint mid = first + h;
        if (VKP_DIST_AT(base + mid) <= u) {
            first = mid;
            size -= h;
        } else {
            size = h;
        }
    }
    return first;
}

/// Cell of x in [0,1] among n equal cells (x = 1 belongs to the last one).
VKP_FN uint distCellOf(float x, uint n) { return min(uint(max(x, 0.0f) * float(n)), n - 1u); }

/// The point (i + du) / n, moved by an ulp or two if rounding put it outside cell i, so that
/// distCellOf gives i back (the pdf of a sample is then always the density of its cell).
VKP_FN float distPointInCell(uint i, uint n, float du) {
    float x = min((float(i) + du) / float(n), 0.99999994f);
    for (int k = 0; k < 2; ++k) {
        uint c = distCellOf(x, n);
        if (c > i) x = uintBitsToFloat(floatBitsToUint(x) - 1u);
        if (c < i) x = uintBitsToFloat(floatBitsToUint(x) + 1u);
    }
    return x;
}

/// Samples the 1D distribution at base (n cells) with u in [0,1): x in [0,1), its density in pdf,
/// the cell in cell. Within a cell x is uniform (u is remapped linearly).
VKP_FN float sampleDistribution1D(VKP_DIST_PARAM uint base, uint n, float u, OUT(float) pdf, OUT(uint) cell) {
    uint i = distFindCell(VKP_DIST_ARG base, n, u);
    float c0 = VKP_DIST_AT(base + i);
    float c1 = VKP_DIST_AT(base + i + 1u);
    float du = (c1 > c0) ? (u - c0) / (c1 - c0) : 0.0f;
    du = min(max(du, 0.0f), 0.99999994f);
    pdf = VKP_DIST_AT(base + n + 1u + i);
    cell = i;
    return distPointInCell(i, n, du);
}

/// Density of the 1D distribution at base (n cells) at x in [0,1] (x = 1 belongs to the last cell).
VKP_FN float pdfDistribution1D(VKP_DIST_PARAM uint base, uint n, float x) {
    return VKP_DIST_AT(base + n + 1u + distCellOf(x, n));
}

/// The u that sampleDistribution1D maps to x (for x in a cell of density > 0).
VKP_FN float invertDistribution1D(VKP_DIST_PARAM uint base, uint n, float x) {
    float xn = max(x, 0.0f) * float(n);
    uint i = min(uint(xn), n - 1u);
    float c0 = VKP_DIST_AT(base + i);
    float c1 = VKP_DIST_AT(base + i + 1u);
    return c0 + min(xn - float(i), 1.0f) * (c1 - c0);
}

/// Samples the 2D distribution at base (nu columns, nv rows) with u in [0,1)^2: first the row v
/// from the marginal with u.y, then the column within that row from its conditional with u.x.
/// Returns (x, y) in [0,1)^2 (x across a row, y down the rows); pdf = p(x, y), the density on the
/// unit square (integrates to 1).
VKP_FN vec2 sampleDistribution2D(VKP_DIST_PARAM uint base, uint nu, uint nv, vec2 u, OUT(float) pdf) {
    float pv;
    uint row;
    float y = sampleDistribution1D(VKP_DIST_ARG base, nv, u.y, pv, row);
    float pu;
    uint col;
    float x = sampleDistribution1D(VKP_DIST_ARG base + distSize1D(nv) + row * distSize1D(nu), nu, u.x, pu, col);
    pdf = pv * pu;
    return vec2(x, y);
}

/// Density of the 2D distribution at (x, y) in [0,1]^2.
VKP_FN float pdfDistribution2D(VKP_DIST_PARAM uint base, uint nu, uint nv, vec2 p) {
    uint row = distCellOf(p.y, nv);
    float pv = pdfDistribution1D(VKP_DIST_ARG base, nv, p.y);
    float pu = pdfDistribution1D(VKP_DIST_ARG base + distSize1D(nv) + row * distSize1D(nu), nu, p.x);
    return pv * pu;
}

/// The u that sampleDistribution2D maps to (x, y) (for a point of density > 0).
VKP_FN vec2 invertDistribution2D(VKP_DIST_PARAM uint base, uint nu, uint nv, vec2 p) {
    uint row = distCellOf(p.y, nv);
    float uy = invertDistribution1D(VKP_DIST_ARG base, nv, p.y);
    float ux = invertDistribution1D(VKP_DIST_ARG base + distSize1D(nv) + row * distSize1D(nu), nu, p.x);
    return vec2(ux, uy);
}

VKP_END
#endif
