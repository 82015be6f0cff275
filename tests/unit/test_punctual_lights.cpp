// Point, spot and directional lights on the host (label unit): the kernel's own sampling code
// (shaders/shared/punctual_light.h) against the KHR_lights_punctual formulas and numerical
// integration, their power, the JSON and glTF loaders (units, placement, transforms) and their
// records in the lights buffer (render/light_table.h).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "file_frame.h"
#include "render/features.h"
#include "render/light_table.h"
#include "scene/gltf.h"
#include "scene/punctual_light.h"
#include "scene/scene.h"
#include "shared/punctual_light.h"
#include "test_paths.h"

namespace vkp {
namespace {

constexpr double kPi = std::numbers::pi;

/// The falloff exactly as the KHR_lights_punctual specification writes it (in double).
double specFalloff(double inner, double outer, double cd) {
    const double scale = 1.0 / std::max(0.001, std::cos(inner) - std::cos(outer));
    const double offset = -std::cos(outer) * scale;
    const double a = std::clamp(cd * scale + offset, 0.0, 1.0);
    return a * a;
}

/// A spot cone pair (radians) and its record values.
struct Cone {
    double inner, outer;
    float cosOuter() const { return float(std::cos(outer)); }
    float scale() const { return gpu::spotScale(float(std::cos(inner)), cosOuter()); }
};
const Cone kCones[] = {{0.0, kPi / 4}, {0.25, 0.5}, {0.5, 0.5 + 1e-5}, {0.0, kPi / 2}, {1.0, 1.2}, {0.05, 0.1}};

TEST(PunctualLights, SpotFalloffIsTheSpecificationsFormula) {
    for (const Cone& c : kCones) {
        for (int i = 0; i <= 2000; ++i) {
            const double angle = kPi * i / 2000.0;
            const double cd = std::cos(angle);
            const double got = gpu::spotFalloff(float(cd), c.cosOuter(), c.scale());
            EXPECT_NEAR(got, specFalloff(c.inner, c.outer, cd), 2e-3) << "cone " << c.inner << ".." << c.outer << " angle " << angle;
            // Full intensity inside the inner cone, unless the cones are closer than the
            // specification's 0.001 in cosine (then the falloff spans that 0.001 below cos(outer)).
            if (angle <= c.inner && std::cos(c.inner) - std::cos(c.outer) >= 0.001) EXPECT_NEAR(got, 1.0, 1e-5) << "inside the inner cone";
            if (angle > c.outer + 1e-6) EXPECT_EQ(got, 0.0) << "outside the outer cone";
        }
    }
}

TEST(PunctualLights, SpotSolidAngleIsTheFalloffsIntegral) {
    for (const Cone& c : kCones) {
        // Midpoint rule over the cosine: integral of the falloff over the sphere / (2 pi).
        const int n = 2000000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) sum += specFalloff(c.inner, c.outer, -1.0 + 2.0 * (i + 0.5) / n);
        const double numeric = sum * 2.0 / n;
        const double closed = gpu::spotSolidAngleOver2Pi(c.cosOuter(), c.scale());
        EXPECT_NEAR(closed / numeric, 1.0, 2e-4) << "cone " << c.inner << ".." << c.outer;
    }
}

gpu::GpuPunctualLight record(std::uint32_t kind, glm::vec3 at, glm::vec3 intensity, glm::vec3 axis = {0, -1, 0},
                             const Cone& c = kCones[0]) {
    gpu::GpuPunctualLight l{};
    l.q0 = glm::vec4(at, std::bit_cast<float>(kind));
    l.q1 = glm::vec4(intensity, c.scale());
    l.q2 = glm::vec4(axis, c.cosOuter());
    return l;
}

TEST(PunctualLights, SampleGivesTheIrradianceOfAFacingSurface) {
    const glm::vec3 x(0.5f, 0.0f, -0.25f);
    // Point: I / d^2 towards the light.
    const gpu::PunctualSample p = gpu::samplePunctualLight(record(gpu::PUNCTUAL_POINT, {0.5f, 2.0f, -0.25f}, {4, 2, 1}), x);
    ASSERT_TRUE(p.valid);
    EXPECT_NEAR(p.dist, 2.0f, 1e-6f);
    EXPECT_NEAR(glm::length(p.dir - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(p.le.x, 1.0f, 1e-6f);
    EXPECT_NEAR(p.le.z, 0.25f, 1e-6f);
    // Spot, pointing down from above x: full intensity on the axis; zero beyond the outer cone.
    const Cone cone{0.25, 0.5};
    const gpu::GpuPunctualLight spot = record(gpu::PUNCTUAL_SPOT, {0.5f, 2.0f, -0.25f}, {4, 4, 4}, {0, -1, 0}, cone);
    EXPECT_NEAR(gpu::samplePunctualLight(spot, x).le.y, 1.0f, 1e-6f);
    const glm::vec3 half(0.5f + 2.0f * float(std::tan(0.375)), 0.0f, -0.25f);  // halfway between the cones
    const gpu::PunctualSample h = gpu::samplePunctualLight(spot, half);
    const double d2 = 4.0 / (std::cos(0.375) * std::cos(0.375));
    EXPECT_NEAR(h.le.x, 4.0 / d2 * specFalloff(0.25, 0.5, std::cos(0.375)), 1e-4);
    EXPECT_GT(h.le.x, 0.0f);
    const glm::vec3 out(0.5f + 2.0f * float(std::tan(0.51)), 0.0f, -0.25f);
    EXPECT_EQ(gpu::samplePunctualLight(spot, out).le.x, 0.0f);
    // Directional: its irradiance, from infinitely far, the same everywhere.
    const gpu::GpuPunctualLight sun = record(gpu::PUNCTUAL_DIRECTIONAL, {0, 0.6f, 0.8f}, {0.5f, 0.5f, 1});
    const gpu::PunctualSample s = gpu::samplePunctualLight(sun, x);
    EXPECT_TRUE(s.valid);
    EXPECT_EQ(s.dist, gpu::VKP_FAR);
    EXPECT_EQ(s.le, glm::vec3(0.5f, 0.5f, 1));
    EXPECT_EQ(s.dir, glm::vec3(0, 0.6f, 0.8f));
    // At the light's own position: no direction, no sample.
    EXPECT_FALSE(gpu::samplePunctualLight(record(gpu::PUNCTUAL_POINT, x, {1, 1, 1}), x).valid);
}

TEST(PunctualLights, PowerOfEachKind) {
    PunctualLight l;
    l.intensity = glm::vec3(1.0f, 0.0f, 0.0f);  // luminance 0.2126
    EXPECT_NEAR(l.power(1.0), 4.0 * kPi * 0.2126, 1e-6);
    l.kind = PunctualLight::Kind::Spot;
    l.innerCone = 0.0f;
    l.outerCone = float(kPi / 2);
    EXPECT_NEAR(l.power(1.0), 2.0 * kPi * 0.2126 / 3.0, 1e-6);  // falloff cos^2 over the hemisphere: 1/3
    l.kind = PunctualLight::Kind::Directional;
    EXPECT_NEAR(l.power(3.0), kPi * 9.0 * 0.2126, 1e-6);
}

// ---- JSON scenes -------------------------------------------------------------------------------

TEST(PunctualLights, JsonLightsInRadiometricUnits) {
    const Scene s = test::inFileFrame(parseSceneJson(R"({
      "camera": {"lookfrom": [0, 1, 9], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 8, "height": 8},
      "objects": [
        {"type": "point_light", "position": [1, 2, 3], "intensity": [1, 2, 3]},
        {"type": "point_light", "position": [0, 0, 0], "power": [400, 0, 40], "transform": [{"translate": [0, 5, 0]}]},
        {"type": "spot_light", "position": [0, 4, 0], "direction": [0, -2, 0], "intensity": [5, 5, 5], "inner_angle": 10, "outer_angle": 30,
         "transform": [{"rotate_z": 90}, {"translate": [1, 0, 0]}]},
        {"type": "directional_light", "direction": [0, -3, 4], "irradiance": [1, 0.5, 0.25]}
      ]})",
                                                   "lights.json"));
    ASSERT_EQ(s.punctualLights.size(), 4u);
    EXPECT_TRUE(s.shapes.empty());
    EXPECT_TRUE(s.lights.empty());
    const PunctualLight& a = s.punctualLights[0];
    EXPECT_EQ(a.kind, PunctualLight::Kind::Point);
    EXPECT_EQ(a.position, glm::vec3(1, 2, 3));
    EXPECT_EQ(a.intensity, glm::vec3(1, 2, 3));
    EXPECT_EQ(a.name, "the light at /objects/0");
    const PunctualLight& b = s.punctualLights[1];  // power P: I = P / (4 pi), as Blender defines a lamp's power
    EXPECT_EQ(b.position, glm::vec3(0, 5, 0));
    EXPECT_NEAR(b.intensity.x, 400.0 / (4.0 * kPi), 1e-5);
    EXPECT_EQ(b.intensity.y, 0.0f);
    const PunctualLight& c = s.punctualLights[2];  // rotated about z by 90 degrees, then moved
    EXPECT_EQ(c.kind, PunctualLight::Kind::Spot);
    EXPECT_NEAR(glm::length(c.position - glm::vec3(-3, 0, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(c.direction - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(c.innerCone, 10.0 * kPi / 180.0, 1e-6);
    EXPECT_NEAR(c.outerCone, 30.0 * kPi / 180.0, 1e-6);
    const PunctualLight& d = s.punctualLights[3];
    EXPECT_EQ(d.kind, PunctualLight::Kind::Directional);
    EXPECT_NEAR(glm::length(d.direction - glm::vec3(0, -0.6f, 0.8f)), 0.0f, 1e-6f);
    EXPECT_EQ(d.intensity, glm::vec3(1, 0.5f, 0.25f));
}

TEST(PunctualLights, JsonLightsAreCameraRelative) {
    // The camera 1e7 from the origin: a light near it keeps its float digits (camera-relative).
    const Scene s = parseSceneJson(R"({
      "camera": {"lookfrom": [10000000, 0, 5], "lookat": [10000000, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 8, "height": 8},
      "objects": [{"type": "point_light", "position": [10000000.125, 2, 0], "intensity": [1, 1, 1]}]})",
                                   "far.json");
    ASSERT_EQ(s.punctualLights.size(), 1u);
    EXPECT_EQ(s.punctualLights[0].position, glm::vec3(0.125f, 2.0f, -5.0f));
}

TEST(PunctualLights, JsonSpotDefaultsAreGltfs) {
    const Scene s = parseSceneJson(R"({"objects": [
        {"type": "spot_light", "position": [0, 4, 0], "direction": [0, -1, 0], "intensity": [1, 1, 1]}]})",
                                   "spot.json");
    ASSERT_EQ(s.punctualLights.size(), 1u);
    EXPECT_EQ(s.punctualLights[0].innerCone, 0.0f);
    EXPECT_NEAR(s.punctualLights[0].outerCone, kPi / 4, 1e-7);
}

TEST(PunctualLights, ReadmeExampleLoads) {
    // The spot of scenes/README.md's "Lights" is valid and means what the README says of it.
    std::ifstream in(test::scenesDir() / "README.md");
    std::stringstream text;
    text << in.rdbuf();
    const std::string readme = text.str();
    const std::size_t begin = readme.find("```json\n", readme.find("### Lights"));
    ASSERT_NE(begin, std::string::npos);
    const std::size_t end = readme.find("```", begin + 8);
    const Scene s = parseSceneJson(R"({"objects": [)" + readme.substr(begin + 8, end - begin - 8) + "]}", "README.md");
    ASSERT_EQ(s.punctualLights.size(), 1u);
    EXPECT_EQ(s.punctualLights[0].kind, PunctualLight::Kind::Spot);
    EXPECT_NEAR(s.punctualLights[0].intensity.x, 500.0 / (4.0 * kPi), 1e-4);
}

// ---- glTF: KHR_lights_punctual -----------------------------------------------------------------

TEST(PunctualLights, GltfLightsConvertedAndPlacedByTheirNodes) {
    const Scene s = test::inFileFrame(loadSceneGltf(test::scenesDir() / "gltf" / "lights.gltf"));
    ASSERT_EQ(s.punctualLights.size(), 3u);  // the fourth light is used by no node
    // One warning: the spot's range is ignored.
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("KHR_lights_punctual light 1 (\"spot\"): range ignored"), std::string::npos) << s.warnings[0];
    const PunctualLight& bulb = s.punctualLights[0];  // 683 cd x (1, 0.5, 0.25): 1 W/sr x the colour
    EXPECT_EQ(bulb.kind, PunctualLight::Kind::Point);
    EXPECT_EQ(bulb.position, glm::vec3(1, 2, 3));
    EXPECT_NEAR(glm::length(bulb.intensity - glm::vec3(1, 0.5f, 0.25f)), 0.0f, 1e-6f);
    EXPECT_EQ(bulb.name, "KHR_lights_punctual light 0 (\"bulb\") of node 1 (\"bulb\")");
    // The spot: under a rig at (0, 4, 0) turned -90 degrees about x and scaled 2, moved 0.5 along
    // the rig's x: at (1, 4, 0), shining down; 1366 cd = 2 W/sr; the scale changes nothing else.
    const PunctualLight& spot = s.punctualLights[1];
    EXPECT_EQ(spot.kind, PunctualLight::Kind::Spot);
    EXPECT_NEAR(glm::length(spot.position - glm::vec3(1, 4, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(spot.direction - glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(spot.intensity - glm::vec3(2.0f)), 0.0f, 1e-6f);
    EXPECT_FLOAT_EQ(spot.innerCone, 0.25f);
    EXPECT_FLOAT_EQ(spot.outerCone, 0.5f);
    // The sun: turned 90 degrees about y, so its -z shines along -x; 341.5 lux = 0.5 W/m^2.
    const PunctualLight& sun = s.punctualLights[2];
    EXPECT_EQ(sun.kind, PunctualLight::Kind::Directional);
    EXPECT_NEAR(glm::length(sun.direction - glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(sun.intensity - glm::vec3(0.25f, 0.25f, 0.5f)), 0.0f, 1e-6f);
}

TEST(PunctualLights, GltfIncludedInAJsonSceneBringsItsLights) {
    const std::string file = (test::scenesDir() / "gltf" / "lights.gltf").generic_string();
    const Scene s = test::inFileFrame(parseSceneJson(R"({"objects": [
        {"type": "gltf", "file": ")" + file + R"(", "transform": [{"translate": [10, 0, 0]}]}]})",
                                                   test::scenesDir() / "gltf" / "include-lights.json"));
    ASSERT_EQ(s.punctualLights.size(), 3u);
    EXPECT_NEAR(glm::length(s.punctualLights[0].position - glm::vec3(11, 2, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(s.punctualLights[1].position - glm::vec3(11, 4, 0)), 0.0f, 1e-5f);
}

// ---- The lights buffer -------------------------------------------------------------------------

TEST(PunctualLights, PackedAfterTheSurfacesAndPickedByPower) {
    const Scene s = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 1, 9], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 8, "height": 8},
      "materials": {"lamp": {"type": "diffuse_light", "emit": [1, 1, 1]}},
      "objects": [
        {"type": "quad", "Q": [0, 3, 0], "u": [1, 0, 0], "v": [0, 0, 1], "material": "lamp"},
        {"type": "point_light", "position": [1, 2, 3], "intensity": [2, 2, 2]},
        {"type": "spot_light", "position": [0, 4, 0], "direction": [0, -1, 0], "intensity": [3, 3, 3], "inner_angle": 20, "outer_angle": 40}
      ]})",
                                   "mixed.json");
    const std::vector<std::uint32_t> primOfShape = {7};
    const std::vector<gpu::GpuLight> lights = packLights(s, primOfShape);
    ASSERT_EQ(lights.size(), 3u + 2u * gpu::GPU_PUNCTUAL_TEXELS);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(lights[0].l0.x), 7u);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(lights[1].l0.x), gpu::LIGHT_PUNCTUAL_BIT | 0u);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(lights[2].l0.x), gpu::LIGHT_PUNCTUAL_BIT | 1u);
    // Probabilities in proportion to power / pi: the quad pi L A / pi = 1 (one face), the point
    // 4 I, the spot 2 I x the falloff's integral over 2 pi.
    const double spotW = 2.0 * 3.0 * gpu::spotSolidAngleOver2Pi(float(std::cos(40 * kPi / 180)),
                                                                gpu::spotScale(float(std::cos(20 * kPi / 180)), float(std::cos(40 * kPi / 180))));
    const double w[3] = {1.0, 8.0, spotW};
    const double total = w[0] + w[1] + w[2];
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(lights[std::size_t(i)].l0.y, w[i] / total, 1e-6) << "entry " << i;
    // The records: position, kind, intensity, falloff, and the pick among the punctual lights alone.
    const gpu::GpuLight* r = &lights[3];
    EXPECT_EQ(glm::vec3(r[0].l0), glm::vec3(1, 2, 3) - glm::vec3(0, 1, 9));  // camera-relative
    EXPECT_EQ(std::bit_cast<std::uint32_t>(r[0].l0.w), gpu::PUNCTUAL_POINT);
    EXPECT_EQ(glm::vec3(r[1].l0), glm::vec3(2, 2, 2));
    EXPECT_NEAR(r[3].l0.y, w[1] / (w[1] + w[2]), 1e-6);
    const gpu::GpuLight* q = &lights[3 + gpu::GPU_PUNCTUAL_TEXELS];
    EXPECT_EQ(std::bit_cast<std::uint32_t>(q[0].l0.w), gpu::PUNCTUAL_SPOT);
    EXPECT_EQ(glm::vec3(q[2].l0), glm::vec3(0, -1, 0));
    EXPECT_FLOAT_EQ(q[2].l0.w, float(std::cos(40 * kPi / 180)));
    EXPECT_NEAR(q[3].l0.y, w[2] / (w[1] + w[2]), 1e-6);
    // The variant compiles the punctual lights in.
    EXPECT_NE(sceneFeatures(s).name().find("lights:quad+punctual"), std::string::npos) << sceneFeatures(s).name();
}

}  // namespace
}  // namespace vkp
