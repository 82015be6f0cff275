// Direct light on a plane (label gpu): a large lambertian plane of albedo rho lit by (i) a quad
// light, (ii) a sphere light, nothing else in the scene, so each pixel equals (rho / pi) times the
// irradiance E averaged over the pixel's footprint on the plane, with E in closed form:
//  - quad: Lambert's polygon formula, E(x) = L/2 |sum_i theta_i (n . g_i)|, theta_i the angle that
//    edge i subtends at x and g_i the unit normal of the plane through x and that edge (Lambert
//    1760; Arvo, "Applications of Irradiance Tensors", SIGGRAPH 1995, eq. 7);
//  - sphere fully above x's horizon: E(x) = pi L (R/d)^2 cos(theta) (the sphere acts as a point of
//    intensity pi R^2 L at its centre; d = distance to the centre, theta = its angle from n).
// The camera looks straight down from far away with a small field of view; the lights are outside
// its frustum. Every sampler (bsdf, light, mixture) must converge to these values.
//
// Suite: this executable (test_gpu_analytic, with test_gpu_analytic_furnace.cpp) declares a budget
// of 1000 z-tests at family-wise false-failure probability 0.01 (critical |z| ~ 4.4, see
// test_gpu_analytic_common.h). Region means here average >= 16 pixels x 1024 samples of bounded
// values (the lights are away from the plane: no 1/d^2 spikes; bsdf hits the lights with
// probability >= 0.5% per sample at 4096 spp), so they are close to normal.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>

#include "gpu_env.h"
#include "render/gpu_scene.h"
#include "test_gpu_analytic_common.h"
#include "file_frame.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(1000, 0.01));

/// E / L at the origin (normal +z) by brute force: directions from a 1024 x 1024 grid of cells in
/// the cosine-weighted parametrisation (r^2 = s, phi = 2 pi t), where E / L = pi * (fraction of
/// cells whose centre direction sees the light).
double bruteIrradiance(const std::function<bool(glm::dvec3)>& seesLight) {
    const int n = 1024;
    long hits = 0;
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const double s = (i + 0.5) / n, phi = 2.0 * kPi * (k + 0.5) / n;
            hits += seesLight(glm::dvec3(std::sqrt(s) * std::cos(phi), std::sqrt(s) * std::sin(phi), std::sqrt(1.0 - s)));
        }
    return kPi * double(hits) / (double(n) * n);
}

// The formulas themselves (host only), against limits and a brute-force integration.
TEST(GpuAnalytic, IrradianceFormulasAgreeWithBruteForce) {
    const glm::dvec3 x(0.0), n(0, 0, 1);
    // A huge square far above fills the hemisphere: E -> pi L.
    const double big = 1e6;
    EXPECT_NEAR(polygonIrradiance(x, n, {{-big, -big, 1}, {big, -big, 1}, {big, big, 1}, {-big, big, 1}}), kPi, 1e-5);
    // A tilted quad Q + a u + b v and a sphere, off-axis.
    const glm::dvec3 q(0.5, -0.4, 1.0), u(1.0, 0.2, 0.3), v(-0.1, 0.8, 0.5);
    const double quadBrute = bruteIrradiance([&](glm::dvec3 d) {
        const glm::dvec3 nq = glm::cross(u, v);
        const double t = glm::dot(q, nq) / glm::dot(d, nq);
        if (!(t > 0)) return false;
        const glm::dvec3 p = t * d - q;  // solve p = a u + b v in the quad's plane
        const double a = glm::dot(glm::cross(p, v), nq) / glm::dot(nq, nq), b = glm::dot(glm::cross(u, p), nq) / glm::dot(nq, nq);
        return a >= 0 && a <= 1 && b >= 0 && b <= 1;
    });
    EXPECT_NEAR(polygonIrradiance(x, n, {q, q + u, q + u + v, q + v}) / quadBrute, 1.0, 3e-3);
    const glm::dvec3 c(1.5, 0.5, 1.2);
    const double sphereBrute = bruteIrradiance([&](glm::dvec3 d) {
        const double b = glm::dot(c, d);
        return b > 0 && glm::length(c - b * d) < 0.5;
    });
    EXPECT_NEAR(sphereIrradiance(x, n, c, 0.5) / sphereBrute, 1.0, 3e-3);
}

TEST(GpuAnalytic, PlaneUnderQuadLight) {
    VKP_REQUIRE_DEVICE(dev);
    // A 1 x 1 one-sided light 1.5 above the plane, facing down (u x v = -z), beside the frustum.
    const std::vector<glm::dvec3> poly = {{2.5, -0.5, 1.5}, {2.5, 0.5, 1.5}, {3.5, 0.5, 1.5}, {3.5, -0.5, 1.5}};
    checkPlane(dev, R"({"type": "quad", "Q": [2.5, -0.5, 1.5], "u": [0, 1, 0], "v": [1, 0, 0], "material": "lamp"})",
               "plane under a quad light", [&](glm::dvec3 x) { return kLampL * polygonIrradiance(x, glm::dvec3(0, 0, 1), poly); });
}

TEST(GpuAnalytic, PlaneUnderSphereLight) {
    VKP_REQUIRE_DEVICE(dev);
    // Radius 0.5 at height 1.2: above every plane point's horizon; beside the frustum.
    checkPlane(dev, R"({"type": "sphere", "center": [-3, 0, 1.2], "radius": 0.5, "material": "lamp"})",
               "plane under a sphere light",
               [](glm::dvec3 x) { return kLampL * sphereIrradiance(x, glm::dvec3(0, 0, 1), glm::dvec3(-3, 0, 1.2), 0.5); });
}


// Three lights of different power (a quad, a triangle and a sphere) and a constant sky over the
// plane, rendered by next-event estimation (`light`, `mis`) with every light pick (power, uniform)
// and every light sampling (auto, solid angle, area): the estimators differ only in variance, so
// each must converge to (rho / pi) (pi B + sum_i (L_i - B) E_i), E_i the irradiance of light i per
// unit radiance (the lights hide the sky B over exactly their projected solid angle E_i). 12
// renders x 3 channels x (image + 4 quadrants) = 180 z-tests of this executable's budget.
TEST(GpuAnalytic, PlaneUnderThreeLightsEveryPickAndLightSampling) {
    VKP_REQUIRE_DEVICE(dev);
    const glm::dvec3 rho(0.2, 0.5, 0.8);
    const double B = 0.5;
    const std::vector<glm::dvec3> quad = {{2.5, -0.5, 1.5}, {2.5, 0.5, 1.5}, {3.5, 0.5, 1.5}, {3.5, -0.5, 1.5}};
    const std::vector<glm::dvec3> tri = {{-1, 2.5, 1.0}, {1, 2.5, 1.0}, {0, 3.5, 2.0}};
    const glm::dvec3 sc(-3, 0, 1.2);
    const double sr = 0.5, Lq = 10.0, Lt = 40.0, Ls = 2.5;
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 0, 100], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 2.2913, "width": 16, "height": 16},
      "render": {"max_depth": 2, "background": [0.5, 0.5, 0.5]},
      "materials": {"plane": {"type": "lambertian", "albedo": [0.2, 0.5, 0.8]},
                    "lampQ": {"type": "diffuse_light", "emit": [10, 10, 10], "two_sided": true},
                    "lampT": {"type": "diffuse_light", "emit": [40, 40, 40], "two_sided": true},
                    "lampS": {"type": "diffuse_light", "emit": [2.5, 2.5, 2.5]}},
      "objects": [{"type": "quad", "Q": [-50, -50, 0], "u": [100, 0, 0], "v": [0, 100, 0], "material": "plane"},
                  {"type": "quad", "Q": [2.5, -0.5, 1.5], "u": [0, 1, 0], "v": [1, 0, 0], "material": "lampQ"},
                  {"type": "triangle", "v0": [-1, 2.5, 1.0], "v1": [1, 2.5, 1.0], "v2": [0, 3.5, 2.0], "material": "lampT"},
                  {"type": "sphere", "center": [-3, 0, 1.2], "radius": 0.5, "material": "lampS"}]})",
                                 "plane-three-lights.json");
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    const glm::dvec3 n(0, 0, 1);
    std::vector<double> expected(16 * 16);
    for (std::uint32_t j = 0; j < 16; ++j)
        for (std::uint32_t i = 0; i < 16; ++i)
            expected[j * 16 + i] = footprintMean(f, i, j, [&](glm::dvec3 x) {
                                       return kPi * B + (Lq - B) * polygonIrradiance(x, n, quad) +
                                              (Lt - B) * polygonIrradiance(x, n, tri) + (Ls - B) * sphereIrradiance(x, n, sc, sr);
                                   }) / kPi;
    std::uint32_t seed = 40;
    for (Sampler s : {Sampler::Light, Sampler::Mis})
        for (LightPick pick : {LightPick::Power, LightPick::Uniform})
            // auto at its default switch samples the quad and the triangle in solid angle from the
            // plane's points nearest to them and in area from the rest (apparent sizes 0.09-0.44
            // and 0.15-0.57 sr across the image): the seam must not show.
            for (LightSampling ls : {LightSampling::Auto, LightSampling::SolidAngle, LightSampling::Area}) {
                RenderOptions o;
                o.sampler = s;
                o.lightPick = pick;
                o.lightSampling = ls;
                o.samplesPerDispatch = 4;
                scene.render.seed = seed++;
                const std::string name =
                    std::string(samplerName(s)) + " pick " + lightPickName(pick) + " sampling " + lightSamplingName(ls);
                const PixelStats st(renderSums(dev, scene, o, 1024, name));
                expectPlanePixels(st, rho, expected, name, 8, false);  // quadrants
            }
}

}  // namespace
}  // namespace vkp::test
