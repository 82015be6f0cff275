// Statistical and numerical tests of the environment map's sampling (shaders/shared/
// environment_map.h compiled as C++, tables from host/render/environment.cpp) on small synthetic
// maps (a sky with a sun, bright rows at both poles, zeros): (a) chi-square of sampled directions
// against pdfEnvMap, (b) pdfEnvMap integrates to 1 over the sphere, (c) the pdf returned with a
// sample equals pdfEnvMap(dir) evaluated alone, (d) the (u, v) <-> direction mapping and rotate_y
// conventions of the header, (e) no sample towards zero radiance and pdf > 0 wherever there is
// radiance (also in the rows at the poles).
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: Sidak-corrected so the
// whole stats suite falsely fails with probability <= 1% for correct code; seeds are fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/environment.h"
#include "shared/environment_map.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;
constexpr double kPi = 3.14159265358979323846;

/// 24 x 12 map: dim sky, a 1-texel sun, a black band, bright texels in both pole rows.
vkp::Image testMap() {
    vkp::Image img(24, 12);
    for (std::uint32_t j = 0; j < img.height; ++j)
        for (std::uint32_t i = 0; i < img.width; ++i) {
            const float sky = j < 6 ? 0.5f + 0.1f * float(i % 5) : 0.2f;
            img.set(i, j, sky, sky, 1.2f * sky);
            if (j == 8) img.set(i, j, 0.0f, 0.0f, 0.0f);
        }
    img.set(17, 3, 400.0f, 380.0f, 300.0f);  // the sun
    img.set(5, 0, 30.0f, 30.0f, 30.0f);      // next to the north pole
    img.set(9, 11, 0.0f, 25.0f, 0.0f);       // next to the south pole
    return img;
}

struct EnvFixture {
    vkp::Image img = testMap();
    std::vector<float> table;
    glm::vec2 cs;
    explicit EnvFixture(float rotateDeg) {
        vkp::Scene scene;
        scene.environment.image = img;
        table = vkp::packEnvironment(scene).distribution;
        const double r = rotateDeg * kPi / 180.0;
        cs = glm::vec2(float(std::cos(r)), float(std::sin(r)));
    }
    float pdf(glm::vec3 d) const { return gpu::pdfEnvMap(table.data(), img.width, img.height, cs, d); }
    glm::vec3 radiance(glm::vec3 d) const {
        const glm::uvec2 t = gpu::envTexel(gpu::envMapUV(gpu::envToMap(d, cs)), img.width, img.height);
        auto p = img.pixel(t.x, t.y);
        return {p[0], p[1], p[2]};
    }
};

TEST(EnvMapping, AxesAndRotation) {
    const glm::vec2 id(1.0f, 0.0f);
    auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-6f; };
    EXPECT_TRUE(near(gpu::envMapDirection(glm::vec2(0.5f, 0.5f)), glm::vec3(0, 0, -1)));   // centre: -z
    EXPECT_TRUE(near(gpu::envMapDirection(glm::vec2(0.75f, 0.5f)), glm::vec3(1, 0, 0)));   // right of it: +x
    EXPECT_TRUE(near(gpu::envMapDirection(glm::vec2(0.0f, 0.5f)), glm::vec3(0, 0, 1)));    // u = 0: +z
    EXPECT_TRUE(near(gpu::envMapDirection(glm::vec2(0.3f, 0.0f)), glm::vec3(0, 1, 0)));    // top row: +y
    // rotate_y 90 turns the map's -z (its centre) to -x, like an object's rotate_y 90.
    EXPECT_TRUE(near(gpu::envToWorld(glm::vec3(0, 0, -1), glm::vec2(0.0f, 1.0f)), glm::vec3(-1, 0, 0)));
    UniformSource src(5);
    const glm::vec2 cs(std::cos(0.7f), std::sin(0.7f));
    for (int i = 0; i < 10000; ++i) {
        const glm::vec2 uv(src.next(), 0.001f + 0.998f * src.next());
        const glm::vec3 d = gpu::envToWorld(gpu::envMapDirection(uv), cs);
        const glm::vec2 back = gpu::envMapUV(gpu::envToMap(d, cs));
        const float du = std::min(std::abs(back.x - uv.x), 1.0f - std::abs(back.x - uv.x));
        ASSERT_LT(du, 2e-5f) << uv.x << " " << uv.y;
        ASSERT_LT(std::abs(back.y - uv.y), 2e-5f);
        (void)id;
    }
}

class EnvSampling : public ::testing::TestWithParam<float> {};

TEST_P(EnvSampling, Chi2IntegralConsistency) {
    const EnvFixture f(GetParam());
    // The solid-angle pdf is ~1/sin(theta) near the poles (uniform in theta within the top and
    // bottom rows): integrable but unbounded, which defeats quadrature on the sphere. So the tests
    // work in the world's (u, v) = envMapUV(d) (the unrotated mapping, checked by EnvMapping
    // above), where the density is pdfEnvMap(d(u, v)) * 2 pi^2 sin(pi v): bounded (the texel's
    // p(u, v)). A 35 x 17 grid, coprime with the map's 24 x 12 texels, so texel edges fall inside
    // cells (where the adaptive quadrature refines) rather than on the cell edges.
    Grid2D g;
    g.nx = 35;
    g.ny = 17;
    const Pdf2D pdfUV = [&](double u, double v) {
        const glm::vec3 d = gpu::envMapDirection(glm::vec2(float(u), float(v)));
        return double(f.pdf(d)) * 2.0 * kPi * kPi * std::sin(kPi * v);
    };
    const std::vector<double> cells = integrateCells(g, pdfUV, 1e-5, 10, 1);
    double integral = 0.0;
    for (double c : cells) integral += c;
    // (b) the pdf integrates to 1 over the sphere.
    EXPECT_NEAR(integral, 1.0, 1e-3);

    UniformSource src(77);
    std::vector<glm::dvec2> uvs;
    int mismatch = 0, dark = 0;
    double worstRel = 0.0;
    for (int i = 0; i < 400000; ++i) {
        float p;
        glm::vec2 uv;
        const glm::vec3 d = gpu::sampleEnvMap(f.table.data(), f.img.width, f.img.height, f.cs, src.next2(), p, uv);
        if (!(p > 0.0f)) continue;  // exactly at a pole: no sample (measure zero)
        const glm::vec2 w = gpu::envMapUV(d);
        uvs.emplace_back(w.x, w.y);
        // (c) same pdf alone: the two compute sin(theta) the same way but reach the cell from
        // the direction again (acos/atan), so they agree except where the direction rounds into
        // the neighbouring texel; 1e-4 relative allows float rounding of the rotation.
        const float alone = f.pdf(d);
        const double rel = std::abs(double(alone) - p) / p;
        worstRel = std::max(worstRel, rel);
        if (rel > 1e-4) ++mismatch;
        // (e) never towards zero radiance.
        const glm::vec3 L = f.radiance(d);
        if (!(std::max(L.x, std::max(L.y, L.z)) > 0.0f)) ++dark;
    }
    EXPECT_LE(mismatch, 4) << "worst relative pdf difference " << worstRel;  // texel-edge roundings only
    EXPECT_LE(dark, 4);
    // (a) chi-square.
    std::vector<double> observed(g.cellCount(), 0.0), expected(g.cellCount(), 0.0);
    for (const glm::dvec2& w : uvs) {
        const int c = g.cell(w.x, w.y);
        ASSERT_GE(c, 0);
        observed[c] += 1.0;
    }
    for (int c = 0; c < g.cellCount(); ++c) expected[c] = cells[c] * double(uvs.size());
    EXPECT_TRUE(passesChi2(chi2Test(observed, expected)));

    // (e) pdf > 0 wherever there is radiance: every texel's centre, poles' rows included.
    for (std::uint32_t j = 0; j < f.img.height; ++j)
        for (std::uint32_t i = 0; i < f.img.width; ++i) {
            if (!(f.img.at(i, j, 0) + f.img.at(i, j, 1) + f.img.at(i, j, 2) > 0.0f)) continue;
            const glm::vec3 d = gpu::envToWorld(
                gpu::envMapDirection(glm::vec2((i + 0.5f) / f.img.width, (j + 0.5f) / f.img.height)), f.cs);
            EXPECT_GT(f.pdf(d), 0.0f) << "texel " << i << "," << j;
        }
}

INSTANTIATE_TEST_SUITE_P(RotateY, EnvSampling, ::testing::Values(0.0f, 37.0f));

}  // namespace
