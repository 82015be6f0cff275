// The JSON scene loader on good input: the shipped scenes (counts, the books' values, outward box
// faces) and the conventions of scenes/README.md (transforms, lights, defaults).
#include <numbers>

#include <gtest/gtest.h>

#include "scene/gltf.h"

#include "file_frame.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "scene/scene.h"
#include "test_paths.h"

namespace {

using vkp::MaterialType;
using vkp::Scene;
using vkp::Shape;
using vkp::ShapeType;

constexpr float kEps = 1e-4f;

void expectNear(glm::vec3 got, glm::vec3 want, float eps = kEps) {
    EXPECT_NEAR(got.x, want.x, eps);
    EXPECT_NEAR(got.y, want.y, eps);
    EXPECT_NEAR(got.z, want.z, eps);
}

glm::vec3 quadNormal(const Shape& s) { return glm::cross(s.p1, s.p2); }
glm::vec3 quadCentre(const Shape& s) { return s.p0 + 0.5f * (s.p1 + s.p2); }

/// A scene with the given materials and objects and a plain camera.
Scene parse(const std::string& materials, const std::string& objects, const std::string& extra = "") {
    const std::string text = R"({"camera":{"lookfrom":[0,0,5],"lookat":[0,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8},)" +
                             extra + R"("materials":)" + materials + R"(,"objects":)" + objects + "}";
    return vkp::test::inFileFrame(vkp::parseSceneJson(text, "inline.json"));
}

const std::string kGrey = R"({"grey":{"type":"lambertian","albedo":[0.5,0.5,0.5]}})";

/// Every face of the six quads [first, first + 6) points away from the box's centre.
void expectBoxFacesOutward(const Scene& s, std::size_t first) {
    glm::vec3 centre(0.0f);
    for (std::size_t i = first; i < first + 6; ++i) centre += quadCentre(s.shapes[i]) / 6.0f;
    for (std::size_t i = first; i < first + 6; ++i) {
        const Shape& q = s.shapes[i];
        ASSERT_EQ(q.type, ShapeType::Quad);
        const glm::vec3 n = glm::normalize(quadNormal(q));
        const glm::vec3 out = glm::normalize(quadCentre(q) - centre);
        EXPECT_GT(glm::dot(n, out), 0.9999f) << "face " << i - first << " does not point out of the box";
    }
}

TEST(SceneLoader, CornellBook3) {
    const Scene s = vkp::test::inFileFrame(vkp::loadSceneJson(vkp::test::scenesDir() / "cornell-book3.json"));
    ASSERT_EQ(s.shapes.size(), 13u);  // 5 walls + light + 6 box faces + sphere
    ASSERT_EQ(s.lights, (std::vector<std::uint32_t>{5, 12}));  // light quad, glass sphere
    ASSERT_EQ(s.materials.size(), 5u);

    // The book's camera and settings (our spp is 256, the book's 1000: see the description).
    expectNear(s.camera.lookfrom, {278, 278, -800});
    expectNear(s.camera.lookat, {278, 278, 0});
    expectNear(s.camera.vup, {0, 1, 0});
    EXPECT_FLOAT_EQ(s.camera.vfov, 40.0f);
    EXPECT_EQ(s.camera.width, 600u);
    EXPECT_EQ(s.camera.height, 600u);
    EXPECT_FLOAT_EQ(s.camera.defocusAngle, 0.0f);
    EXPECT_EQ(s.render.maxDepth, 50u);
    EXPECT_EQ(s.render.rouletteDepth, 3u);
    EXPECT_EQ(s.render.spp, 256u);
    expectNear(s.render.background, {0, 0, 0});

    const Shape& light = s.shapes[5];
    EXPECT_EQ(light.type, ShapeType::Quad);
    EXPECT_TRUE(light.sampled);
    const vkp::Material& lm = s.materials[light.material];
    EXPECT_EQ(lm.type, MaterialType::DiffuseLight);
    EXPECT_FALSE(lm.twoSided);
    expectNear(lm.emit, {15, 15, 15});
    expectNear(glm::normalize(quadNormal(light)), {0, -1, 0});  // the front (u x v) faces down
    EXPECT_FLOAT_EQ(vkp::shapeArea(light), 130.0f * 105.0f);

    const Shape& sphere = s.shapes[12];
    EXPECT_EQ(sphere.type, ShapeType::Sphere);
    EXPECT_TRUE(sphere.sampled);
    expectNear(sphere.p0, {190, 90, 190});
    EXPECT_FLOAT_EQ(sphere.radius, 90.0f);
    const vkp::Material& glass = s.materials[sphere.material];
    EXPECT_EQ(glass.type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(glass.ior, 1.5f);
    EXPECT_FALSE(glass.fresnelExact);
    EXPECT_FALSE(glass.emits());

    // Albedos of the book; the box is white Lambertian.
    const auto albedoOf = [&](std::size_t shape) { return s.materials[s.shapes[shape].material].albedo; };
    expectNear(albedoOf(0), {0.12f, 0.45f, 0.15f});  // green
    expectNear(albedoOf(1), {0.65f, 0.05f, 0.05f});  // red
    for (std::size_t i : {2u, 3u, 4u, 6u, 11u}) expectNear(albedoOf(i), {0.73f, 0.73f, 0.73f});
    EXPECT_EQ(s.materials[s.shapes[6].material].type, MaterialType::Lambertian);
    for (std::size_t i = 0; i < 12; ++i) {
        if (i != 5) {
            EXPECT_FALSE(s.shapes[i].sampled) << i;
        }
    }

    expectBoxFacesOutward(s, 6);
    // The box's bottom face: (0,0,0)-(165,_,165) turned 15 degrees about y, moved to (265,0,295).
    const Shape& bottom = s.shapes[11];
    expectNear(bottom.p0, {265, 0, 295});
    const float c = std::cos(glm::radians(15.0f)), sn = std::sin(glm::radians(15.0f));
    expectNear(bottom.p1, {165 * c, 0, -165 * sn}, 1e-3f);
    expectNear(bottom.p2, {165 * sn, 0, 165 * c}, 1e-3f);
}

TEST(SceneLoader, VupDefaultsToPlusY) {
    const Scene s = vkp::parseSceneJson(R"({"camera": {"lookfrom": [0, 1, 5], "lookat": [0, 0, 0], "vfov": 40, "width": 8, "height": 8},
                                            "objects": []})",
                                        "vup.json");
    EXPECT_EQ(s.camera.vup, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(SceneLoader, CornellClassic) {
    const Scene s = vkp::test::inFileFrame(vkp::loadSceneJson(vkp::test::scenesDir() / "cornell-classic.json"));
    ASSERT_EQ(s.shapes.size(), 18u);  // 5 walls + light + 2 boxes
    EXPECT_EQ(s.lights, (std::vector<std::uint32_t>{5}));
    for (const auto& m : s.materials) {
        EXPECT_TRUE(m.type == MaterialType::Lambertian || m.type == MaterialType::DiffuseLight) << m.name;
    }
    expectBoxFacesOutward(s, 6);
    expectBoxFacesOutward(s, 12);
    // The short box: its bottom-face corner (0,0,0) lands on (130,0,65); rotated by -18 degrees.
    const Shape& bottom = s.shapes[17];
    expectNear(bottom.p0, {130, 0, 65});
    const float c = std::cos(glm::radians(-18.0f)), sn = std::sin(glm::radians(-18.0f));
    expectNear(bottom.p1, {165 * c, 0, -165 * sn}, 1e-3f);
    EXPECT_NEAR(s.shapes[16].p0.y, 165.0f, kEps);  // top face at the box's height
}

TEST(SceneLoader, SpheresBook1) {
    const Scene s = vkp::test::inFileFrame(vkp::loadSceneJson(vkp::test::scenesDir() / "spheres-book1.json"));
    ASSERT_GE(s.shapes.size(), 4u + 400u);
    ASSERT_LE(s.shapes.size(), 4u + 22u * 22u);
    EXPECT_TRUE(s.lights.empty());
    EXPECT_EQ(s.materials.size(), s.shapes.size());  // one material per sphere
    std::set<std::uint32_t> used;
    for (const Shape& sh : s.shapes) {
        EXPECT_EQ(sh.type, ShapeType::Sphere);
        used.insert(sh.material);
    }
    EXPECT_EQ(used.size(), s.shapes.size());

    const Shape& ground = s.shapes.front();
    expectNear(ground.p0, {0, -1000, 0});
    EXPECT_FLOAT_EQ(ground.radius, 1000.0f);
    expectNear(s.materials[ground.material].albedo, {0.5f, 0.5f, 0.5f});
    const std::size_t n = s.shapes.size();
    const Shape& glass = s.shapes[n - 3];
    const Shape& brown = s.shapes[n - 2];
    const Shape& metal = s.shapes[n - 1];
    expectNear(glass.p0, {0, 1, 0});
    EXPECT_EQ(s.materials[glass.material].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(s.materials[glass.material].ior, 1.5f);
    expectNear(brown.p0, {-4, 1, 0});
    expectNear(s.materials[brown.material].albedo, {0.4f, 0.2f, 0.1f});
    expectNear(metal.p0, {4, 1, 0});
    EXPECT_EQ(s.materials[metal.material].type, MaterialType::Metal);
    expectNear(s.materials[metal.material].albedo, {0.7f, 0.6f, 0.5f});
    EXPECT_FLOAT_EQ(s.materials[metal.material].fuzz, 0.0f);

    int lambertian = 0, metals = 0, dielectrics = 0;
    for (std::size_t i = 1; i + 3 < n; ++i) {
        const Shape& sh = s.shapes[i];
        EXPECT_FLOAT_EQ(sh.radius, 0.2f);
        EXPECT_FLOAT_EQ(sh.p0.y, 0.2f);
        EXPECT_GT(glm::length(sh.p0 - glm::vec3(4, 0.2f, 0)), 0.9f);
        const vkp::Material& m = s.materials[sh.material];
        if (m.type == MaterialType::Lambertian) ++lambertian;
        if (m.type == MaterialType::Metal) {
            ++metals;
            EXPECT_GE(m.albedo.x, 0.5f);
            EXPECT_LE(m.fuzz, 0.5f);
        }
        if (m.type == MaterialType::Dielectric) ++dielectrics;
    }
    // Book proportions 80% / 15% / 5% of ~480 draws.
    EXPECT_GT(lambertian, 300);
    EXPECT_GT(metals, 30);
    EXPECT_GT(dielectrics, 5);

    expectNear(s.camera.lookfrom, {13, 2, 3});
    expectNear(s.camera.lookat, {0, 0, 0});
    EXPECT_FLOAT_EQ(s.camera.vfov, 20.0f);
    EXPECT_FLOAT_EQ(s.camera.defocusAngle, 0.6f);
    EXPECT_FLOAT_EQ(s.camera.focusDist, 10.0f);
    EXPECT_EQ(s.camera.width, 640u);
    EXPECT_EQ(s.camera.height, 360u);
    expectNear(s.render.background, {0.7f, 0.8f, 1.0f});
}

TEST(SceneLoader, EnvSky) {
    const Scene s = vkp::test::inFileFrame(vkp::loadSceneJson(vkp::test::scenesDir() / "env-sky.json"));
    ASSERT_TRUE(s.environment.hasMap());
    EXPECT_EQ(s.environment.file, vkp::test::scenesDir() / "env" / "sky.hdr");  // relative to the JSON file
    EXPECT_EQ(s.environment.image.width, 48u);
    EXPECT_EQ(s.environment.image.height, 24u);
    EXPECT_EQ(s.environment.rotateY, 0.0f);
    EXPECT_EQ(s.render.background, glm::vec3(0.0f));
    // The sun texel (tools/gen_env_sky.py: column 31, row 5) is the brightest, at RGBE precision.
    EXPECT_NEAR(s.environment.image.at(31, 5, 0), 2400.0f, 2400.0f / 128.0f);
    EXPECT_TRUE(s.lights.empty());
}

TEST(SceneLoader, Furnace) {
    const Scene s = vkp::test::inFileFrame(vkp::loadSceneJson(vkp::test::scenesDir() / "furnace.json"));
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_TRUE(s.lights.empty());
    expectNear(s.render.background, {1, 1, 1});
    EXPECT_EQ(s.materials[0].type, MaterialType::Lambertian);
    expectNear(s.materials[0].albedo, {0.5f, 0.5f, 0.5f});
    EXPECT_EQ(s.camera.width, 32u);
    EXPECT_EQ(s.camera.height, 32u);
    // The sphere fills the middle with background all around: its angular radius is between a
    // half and the whole of the half field of view.
    const float angular = std::asin(s.shapes[0].radius / glm::length(s.camera.lookfrom - s.shapes[0].p0));
    EXPECT_LT(angular, glm::radians(s.camera.vfov / 2.0f) * 0.9f);
    EXPECT_GT(angular, glm::radians(s.camera.vfov / 2.0f) * 0.5f);
}

TEST(SceneLoader, Defaults) {
    const Scene s = parse(kGrey, R"([{"type":"sphere","center":[0,0,0],"radius":1,"material":"grey"}])");
    EXPECT_EQ(s.render.spp, 64u);
    EXPECT_EQ(s.render.maxDepth, 50u);
    EXPECT_EQ(s.render.seed, 0u);
    expectNear(s.render.background, {0, 0, 0});
    EXPECT_FLOAT_EQ(s.camera.defocusAngle, 0.0f);
    EXPECT_FLOAT_EQ(s.camera.focusDist, 5.0f);  // |lookfrom - lookat|
    EXPECT_EQ(s.path, "inline.json");
}

TEST(SceneLoader, EmptyObjectListIsAScene) {
    const Scene s = parse("{}", "[]");
    EXPECT_TRUE(s.shapes.empty());
    EXPECT_TRUE(s.lights.empty());
}

// "camera" and "materials" are optional (a scene file may hold just objects, lit by
// --background or --environment): the framing camera of a glTF file without one, and the scene
// read relative to it in double, so a scene 1e7 from the origin keeps its floats.
TEST(SceneLoader, WithoutCameraAndMaterialsTheSceneIsFramed) {
    const Scene empty = vkp::parseSceneJson(R"({"objects": []})", "inline.json");
    EXPECT_TRUE(empty.shapes.empty());
    EXPECT_EQ(empty.camera.width, vkp::kGltfDefaultImageSide);
    EXPECT_EQ(empty.camera.height, vkp::kGltfDefaultImageSide);
    for (double at : {0.0, 1e7}) {
        const std::string text = R"({"materials": {"m": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}}, "objects": [
            {"type": "sphere", "center": [)" + std::to_string(at) + R"(, 2, 3], "radius": 1, "material": "m"}]})";
        const Scene s = vkp::parseSceneJson(text, "inline.json");
        ASSERT_EQ(s.shapes.size(), 1u);
        EXPECT_FLOAT_EQ(s.camera.vfov, 40.0f);
        EXPECT_EQ(s.camera.lookfrom, glm::vec3(0.0f));
        // Looking along -z at the sphere's centre from where its bounding sphere (radius sqrt(3))
        // fits 40 degrees with 5% to spare.
        const double dist = 1.05 * std::sqrt(3.0) / std::sin(20.0 * std::numbers::pi / 180.0);
        EXPECT_NEAR(s.origin.x, at, 1e-9 * std::max(1.0, at));
        EXPECT_NEAR(s.origin.y, 2.0, 1e-9);
        EXPECT_NEAR(s.origin.z, 3.0 + dist, 1e-9);
        EXPECT_EQ(s.shapes[0].p0, glm::vec3(0.0f, 0.0f, float(-dist))) << "at " << at;
        EXPECT_EQ(glm::normalize(s.camera.lookat), glm::vec3(0.0f, 0.0f, -1.0f));
        vkp::SceneJsonOptions wide;
        wide.width = 800;
        wide.height = 200;
        const Scene w = vkp::parseSceneJson(text, "inline.json", wide);
        EXPECT_EQ(w.camera.width, 800u);
        EXPECT_EQ(w.camera.height, 200u);
        EXPECT_NEAR(w.origin.z, 3.0 + dist, 1e-9) << "vfov is the narrower angle here";
    }
}

TEST(SceneLoader, MaterialsInFileOrderWithAllFields) {
    const Scene s = parse(R"({
        "z":{"type":"metal","albedo":[1,0.5,0],"fuzz":0.25},
        "a":{"type":"dielectric","ior":1.33,"fresnel":"exact"},
        "m":{"type":"diffuse_light","emit":[1,2,3],"two_sided":true},
        "e":{"type":"lambertian","albedo":[0.1,0.2,0.3],"emit":[4,0,0]}})",
                          "[]");
    ASSERT_EQ(s.materials.size(), 4u);
    EXPECT_EQ(s.materials[0].name, "z");
    EXPECT_EQ(s.materials[0].type, MaterialType::Metal);
    EXPECT_FLOAT_EQ(s.materials[0].fuzz, 0.25f);
    EXPECT_EQ(s.materials[1].name, "a");
    EXPECT_TRUE(s.materials[1].fresnelExact);
    EXPECT_FLOAT_EQ(s.materials[1].ior, 1.33f);
    expectNear(s.materials[1].albedo, {1, 1, 1});
    EXPECT_TRUE(s.materials[2].twoSided);
    expectNear(s.materials[2].emit, {1, 2, 3});
    EXPECT_TRUE(s.materials[3].emits());
    EXPECT_TRUE(s.materials[3].twoSided);  // emitting lambertian: both faces
}

TEST(SceneLoader, LightsAreEmittersAndSampledObjectsInFileOrder) {
    const Scene s = parse(R"({"grey":{"type":"lambertian","albedo":[0.5,0.5,0.5]},
                             "lamp":{"type":"diffuse_light","emit":[1,1,1]},
                             "dark":{"type":"diffuse_light","emit":[0,0,0]},
                             "glow":{"type":"lambertian","albedo":[0.5,0.5,0.5],"emit":[0,0,2]}})",
                          R"([{"type":"sphere","center":[0,0,0],"radius":1,"material":"grey"},
                              {"type":"box","min":[0,0,0],"max":[1,1,1],"material":"grey","sample":true},
                              {"type":"quad","Q":[0,0,0],"u":[1,0,0],"v":[0,1,0],"material":"lamp"},
                              {"type":"sphere","center":[0,0,0],"radius":1,"material":"grey","sample":false},
                              {"type":"quad","Q":[0,0,0],"u":[1,0,0],"v":[0,1,0],"material":"dark"},
                              {"type":"triangle","v0":[0,0,0],"v1":[1,0,0],"v2":[0,1,0],"material":"glow"}])");
    ASSERT_EQ(s.shapes.size(), 11u);  // sphere, 6 box faces, quad, sphere, quad, triangle
    EXPECT_EQ(s.lights, (std::vector<std::uint32_t>{1, 2, 3, 4, 5, 6, 7, 10}));
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        const bool inList = std::find(s.lights.begin(), s.lights.end(), i) != s.lights.end();
        EXPECT_EQ(s.shapes[i].sampled, inList) << i;
    }
}

TEST(SceneLoader, ZeroAreaTriangleIsKeptButNotALight) {
    const Scene s = parse(kGrey, R"([{"type":"triangle","v0":[0,0,0],"v1":[1,1,1],"v2":[2,2,2],"material":"grey"}])");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_FALSE(s.shapes[0].sampled);
    EXPECT_TRUE(s.lights.empty());
    EXPECT_EQ(vkp::shapeArea(s.shapes[0]), 0.0f);
}

/// The triangle's vertex v0 after the given transform list, starting from point p.
glm::vec3 mapPoint(glm::vec3 p, const std::string& transform) {
    std::string v("[");  // (built step by step: GCC 12 warns falsely on "[" + std::string)
    v += std::to_string(p.x) + "," + std::to_string(p.y) + "," + std::to_string(p.z) + "]";
    const Scene s = parse(kGrey, R"([{"type":"triangle","v0":)" + v +
                                     R"(,"v1":[5,0,0],"v2":[0,5,0],"material":"grey","transform":)" + transform + "}]");
    return s.shapes.at(0).p0;
}

TEST(SceneLoader, RotationConventions) {
    // rotate_y (the book's): x' = cos x + sin z, z' = -sin x + cos z.
    const float c = std::cos(glm::radians(30.0f)), sn = std::sin(glm::radians(30.0f));
    expectNear(mapPoint({1, 2, 3}, R"([{"rotate_y":30}])"), {c * 1 + sn * 3, 2, -sn * 1 + c * 3});
    expectNear(mapPoint({1, 0, 0}, R"([{"rotate_y":90}])"), {0, 0, -1});
    // Right-handed x and z: y -> z about x, x -> y about z.
    expectNear(mapPoint({0, 1, 0}, R"([{"rotate_x":90}])"), {0, 0, 1});
    expectNear(mapPoint({1, 2, 3}, R"([{"rotate_x":30}])"), {1, c * 2 - sn * 3, sn * 2 + c * 3});
    expectNear(mapPoint({1, 0, 0}, R"([{"rotate_z":90}])"), {0, 1, 0});
    expectNear(mapPoint({1, 2, 3}, R"([{"rotate_z":30}])"), {c * 1 - sn * 2, sn * 1 + c * 2, 3});
    // Multiples of 90 degrees are exact.
    EXPECT_EQ(mapPoint({1, 0, 0}, R"([{"rotate_y":-270}])"), glm::vec3(0, 0, -1));
}

TEST(SceneLoader, TransformListAppliesInOrder) {
    expectNear(mapPoint({0, 0, 0}, R"([{"translate":[1,0,0]},{"rotate_y":90}])"), {0, 0, -1});
    expectNear(mapPoint({0, 0, 0}, R"([{"rotate_y":90},{"translate":[1,0,0]}])"), {1, 0, 0});
    expectNear(mapPoint({1, 1, 1}, R"([{"scale":2},{"translate":[1,0,0]}])"), {3, 2, 2});
    expectNear(mapPoint({1, 1, 1}, R"([{"translate":[1,0,0]},{"scale":[2,3,4]}])"), {4, 3, 4});
    expectNear(mapPoint({1, 2, 3}, "[]"), {1, 2, 3});
}

TEST(SceneLoader, SphereTransform) {
    const Scene s = parse(kGrey, R"([{"type":"sphere","center":[1,0,0],"radius":0.5,"material":"grey",
        "transform":[{"scale":2},{"rotate_z":90},{"scale":[-3,3,3]},{"translate":[0,0,7]}]}])");
    expectNear(s.shapes[0].p0, {0, 6, 7});
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 3.0f);  // 0.5 * 2 * 3; a mirror does not change a sphere
}

TEST(SceneLoader, QuadTransformAndMirror) {
    const std::string quad = R"([{"type":"quad","Q":[1,0,0],"u":[1,0,0],"v":[0,1,0],"material":"grey","transform":)";
    const Scene turned = parse(kGrey, quad + R"([{"rotate_y":90},{"translate":[0,1,0]}]}])");
    expectNear(turned.shapes[0].p0, {0, 1, -1});  // a point: rotated and moved
    expectNear(turned.shapes[0].p1, {0, 0, -1});  // edges: rotated only
    expectNear(turned.shapes[0].p2, {0, 1, 0});
    expectNear(glm::normalize(quadNormal(turned.shapes[0])), {1, 0, 0});
    // A mirror maps u and v and so turns the front face (u x v) over: +z becomes +z, not -z,
    // although the mirror z -> -z maps the old front side onto -z.
    const Scene mirrored = parse(kGrey, quad + R"([{"scale":[1,1,-1]}]}])");
    expectNear(quadNormal(mirrored.shapes[0]), {0, 0, 1});
    const Scene flipped = parse(kGrey, quad + R"([{"scale":[-1,1,1]}]}])");
    expectNear(quadNormal(flipped.shapes[0]), {0, 0, -1});
}

TEST(SceneLoader, BoxFacesPointOutward) {
    const Scene s = parse(kGrey, R"([{"type":"box","min":[-1,-2,-3],"max":[4,5,6],"material":"grey"},
        {"type":"box","min":[0,0,0],"max":[1,2,3],"material":"grey","transform":[{"rotate_x":33},{"rotate_z":-71},{"scale":3}]}])");
    ASSERT_EQ(s.shapes.size(), 12u);
    expectBoxFacesOutward(s, 0);
    expectBoxFacesOutward(s, 6);
    // Each face of the first box lies in its plane and spans the whole side.
    float area = 0.0f;
    for (std::size_t i = 0; i < 6; ++i) area += vkp::shapeArea(s.shapes[i]);
    EXPECT_FLOAT_EQ(area, 2.0f * (5 * 7 + 5 * 9 + 7 * 9));
    expectNear(s.shapes[0].p0, {-1, -2, 6});  // front face (z = max), as the book orders them
    expectNear(glm::normalize(quadNormal(s.shapes[0])), {0, 0, 1});
}

TEST(SceneLoader, ReadmeExampleLoads) {
    // The complete example of scenes/README.md is valid and means what the README says of it.
    std::ifstream in(vkp::test::scenesDir() / "README.md");
    ASSERT_TRUE(in);
    std::stringstream text;
    text << in.rdbuf();
    const std::string readme = text.str();
    const std::size_t begin = readme.find("```json\n", readme.find("## A complete example"));
    ASSERT_NE(begin, std::string::npos);
    const std::size_t end = readme.find("```", begin + 8);
    ASSERT_NE(end, std::string::npos);
    const Scene s = vkp::test::inFileFrame(vkp::parseSceneJson(readme.substr(begin + 8, end - begin - 8), "README.md"));
    ASSERT_EQ(s.shapes.size(), 10u);
    EXPECT_EQ(s.lights, (std::vector<std::uint32_t>{1, 2, 9}));
    expectNear(glm::normalize(quadNormal(s.shapes[0])), {0, 1, 0});
    expectNear(glm::normalize(quadNormal(s.shapes[1])), {0, -1, 0});
    expectBoxFacesOutward(s, 3);
}

TEST(SceneLoader, ShapeArea) {
    Shape sphere;
    sphere.radius = 2.0f;
    EXPECT_FLOAT_EQ(vkp::shapeArea(sphere), 16.0f * 3.14159265f);
    Shape tri;
    tri.type = ShapeType::Triangle;
    tri.p0 = {1, 1, 1};
    tri.p1 = {3, 1, 1};
    tri.p2 = {1, 4, 1};
    EXPECT_FLOAT_EQ(vkp::shapeArea(tri), 3.0f);
}

}  // namespace
