// Shared settings of the statistical tests (label `stats`): the uniform source they draw from and
// the family-wise significance.
//
// Significance: every chi-square test in tests/stats runs at the Sidak-corrected level
// kStatsAlpha = 1 - (1 - 0.01)^(1/kStatsChi2Budget), so that, if every routine is correct, the
// probability that at least one of up to kStatsChi2Budget independent tests fails is <= 1%.
// The seeds are fixed, so a given build either always passes or always fails: the 1% is the chance
// that the fixed seeds are "unlucky" for correct code. kStatsChi2Budget is an upper bound on the
// number of chi-square tests in the suite (a larger bound only makes each test stricter about
// false failures); raise it if the suite grows beyond it.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <glm/glm.hpp>
#include <random>

#include "chi2.h"

namespace vkp::test {

constexpr double kStatsFamilyAlpha = 0.01;
constexpr int kStatsChi2Budget = 128;
/// Per-test significance (~7.85e-5).
inline double statsAlpha() { return sidakAlpha(kStatsFamilyAlpha, kStatsChi2Budget); }

/// gtest predicate: the test's p-value is at least statsAlpha(). The message carries the
/// statistic, the degrees of freedom and the p-value.
inline ::testing::AssertionResult passesChi2(const Chi2Result& r) {
    std::printf("    [chi2] %s\n", r.message.c_str());
    if (r.pValue >= statsAlpha()) return ::testing::AssertionSuccess() << r.message;
    return ::testing::AssertionFailure() << r.message << " (alpha = " << statsAlpha() << ")";
}

/// Two-sided version for random number generators: also rejects a statistic that is too small
/// (P(X <= statistic) < alpha/2), the signature of a too-regular sequence such as a bare LCG.
/// Each side gets alpha/2, so the false-failure rate is the same as passesChi2's.
inline ::testing::AssertionResult passesChi2TwoSided(const Chi2Result& r) {
    std::printf("    [chi2] %s\n", r.message.c_str());
    double lower = chi2LowerTail(r.statistic, r.dof);
    if (r.pValue >= 0.5 * statsAlpha() && lower >= 0.5 * statsAlpha())
        return ::testing::AssertionSuccess() << r.message;
    return ::testing::AssertionFailure()
           << r.message << ", lower tail " << lower << " (alpha/2 = " << 0.5 * statsAlpha() << ")";
}

/// Uniform numbers for the tests, independent of the renderer's own RNG (rng.h) so that a bug
/// there cannot hide a bug in a warp. mt19937 is fully specified by the C++ standard; floats are
/// built from the top 24 bits, so the stream is identical on every platform and never yields 1.0.
class UniformSource {
public:
    explicit UniformSource(std::uint32_t seed) : gen_(seed) {}
    float next() { return static_cast<float>(gen_() >> 8) * (1.0f / 16777216.0f); }
    glm::vec2 next2() {
        float a = next();
        return {a, next()};
    }
    glm::vec3 next3() {
        float a = next();
        float b = next();
        return {a, b, next()};
    }

private:
    std::mt19937 gen_;
};

}  // namespace vkp::test
