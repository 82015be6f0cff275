// Building the tables of shaders/shared/distribution.h (piecewise-constant 1D/2D distributions
// sampled by inverting their CDF; pbrt-v4 sec. A.5) from non-negative weights.
#pragma once
#include <cstdint>
#include <vector>

namespace vkp {

/// Appends the 1D table of `weights` (n = weights.size() >= 1 cells) to `out`: CDF then densities.
/// Negative and NaN weights count as 0; all-zero weights give the uniform distribution.
void appendDistribution1D(const std::vector<double>& weights, std::vector<float>& out);

/// The 2D table of nu x nv weights (row-major, nv rows of nu: weights[r * nu + c]): the marginal
/// over rows (a row's weight is the sum of its cells) and one conditional per row.
std::vector<float> buildDistribution2D(const std::vector<double>& weights, std::uint32_t nu, std::uint32_t nv);

}  // namespace vkp
