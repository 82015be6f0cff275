// shared/compensated_sum.h, the C++ build of the code the kernel runs on its pixel sums.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shared/compensated_sum.h"

namespace vkp::gpu {
namespace {

// 10^6 values of mixed magnitude and sign: the pair (hi, lo) matches the exact sum (a long-double
// sum of the same floats) to 1e-8 relative (bound ~n eps^2 = 3.6e-9); a plain float sum of the same
// values is far off, and so is Neumaier's compensated sum without renormalisation (lo's own
// rounding: 1e6 additions of 0.1f are off by 6e-5 relative), which this tolerance would catch.
TEST(CompensatedSum, MatchesExactSumWhereAFloatSumDrifts) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    vec4 hi(0.0f), lo(0.0f), plain(0.0f);
    long double exact[4] = {0, 0, 0, 0};
    for (int i = 0; i < 1000000; ++i) {
        const vec4 x(u(rng), 0.1f, u(rng) * 1e3f - 500.0f, (i % 3 == 0) ? 1e-4f : 1.0f);
        addCompensated(hi, lo, x);
        plain += x;
        for (int c = 0; c < 4; ++c) exact[c] += x[c];
    }
    for (int c = 0; c < 4; ++c) {
        const long double got = (long double)hi[c] + (long double)lo[c];
        const long double scale = std::max<long double>(std::fabs(exact[c]), 1.0L);
        EXPECT_LT(std::fabs(double((got - exact[c]) / scale)), 1e-8) << "channel " << c;
        EXPECT_GT(std::fabs(double((plain[c] - exact[c]) / scale)), 1e-6) << "plain float sum: no teeth, channel " << c;
    }
}

// Integers below 2^24 stay exact (the sample count in w), and lo stays 0 for them.
TEST(CompensatedSum, CountsStayExact) {
    vec4 hi(0.0f), lo(0.0f);
    for (int i = 0; i < 100000; ++i) addCompensated(hi, lo, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    EXPECT_EQ(hi.w, 100000.0f);
    EXPECT_EQ(lo.w, 0.0f);
}

// Cancellation: adding x then -x leaves exactly what was there, big and small alike.
TEST(CompensatedSum, CancellationIsExact) {
    vec4 hi(0.0f), lo(0.0f);
    addCompensated(hi, lo, vec4(1.0f, 1e8f, 3.0f, 0.0f));
    addCompensated(hi, lo, vec4(1e-8f, 1.0f, 1e30f, 0.0f));
    addCompensated(hi, lo, vec4(-1.0f, -1e8f, -1e30f, 0.0f));
    EXPECT_EQ(double(hi.x) + double(lo.x), double(1e-8f));
    EXPECT_EQ(double(hi.y) + double(lo.y), 1.0);
    EXPECT_EQ(double(hi.z) + double(lo.z), 3.0);
}

}  // namespace
}  // namespace vkp::gpu
