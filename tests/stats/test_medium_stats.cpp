// Statistical and numerical tests of shaders/shared/medium.h (compiled as C++): the free-flight
// distance triple (sampleFreeFlight, pdfFreeFlight, invertFreeFlight) and the isotropic phase
// function's (sampleIsotropicPhase, pdfIsotropicPhase, invertIsotropicPhase): chi-square goodness
// of fit of the samples against the pdf, the pdf's integral, the sample -> invert round trip.
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: the whole stats suite
// falsely fails with probability <= 1% for correct code; the seeds are fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "shared/medium.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;

constexpr int kSamples = 200000;

// Free flight in densities from thin fog to dense smoke: 64 equal cells of optical depth up to 8
// (the tail beyond, probability e^-8, pooled with the last cell), expected counts from the
// closed-form integral of the pdf over each cell.
TEST(MediumStats, FreeFlightFollowsItsPdf) {
    std::uint32_t seed = 4201;
    for (float sigma : {1e-4f, 0.01f, 1.0f, 25.0f}) {
        SCOPED_TRACE(sigma);
        UniformSource rng(seed++);
        const int cells = 64;
        const double tMax = 8.0 / sigma, width = tMax / cells;
        std::vector<double> observed(cells, 0.0), expected(cells, 0.0);
        double worstTrip = 0.0;
        for (int i = 0; i < kSamples; ++i) {
            const float u = rng.next();
            const float t = gpu::sampleFreeFlight(sigma, u);
            ASSERT_TRUE(std::isfinite(t) && t >= 0.0f) << "u " << u;
            observed[std::min(cells - 1, int(double(t) / width))] += 1.0;
            worstTrip = std::max(worstTrip, std::fabs(double(gpu::invertFreeFlight(sigma, t)) - u));
        }
        for (int c = 0; c < cells; ++c) {
            const double a = c * width, b = (c == cells - 1) ? INFINITY : (c + 1) * width;
            expected[c] = kSamples * (std::exp(-sigma * a) - (std::isinf(b) ? 0.0 : std::exp(-sigma * b)));
        }
        // The pdf integrates to 1 (midpoint rule on a fine grid to 40 optical depths).
        double integral = 0.0;
        const int steps = 400000;
        const double h = 40.0 / sigma / steps;
        for (int k = 0; k < steps; ++k) integral += double(gpu::pdfFreeFlight(sigma, float((k + 0.5) * h))) * h;
        std::printf("    sigma %g: pdf integral %.6f, worst round trip %.2e\n", double(sigma), integral, worstTrip);
        EXPECT_NEAR(integral, 1.0, 1e-4);
        EXPECT_LT(worstTrip, 2e-6);
        EXPECT_TRUE(passesChi2(chi2Test(observed, expected)));
        EXPECT_EQ(gpu::pdfFreeFlight(sigma, -1.0f), 0.0f);
        EXPECT_NEAR(gpu::freeFlightTransmittance(sigma, 2.0f / sigma), std::exp(-2.0), 1e-6);
    }
}

// The isotropic phase function: uniform on the sphere, value = density = 1/(4 pi).
TEST(MediumStats, IsotropicPhaseIsUniformOnTheSphere) {
    UniformSource rng(4301);
    std::vector<glm::dvec3> dirs;
    double worstTrip = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const glm::vec2 u = rng.next2();
        const glm::vec3 w = gpu::sampleIsotropicPhase(u);
        ASSERT_NEAR(glm::length(w), 1.0f, 1e-6f);
        dirs.emplace_back(w);
        const glm::vec2 back = gpu::invertIsotropicPhase(w);
        const double dy = std::fabs(double(back.y) - u.y);
        worstTrip = std::max({worstTrip, std::fabs(double(back.x) - u.x), std::min(dy, 1.0 - dy)});
    }
    SphereBinning bins;
    bins.zMin = -1.0;
    bins.nZ = 30;
    bins.nPhi = 40;
    const PdfDir pdf = [](const glm::dvec3&) { return double(gpu::pdfIsotropicPhase()); };
    const std::vector<double> cells = integrateDirectionCells(bins, pdf);
    double total = 0.0;
    for (double c : cells) total += c;
    std::printf("    pdf integral %.6f, worst round trip %.2e\n", total, worstTrip);
    EXPECT_NEAR(total, 1.0, 1e-4);
    EXPECT_LT(worstTrip, 2e-5);
    EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, bins, cells)));
}

}  // namespace
