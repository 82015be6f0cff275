// Camera-relative space (docs/design.md "Camera-relative space"): the loaders compose a scene in
// double and express it relative to the camera before anything becomes float, so a scene moved
// far from the origin loads as the same floats (to one float step) as at the origin, and its
// Scene::origin says where it was.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/errors.h"
#include "file_frame.h"
#include "moved_scene.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

/// The spacing of floats at |x| (one unit in the last place).
double ulp(float x) { return double(std::nextafter(std::abs(x), INFINITY)) - double(std::abs(x)); }

/// a and b agree to one float step in every coordinate of every position; returns the largest
/// difference seen (in units of the scene).
double expectSamePositions(const Scene& a, const Scene& b, const std::string& what) {
    EXPECT_EQ(a.shapes.size(), b.shapes.size()) << what;
    double worst = 0.0;
    auto same = [&](glm::vec3 p, glm::vec3 q, std::size_t i) {
        for (int k = 0; k < 3; ++k) {
            const double d = std::abs(double(p[k]) - double(q[k]));
            worst = std::max(worst, d);
            EXPECT_LE(d, std::max(ulp(p[k]), ulp(q[k]))) << what << ": shape " << i << " coordinate " << k;
        }
    };
    for (std::size_t i = 0; i < std::min(a.shapes.size(), b.shapes.size()); ++i) {
        same(a.shapes[i].p0, b.shapes[i].p0, i);
        same(a.shapes[i].p1, b.shapes[i].p1, i);
        same(a.shapes[i].p2, b.shapes[i].p2, i);
        EXPECT_EQ(a.shapes[i].radius, b.shapes[i].radius) << what << ": shape " << i;
    }
    same(a.camera.lookfrom, b.camera.lookfrom, 99999);
    same(a.camera.lookat, b.camera.lookat, 99999);
    return worst;
}

const std::vector<glm::dvec3> kDirections = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};

TEST(SceneFrame, JsonSceneIsCameraRelative) {
    const Scene s = loadSceneJson(scenesDir() / "cornell-classic.json");
    EXPECT_EQ(s.origin, glm::dvec3(278, 278, -800));  // the camera's lookfrom
    EXPECT_EQ(s.camera.lookfrom, glm::vec3(0.0f));
    EXPECT_EQ(s.camera.lookat, glm::vec3(0, 0, 800));
    EXPECT_EQ(s.shapes[0].p0, glm::vec3(555 - 278, 0 - 278, 0 + 800));  // Q of the green wall
    EXPECT_EQ(s.shapes[0].p1, glm::vec3(0, 0, 555));                    // u: a direction, not moved
}

TEST(SceneFrame, CornellMovedUpTo1e7LoadsAsTheSameFloats) {
    const Scene base = loadSceneJson(scenesDir() / "cornell-classic.json");
    for (double m : {1e5, 1e6, 1e7, 1e9})
        for (glm::dvec3 dir : kDirections) {
            const glm::dvec3 t = m * dir;
            const std::string what = describeMove(t, 1.0);
            const Scene moved = loadSceneJson(movedJsonScene(scenesDir() / "cornell-classic.json", t, 1.0, "frame_moved"));
            EXPECT_EQ(moved.origin, base.origin + t) << what;
            expectSamePositions(moved, base, what);
        }
}

TEST(SceneFrame, ScaledSceneKeepsItsShapeAtEveryScale) {
    // Scaled by s about the origin: every float is the unscaled one times s, to a few float steps
    // (the scale is applied in double, then one rounding).
    const Scene base = loadSceneJson(scenesDir() / "cornell-classic.json");
    for (double s : {1e-6, 1e-3, 1e3, 1e6}) {
        const Scene scaled = loadSceneJson(movedJsonScene(scenesDir() / "cornell-classic.json", glm::dvec3(0.0), s, "frame_scaled"));
        EXPECT_NEAR(scaled.origin.x / base.origin.x, s, 1e-12 * s);
        for (std::size_t i = 0; i < base.shapes.size(); ++i)
            for (int k = 0; k < 3; ++k) {
                const double want = double(base.shapes[i].p0[k]) * s;
                EXPECT_NEAR(scaled.shapes[i].p0[k], want, 4.0 * ulp(float(want)) + 1e-30) << "scale " << s << " shape " << i;
            }
    }
}

TEST(SceneFrame, GltfRootTranslatedBy1e7LoadsAsTheSameFloats) {
    const std::filesystem::path src = scenesDir() / "blender-cornell-classic" / "cornell-rtiow.gltf";
    const Scene base = loadSceneGltf(src);
    for (glm::dvec3 dir : kDirections) {
        const glm::dvec3 t = 1e7 * dir;
        const Scene moved = loadSceneGltf(movedGltfScene(src, t, "frame_gltf"));
        const glm::dvec3 d = moved.origin - (base.origin + t);
        EXPECT_LE(glm::length(d), 1e-8 * 1e7) << describeMove(t, 1.0);  // the camera node's position, in double
        expectSamePositions(moved, base, "glTF " + describeMove(t, 1.0));
    }
}

TEST(SceneFrame, GltfWithoutCameraIsFramedAndCameraRelative) {
    const std::filesystem::path src = scenesDir() / "gltf" / "no-camera.gltf";
    const Scene base = loadSceneGltf(src);
    EXPECT_EQ(base.camera.lookfrom, glm::vec3(0.0f));
    const Scene moved = loadSceneGltf(movedGltfScene(src, glm::dvec3(1e7, -1e7, 1e7), "frame_gltf_framed"));
    EXPECT_EQ(moved.camera.lookfrom, glm::vec3(0.0f));
    EXPECT_NEAR(moved.origin.x - base.origin.x, 1e7, 1e-6);
    expectSamePositions(moved, base, "framed glTF moved by 1e7");
}

TEST(SceneFrame, IncludedGltfFollowsTheJsonCamera) {
    // include.json places glTF files under JSON transforms: the include's matrix is moved into the
    // camera's frame in double before the file's vertices become float.
    const Scene base = loadSceneJson(scenesDir() / "gltf" / "include.json");
    nlohmann::ordered_json doc = readJsonFile(scenesDir() / "gltf" / "include.json");
    const std::filesystem::path dir = scratchDir("frame_include");
    for (auto& o : doc["objects"])
        if (o.contains("file")) o["file"] = (scenesDir() / "gltf" / o["file"].get<std::string>()).string();
    writeJsonFile(doc, dir / "include-abs.json");
    SceneJsonOptions allow;  // the included files are in scenes/gltf, not beside include-abs.json
    allow.allowPaths = {scenesDir() / "gltf"};
    const Scene absBase = loadSceneJson(dir / "include-abs.json", allow);
    expectSamePositions(absBase, base, "include with absolute paths");
    const Scene moved = loadSceneJson(movedJsonScene(dir / "include-abs.json", glm::dvec3(1e7, 1e7, 1e7), 1.0, "frame_include_moved"), allow);
    expectSamePositions(moved, base, "include moved by 1e7");
    EXPECT_EQ(moved.origin, base.origin + glm::dvec3(1e7));
}

TEST(SceneFrame, CoordinatesBeyondFloatRangeLoadWhenTheCameraIsNear) {
    // 3e38 + 1e38 is not a float, but it is 1e38 from a camera at 3e38.
    const std::string text = R"({"camera":{"lookfrom":[3e38,0,5],"lookat":[3e38,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8},
        "materials":{"m":{"type":"lambertian","albedo":[0.5,0.5,0.5]}},
        "objects":[{"type":"sphere","center":[3e38,0,0],"radius":1,"material":"m"},
                   {"type":"triangle","v0":[4e38,0,0],"v1":[3e38,1,0],"v2":[3e38,0,1],"material":"m"}]})";
    const Scene s = parseSceneJson(text, "far.json");
    EXPECT_EQ(s.origin, glm::dvec3(3e38, 0, 5));
    EXPECT_EQ(s.shapes[0].p0, glm::vec3(0, 0, -5));
    EXPECT_FLOAT_EQ(s.shapes[1].p0.x, 1e38f);
}

TEST(SceneFrame, InFileFrameUndoesTheMove) {
    const Scene s = inFileFrame(loadSceneJson(scenesDir() / "cornell-classic.json"));
    EXPECT_EQ(s.origin, glm::dvec3(0.0));
    EXPECT_EQ(s.camera.lookfrom, glm::vec3(278, 278, -800));
    EXPECT_EQ(s.shapes[0].p0, glm::vec3(555, 0, 0));
}

// sceneBounds (the framing camera's box): placed shapes exactly, and each instance as the placed
// box of its mesh's object-space box.
TEST(SceneFrame, BoundsOfShapesAndInstances) {
    Scene s;
    Shape tri;
    tri.type = ShapeType::Triangle;
    tri.p0 = glm::vec3(0.0f);
    tri.p1 = glm::vec3(1.0f, 0.0f, 0.0f);
    tri.p2 = glm::vec3(0.0f, 1.0f, 0.0f);
    const auto [elo, ehi] = sceneBounds(s);
    EXPECT_GT(elo.x, ehi.x) << "empty: lo > hi";
    s.meshes.push_back(InstancedMesh{"m", {tri}});
    MeshInstance a, b;
    a.objectToWorld[3] = glm::dvec4(10.0, 0.0, 0.0, 1.0);
    b.objectToWorld = glm::dmat4(2.0);
    b.objectToWorld[3] = glm::dvec4(0.0, -5.0, 3.0, 1.0);
    s.instances = {a, b};
    Shape sphere;
    sphere.p0 = glm::vec3(0.0f, 0.0f, -4.0f);
    sphere.radius = 1.0f;
    s.shapes.push_back(sphere);
    const auto [lo, hi] = sceneBounds(s);
    EXPECT_EQ(lo, glm::dvec3(-1.0, -5.0, -5.0));
    EXPECT_EQ(hi, glm::dvec3(11.0, 1.0, 3.0));
}

}  // namespace
}  // namespace vkp::test
