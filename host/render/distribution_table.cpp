#include "render/distribution_table.h"

#include <cmath>
#include <stdexcept>

#include "shared/distribution.h"

namespace vkp {

namespace {
double clean(double w) { return (w > 0.0 && std::isfinite(w)) ? w : 0.0; }
}  // namespace

void appendDistribution1D(const std::vector<double>& weights, std::vector<float>& out) {
    const std::size_t n = weights.size();
    if (n == 0) throw std::invalid_argument("appendDistribution1D: no cells");
    double sum = 0.0;
    for (double w : weights) sum += clean(w);
    const bool uniform = !(sum > 0.0);
    std::vector<double> cdf(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + (uniform ? 1.0 : clean(weights[i]));
    const double total = cdf[n];
    for (std::size_t i = 0; i <= n; ++i) out.push_back(i == n ? 1.0f : float(cdf[i] / total));
    for (std::size_t i = 0; i < n; ++i) {
        const double p = (uniform ? 1.0 : clean(weights[i])) / total;
        // A cell with weight keeps a density > 0 even if it underflows (never a zero pdf where
        // the function is not zero).
        float d = float(p * double(n));
        if (p > 0.0 && !(d > 0.0f)) d = 1e-38f;
        out.push_back(d);
    }
}

std::vector<float> buildDistribution2D(const std::vector<double>& weights, std::uint32_t nu, std::uint32_t nv) {
    if (nu == 0 || nv == 0 || weights.size() != std::size_t(nu) * nv)
        throw std::invalid_argument("buildDistribution2D: weights must hold nu * nv > 0 values");
    std::vector<double> rows(nv, 0.0);
    for (std::uint32_t r = 0; r < nv; ++r)
        for (std::uint32_t c = 0; c < nu; ++c) rows[r] += clean(weights[std::size_t(r) * nu + c]);
    std::vector<float> out;
    out.reserve(gpu::distSize2D(nu, nv));
    appendDistribution1D(rows, out);
    std::vector<double> row(nu);
    for (std::uint32_t r = 0; r < nv; ++r) {
        for (std::uint32_t c = 0; c < nu; ++c) row[c] = weights[std::size_t(r) * nu + c];
        appendDistribution1D(row, out);
    }
    return out;
}

}  // namespace vkp
