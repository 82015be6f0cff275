// Light selection by power: the alias table reproduces the power distribution exactly, and the
// shared pick routine (shaders/shared/light_pick.h, the code the kernel runs) picks each light with
// the probability it reports.
#include <gtest/gtest.h>

#include <random>

#include "chi2.h"
#include "render/light_table.h"
#include "shared/light_pick.h"
#include "stat_suite.h"

namespace vkp {
namespace {

TEST(LightTable, AliasTableReproducesTheDistributionExactly) {
    const std::vector<double> w = {1.0, 0.0, 7.0, 2.0, 0.5, 0.0, 30.0};
    const AliasTable t = buildAliasTable(w);
    const double sum = 40.5;
    std::vector<double> p(w.size(), 0.0);
    for (std::size_t i = 0; i < w.size(); ++i) {
        ASSERT_GE(t.threshold[i], 0.0f);
        ASSERT_LE(t.threshold[i], 1.0f);
        ASSERT_LT(t.alias[i], w.size());
        p[i] += t.threshold[i] / double(w.size());
        p[t.alias[i]] += (1.0 - t.threshold[i]) / double(w.size());
    }
    for (std::size_t i = 0; i < w.size(); ++i) {
        EXPECT_NEAR(p[i], w[i] / sum, 1e-6) << i;
        EXPECT_NEAR(t.probability[i], w[i] / sum, 1e-7) << i;
    }
}

TEST(LightTable, AllZeroWeightsGiveNoPicks) {
    const AliasTable t = buildAliasTable({0.0, 0.0});
    EXPECT_EQ(t.probability[0], 0.0f);
    EXPECT_EQ(t.probability[1], 0.0f);
}

// Chi-square test of the pick frequencies against the reported probabilities, with the shared
// routine fed by the suite's uniform source. Fixed seed; false-failure probability statsAlpha()
// (the stats suite's Sidak share, see stat_suite.h).
TEST(LightTable, SharedPickMatchesReportedProbabilities) {
    const std::vector<double> w = {3.0, 0.0, 1.0, 12.0, 0.25, 5.0};
    const AliasTable t = buildAliasTable(w);
    std::vector<gpu::GpuLight> lights(w.size());
    for (std::size_t i = 0; i < w.size(); ++i)
        lights[i].l0 = glm::vec4(0.0f, t.probability[i], t.threshold[i], glm::uintBitsToFloat(t.alias[i]));
    test::UniformSource rng(12345);
    const int n = 200000;
    std::vector<double> observed(w.size(), 0.0), expected(w.size(), 0.0);
    for (int k = 0; k < n; ++k) {
        float frac;
        const std::uint32_t column = gpu::aliasColumn(rng.next(), std::uint32_t(w.size()), frac);
        const std::uint32_t li = gpu::aliasResolve(column, frac, lights[column]);
        ASSERT_LT(li, w.size());
        observed[li] += 1.0;
    }
    for (std::size_t i = 0; i < w.size(); ++i) expected[i] = n * double(lights[i].l0.y);
    EXPECT_EQ(observed[1], 0.0);  // a light of zero power is never picked
    EXPECT_TRUE(test::passesChi2(test::chi2Test(observed, expected))) << "pick frequencies differ from reported pdfs";
}

TEST(LightTable, PowerHeuristic) {
    EXPECT_FLOAT_EQ(gpu::powerHeuristic(1.0f, 1.0f), 0.5f);
    EXPECT_FLOAT_EQ(gpu::powerHeuristic(3.0f, 1.0f), 0.9f);
    EXPECT_EQ(gpu::powerHeuristic(0.0f, 0.0f), 0.0f);
    EXPECT_EQ(gpu::powerHeuristic(0.0f, 2.0f), 0.0f);
}

}  // namespace
}  // namespace vkp
