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

/// cornell-classic.json's room and light without its boxes, direct light only (max_depth 2), seen
/// by `camera` (the JSON camera object's members).
Scene emptyCornellRoom(const std::string& camera) {
    return parseSceneJson(R"({
      "camera": {)" + camera + R"(},
      "render": {"max_depth": 2, "background": [0, 0, 0]},
      "materials": {"red": {"type": "lambertian", "albedo": [0.65, 0.05, 0.05]},
                    "white": {"type": "lambertian", "albedo": [0.73, 0.73, 0.73]},
                    "green": {"type": "lambertian", "albedo": [0.12, 0.45, 0.15]},
                    "light": {"type": "diffuse_light", "emit": [15, 15, 15]}},
      "objects": [{"type": "quad", "Q": [555, 0, 0], "u": [0, 0, 555], "v": [0, 555, 0], "material": "green"},
                  {"type": "quad", "Q": [0, 0, 555], "u": [0, 0, -555], "v": [0, 555, 0], "material": "red"},
                  {"type": "quad", "Q": [0, 555, 0], "u": [555, 0, 0], "v": [0, 0, 555], "material": "white"},
                  {"type": "quad", "Q": [0, 0, 555], "u": [555, 0, 0], "v": [0, 0, -555], "material": "white"},
                  {"type": "quad", "Q": [555, 0, 555], "u": [-555, 0, 0], "v": [0, 555, 0], "material": "white"},
                  {"type": "quad", "Q": [213, 554, 227], "u": [130, 0, 0], "v": [0, 0, 105], "material": "light"}]})",
                          "empty-cornell-room.json");
}

const std::vector<glm::dvec3> kRoomLight = {{213, 554, 227}, {343, 554, 227}, {343, 554, 332}, {213, 554, 332}};

// The room of cornell-classic.json without its boxes, direct light only (max_depth 2): a convex room
// whose walls see the ceiling light edge-on. A wall point near the ceiling sees the light's downward
// face at emission angles of 75-85 degrees, where Cycles 3.4 renders the same room 0.4-0.9 % darker
// than Lambert's formula (docs/accuracy.md "Against Cycles: the Cornell box's walls"). Every pixel
// whose footprint lies on one wall (a 10 x 10 grid of its points, edges included, hits the same
// surface and not the light) must equal (rho / pi) L E(x) averaged over the footprint; z-tests of
// each surface's pixels (their average), per channel and sampler; the ceiling, which sees only the
// light's back, is exactly 0.
TEST(GpuAnalytic, EmptyCornellRoomWallsSeeTheLightEdgeOn) {
    VKP_REQUIRE_DEVICE(dev);
    constexpr std::uint32_t kSize = 32;
    Scene scene = emptyCornellRoom(R"("lookfrom": [278, 278, -800], "lookat": [278, 278, 0], "vup": [0, 1, 0], "vfov": 40, "width": 32, "height": 32)");
    struct Surface {
        const char* name;
        int axis;      // the plane coordinate axis ...
        double at;     // ... and its value
        glm::dvec3 n;  // inward normal
        glm::dvec3 rho;
    };
    const Surface surfaces[] = {{"green wall", 0, 555, {-1, 0, 0}, {0.12, 0.45, 0.15}}, {"red wall", 0, 0, {1, 0, 0}, {0.65, 0.05, 0.05}},
                                {"ceiling", 1, 555, {0, -1, 0}, {0.73, 0.73, 0.73}},    {"floor", 1, 0, {0, 1, 0}, {0.73, 0.73, 0.73}},
                                {"back wall", 2, 555, {0, 0, -1}, {0.73, 0.73, 0.73}}};
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    const glm::dvec3 o(f.origin), p00(f.pixel00), du(f.pixelDu), dv(f.pixelDv);
    // The surface a camera ray through pixel coordinates (i + jx, j + jy) hits inside the room
    // (entered through its open front, z = 0), -1 for the light or a miss; x = the point.
    const auto surfaceHit = [&](double px, double py, glm::dvec3& x) {
        const glm::dvec3 d = p00 + px * du + py * dv - o;
        const double t0 = -o.z / d.z;
        const glm::dvec3 e = o + t0 * d;
        if (!(e.x > 0 && e.x < 555 && e.y > 0 && e.y < 555)) return -1;
        int best = -1;
        double tBest = 1e30;
        for (int k = 0; k < 5; ++k) {
            const double t = (surfaces[k].at - o[surfaces[k].axis]) / d[surfaces[k].axis];
            if (t > t0 && t < tBest) tBest = t, best = k;
        }
        x = o + tBest * d;
        const glm::dvec3 lo = kRoomLight[0], hi = kRoomLight[2];  // the light's corners, at height lo.y
        const double tl = (lo.y - o.y) / d.y;                        // seen from below
        const glm::dvec3 xl = o + tl * d;
        if (tl > t0 && tl < tBest && xl.x >= lo.x && xl.x <= hi.x && xl.z >= lo.z && xl.z <= hi.z) return -1;
        return best;
    };
    std::vector<std::vector<Pixel>> pixelsOf(5);
    std::vector<double> expected(kSize * kSize, 0.0);  // E / pi averaged over the footprint
    for (std::uint32_t j = 0; j < kSize; ++j)
        for (std::uint32_t i = 0; i < kSize; ++i) {
            glm::dvec3 x;
            int k = surfaceHit(i - 0.5, j - 0.5, x);
            for (int a = 0; a < 10 && k >= 0; ++a)
                for (int b = 0; b < 10 && k >= 0; ++b)
                    if (surfaceHit(i - 0.5 + a / 9.0, j - 0.5 + b / 9.0, x) != k) k = -1;
            if (k < 0) continue;
            double sum = 0.0;
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b) {
                    surfaceHit(i + kGlX[a], j + kGlX[b], x);
                    // The light faces down: points above its plane (the ceiling) see its back.
                    if (x.y < kRoomLight[0].y) sum += kGlW[a] * kGlW[b] * 15.0 * polygonIrradiance(x, surfaces[k].n, kRoomLight);
                }
            expected[j * kSize + i] = sum / kPi;
            pixelsOf[std::size_t(k)].push_back({i, j});
        }
    for (const auto& px : pixelsOf) ASSERT_GE(px.size(), 20u) << "too few pixels see one surface alone";
    std::uint32_t seed = 60;
    for (Sampler s : {Sampler::Light, Sampler::Mis, Sampler::Bsdf}) {
        scene.render.seed = seed++;
        const std::string name = std::string(samplerName(s)) + " empty room";
        const PixelStats st(renderSums(dev, scene, s, s == Sampler::Bsdf ? 4096 : 1024, name));
        for (int k = 0; k < 5; ++k)
            for (int c = 0; c < 3; ++c) {
                double want = 0.0;
                for (const Pixel& p : pixelsOf[std::size_t(k)]) want += surfaces[k].rho[c] * expected[p.y * kSize + p.x];
                want /= double(pixelsOf[std::size_t(k)].size());
                EXPECT_TRUE(withinNoise(average(st, pixelsOf[std::size_t(k)], c), want,
                                        name + ", " + surfaces[k].name + " (" + std::to_string(pixelsOf[std::size_t(k)].size()) + " pixels), " +
                                            kChannel[c],
                                        c == 0));
            }
    }
}

// A BSDF-sampled ray leaves a diffuse vertex x from a point moved off the surface (shared/ray_offset.h:
// 256 ulps of each coordinate, relative to the camera), from where the light looks a little larger.
// The light it finds is weighed against next-event estimation's density for its direction from
// that origin (shaders/pathtrace.comp, foundLightWeight); from x, the density of that sliver of directions is 0
// and their weight was 1: a bias of about twice the offset over the distance to the light. Seen
// from 1e5 units away, a point high on the empty room's back wall is offset by ~2 units, 300 from
// the light: `mis` read 3.3 % too bright there (12 standard errors; 0.035 % seen from the box's own
// camera). Now `mis` and `light` must both equal the closed form, z-tested per channel (8 x 8 pixels
// on 0.2 units of the wall).
TEST(GpuAnalytic, MisWeighsAFoundLightFromTheRaysOrigin) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = emptyCornellRoom(R"("lookfrom": [278, 450, -100000], "lookat": [278, 450, 555], "vup": [0, 1, 0], "vfov": 0.0001, "width": 8, "height": 8)");
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    const glm::dvec3 o(f.origin), p00(f.pixel00), du(f.pixelDu), dv(f.pixelDv), n(0, 0, -1);
    double want = 0.0;  // E / pi over the image (every pixel sees the back wall)
    for (std::uint32_t j = 0; j < 8; ++j)
        for (std::uint32_t i = 0; i < 8; ++i)
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b) {
                    const glm::dvec3 d = p00 + (i + kGlX[a]) * du + (j + kGlX[b]) * dv - o;
                    const glm::dvec3 x = o + ((555.0 - o.z) / d.z) * d;
                    want += kGlW[a] * kGlW[b] * 15.0 * polygonIrradiance(x, n, kRoomLight) / kPi / 64.0;
                }
    std::uint32_t seed = 80;
    for (Sampler s : {Sampler::Light, Sampler::Mis}) {
        scene.render.seed = seed++;
        const std::string name = std::string(samplerName(s)) + " back wall from 1e5 away";
        const PixelStats st(renderSums(dev, scene, s, 4096, name));
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(withinNoise(average(st, rect(0, 0, 8, 8), c), 0.73 * want, name + ", " + kChannel[c], c == 0));
    }
}

}  // namespace
}  // namespace vkp::test
