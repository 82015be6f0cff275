// The glTF loader on well-formed files: the Blender-exported Cornell box against
// cornell-classic.json, and the scenes of scenes/gltf/ (tools/gen_gltf_scenes.py), one feature each:
// topologies and index types, the node hierarchy, accessors, cameras, framing, extensions,
// and glTF files included in a JSON scene.
#include <gtest/gtest.h>

#include "file_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>

#include "core/errors.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace {

using namespace vkp;

std::filesystem::path gltfScene(const std::string& name) { return test::scenesDir() / "gltf" / name; }

glm::vec3 faceNormal(const Shape& s) { return glm::normalize(glm::cross(s.p1 - s.p0, s.p2 - s.p0)); }

void expectVec(glm::vec3 a, glm::vec3 b, float tol, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

/// The triangle's corners as a set (any rotation of the order), compared with tolerance.
bool sameCorners(const Shape& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, float tol = 1e-5f) {
    const glm::vec3 p[3] = {s.p0, s.p1, s.p2};
    const glm::vec3 q[3] = {a, b, c};
    for (int r = 0; r < 3; ++r) {  // same winding: a rotation of (a, b, c)
        bool all = true;
        for (int i = 0; i < 3; ++i) all = all && glm::length(p[i] - q[(i + r) % 3]) <= tol;
        if (all) return true;
    }
    return false;
}

// ---- The Blender Cornell box -------------------------------------------------------------

/// scenes/blender-cornell-classic/cornell-rtiow.gltf (its README.md says how it was made). Part of
/// the repository: a missing file fails the test.
class BlenderCornell : public ::testing::Test {
protected:
    void SetUp() override { ASSERT_TRUE(std::filesystem::exists(path_)) << path_ << " is missing"; }
    std::filesystem::path path_ = test::scenesDir() / "blender-cornell-classic" / "cornell-rtiow.gltf";
};

TEST_F(BlenderCornell, LoadsWithoutWarningsAs36TrianglesAnd2Lights) {
    const Scene s = vkp::test::inFileFrame(loadSceneGltf(path_));
    EXPECT_TRUE(s.warnings.empty()) << (s.warnings.empty() ? "" : s.warnings[0]);
    ASSERT_EQ(s.shapes.size(), 36u);  // 5 walls + light: 2 triangles each; 2 boxes: 12 each
    for (const Shape& sh : s.shapes) EXPECT_EQ(sh.type, ShapeType::Triangle);
    ASSERT_EQ(s.lights.size(), 2u);
    for (std::uint32_t l : s.lights) {
        const Shape& sh = s.shapes[l];
        const Material& m = s.materials[sh.material];
        EXPECT_EQ(m.type, MaterialType::Pbr);
        expectVec(m.emit, glm::vec3(15.0f), 1e-6f, "emissiveFactor x KHR_materials_emissive_strength");
        EXPECT_FALSE(m.twoSided);
        expectVec(faceNormal(sh), glm::vec3(0, -1, 0), 1e-6f, "the light faces down");
    }
    // Every triangle has its NORMAL, which agrees with its winding (Blender writes flat faces).
    for (const Shape& sh : s.shapes) {
        const TriangleVertices& tv = s.triangleVertices.at(sh.attributes);
        EXPECT_EQ(tv.flags, TriangleVertices::kHasNormal);
        for (std::uint32_t v : tv.v) EXPECT_GT(glm::dot(s.vertices.normal.at(v), faceNormal(sh)), 0.999f);
    }
    EXPECT_TRUE(s.vertices.uv.empty());
    EXPECT_TRUE(s.vertices.tangent.empty());
}

TEST_F(BlenderCornell, CameraMatchesCornellClassicJson) {
    const Scene g = vkp::test::inFileFrame(loadSceneGltf(path_));
    const Scene j = vkp::test::inFileFrame(loadSceneJson(test::scenesDir() / "cornell-classic.json"));
    expectVec(g.camera.lookfrom, j.camera.lookfrom, 1e-3f, "lookfrom");
    expectVec(glm::normalize(g.camera.lookat - g.camera.lookfrom), glm::normalize(j.camera.lookat - j.camera.lookfrom),
              1e-6f, "view direction");
    expectVec(glm::normalize(g.camera.vup), glm::normalize(j.camera.vup), 1e-6f, "vup");
    EXPECT_NEAR(g.camera.vfov, j.camera.vfov, 1e-4f);  // yfov is stored as float32 radians
    EXPECT_EQ(g.camera.defocusAngle, 0.0f);
    EXPECT_EQ(g.camera.width, kGltfDefaultImageSide);  // aspectRatio 1
    EXPECT_EQ(g.camera.height, kGltfDefaultImageSide);
    GltfOptions o;
    o.width = 600;  // the other side follows the aspect ratio
    const Scene g600 = vkp::test::inFileFrame(loadSceneGltf(path_, o));
    EXPECT_EQ(g600.camera.width, j.camera.width);
    EXPECT_EQ(g600.camera.height, j.camera.height);
}

TEST_F(BlenderCornell, GeometryAndKernelMaterialsMatchCornellClassicJson) {
    const Scene g = vkp::test::inFileFrame(loadSceneGltf(path_));
    const Scene j = vkp::test::inFileFrame(loadSceneJson(test::scenesDir() / "cornell-classic.json"));
    // Area per kernel material and the faces' orientation, quad by quad.
    std::map<std::string, double> areaG, areaJ;
    // The glTF walls are the glTF BRDF with metallic 0 (a specular layer over the JSON lambertian's
    // base colour): keyed as lambertian, so that the base colours and areas are compared. Sides
    // matter for emitters only (glTF doubleSided).
    auto key = [](const Material& m) {
        const Material k = kernelMaterial(m);
        const bool dielectricPbr = k.type == MaterialType::Pbr && k.pbr.metallic == 0.0f;
        const unsigned type = unsigned(dielectricPbr ? MaterialType::Lambertian : k.type);
        char buf[128];
        std::snprintf(buf, sizeof buf, "%u %.4f %.4f %.4f emit %.3f %.3f %.3f %d", type, k.albedo.x, k.albedo.y,
                      k.albedo.z, k.emit.x, k.emit.y, k.emit.z, int(k.emits() && k.twoSided));
        return std::string(buf);
    };
    for (const Shape& s : g.shapes) areaG[key(g.materials[s.material])] += shapeArea(s);
    for (const Shape& s : j.shapes) areaJ[key(j.materials[s.material])] += shapeArea(s);
    ASSERT_EQ(areaG.size(), areaJ.size());
    for (const auto& [k, a] : areaJ) {
        ASSERT_TRUE(areaG.count(k)) << "no glTF surface renders as " << k;
        EXPECT_NEAR(areaG[k], a, 1e-4 * a) << k;
    }
    // Each glTF triangle lies on a JSON quad of the same kernel material facing the same way
    // (where a box's bottom lies on the floor, either of the two quads there).
    for (const Shape& t : g.shapes) {
        const glm::vec3 c = (t.p0 + t.p1 + t.p2) / 3.0f;
        bool found = false;
        for (const Shape& q : j.shapes) {
            const glm::vec3 n = glm::normalize(glm::cross(q.p1, q.p2));
            const glm::vec3 d = c - q.p0;
            const float a = glm::dot(d, q.p1) / glm::dot(q.p1, q.p1), b = glm::dot(d, q.p2) / glm::dot(q.p2, q.p2);
            if (std::abs(glm::dot(d, n)) < 1e-2f && a > 0 && a < 1 && b > 0 && b < 1 &&
                key(g.materials[t.material]) == key(j.materials[q.material]) && glm::dot(faceNormal(t), n) > 0.9999f) {
                found = true;
            }
        }
        EXPECT_TRUE(found) << "no JSON quad like the triangle with centroid " << c.x << " " << c.y << " " << c.z;
    }
}

// ---- Topologies, index types, the default material ----------------------------------------

TEST(GltfLoader, EveryTopologyAndIndexType) {
    const Scene s = vkp::test::inFileFrame(loadSceneGltf(gltfScene("modes.gltf")));
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.shapes.size(), 14u);  // 4 x 2 (list), 2 (strip), 4 (fan)
    std::map<int, double> areaBySquare;
    for (const Shape& sh : s.shapes) {
        expectVec(faceNormal(sh), glm::vec3(0, 0, 1), 1e-6f, "front faces +z");
        const glm::vec3 c = (sh.p0 + sh.p1 + sh.p2) / 3.0f;
        areaBySquare[int(std::floor(c.x / 2.0f))] += shapeArea(sh);
        EXPECT_EQ(s.triangleVertices.at(sh.attributes).flags, 0u);  // no NORMAL: flat
    }
    ASSERT_EQ(areaBySquare.size(), 6u);  // non-indexed, u8, u16, u32, strip, fan: one unit square each
    for (const auto& [sq, a] : areaBySquare) EXPECT_NEAR(a, 1.0, 1e-6) << "square " << sq;
    EXPECT_TRUE(sameCorners(s.shapes[8], {8, 0, 0}, {9, 0, 0}, {8, 1, 0}));   // strip: p0 p1 p2
    EXPECT_TRUE(sameCorners(s.shapes[9], {9, 0, 0}, {9, 1, 0}, {8, 1, 0}));   // strip: p1 p3 p2
    EXPECT_TRUE(sameCorners(s.shapes[10], {10, 0, 0}, {11, 0, 0}, {10.5f, 0.5f, 0}));  // fan: p1 p2 p0
    // No material: the glTF default (white, metallic 1, roughness 1, single-sided).
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    EXPECT_EQ(m.type, MaterialType::Pbr);
    EXPECT_EQ(m.pbr.baseColor, glm::vec4(1.0f));
    EXPECT_EQ(m.pbr.metallic, 1.0f);
    EXPECT_EQ(m.pbr.roughness, 1.0f);
    EXPECT_FALSE(m.twoSided);
    EXPECT_TRUE(s.lights.empty());
}

// ---- The node hierarchy ------------------------------------------------------------------

TEST(GltfLoader, NodeHierarchyWithTrsMatrixMirrorAndZeroScale) {
    const Scene s = vkp::test::inFileFrame(loadSceneGltf(gltfScene("hierarchy.gltf")));  // default scene: 1
    // Depth first, children in order: trs, child (under matrix), mirror; the zero-scaled node is gone.
    ASSERT_EQ(s.shapes.size(), 3u);
    // trs: scale 2, rotate 90 degrees about z, translate (0,5,0), parent (10,0,0).
    EXPECT_TRUE(sameCorners(s.shapes[0], {10, 5, 0}, {10, 7, 0}, {8, 5, 0}));
    // child: translate (1,0,0) under matrix (translate (0,0,3)) under parent.
    EXPECT_TRUE(sameCorners(s.shapes[1], {11, 0, 3}, {12, 0, 3}, {11, 1, 3}));
    // mirror: scale (-1,1,1); corners (10,0,0), (9,0,0), (10,1,0) with two swapped: the front stays +z.
    EXPECT_TRUE(sameCorners(s.shapes[2], {10, 0, 0}, {10, 1, 0}, {9, 0, 0}));
    for (const Shape& sh : s.shapes) {
        expectVec(faceNormal(sh), glm::vec3(0, 0, 1), 1e-6f, "front faces");
        const TriangleVertices& tv = s.triangleVertices.at(sh.attributes);
        EXPECT_EQ(tv.flags, TriangleVertices::kHasNormal);
        for (std::uint32_t v : tv.v) expectVec(s.vertices.normal.at(v), glm::vec3(0, 0, 1), 1e-6f, "shading normal");
    }
    GltfOptions other;
    other.scene = 0;
    const Scene s0 = vkp::test::inFileFrame(loadSceneGltf(gltfScene("hierarchy.gltf"), other));
    ASSERT_EQ(s0.shapes.size(), 1u);
    EXPECT_TRUE(sameCorners(s0.shapes[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
    GltfOptions missing;
    missing.scene = 2;
    try {
        loadSceneGltf(gltfScene("hierarchy.gltf"), missing);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--gltf-scene 2: scene 2 does not exist (the file has 2 scenes)"), std::string::npos)
            << e.what();
    }
}

// ---- Accessors ---------------------------------------------------------------------------

TEST(GltfLoader, StridedSparseNormalizedAndQuantizedAccessors) {
    const Scene s = vkp::test::inFileFrame(loadSceneGltf(gltfScene("accessors.glb")));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();  // KHR_mesh_quantization is implemented
    ASSERT_EQ(s.shapes.size(), 6u);
    // 0: interleaved float positions, int8 normalized normals, uint16 normalized UVs.
    EXPECT_TRUE(sameCorners(s.shapes[0], {0, 0, 0}, {1, 0, 0}, {1, 1, 0}));
    const TriangleVertices& t0 = s.triangleVertices.at(s.shapes[0].attributes);
    EXPECT_EQ(t0.flags, TriangleVertices::kHasNormal | TriangleVertices::kHasUv);
    expectVec(s.vertices.normal.at(t0.v[0]), glm::vec3(0, 0, 1), 0.0f, "127 / 127");
    EXPECT_EQ(s.vertices.uv.at(t0.v[0]), glm::vec2(0, 1));  // 65535 / 65535
    EXPECT_EQ(s.vertices.uv.at(t0.v[1]), glm::vec2(1, 1));
    EXPECT_EQ(s.vertices.uv.at(t0.v[2]), glm::vec2(1, 0));
    // 1: sparse: vertex 3 moved to (2,2,0).
    EXPECT_TRUE(sameCorners(s.shapes[3], {2, 0, 0}, {3, 1, 0}, {2, 2, 0}));
    // 2: no bufferView (zeros) with every vertex set by sparse values.
    EXPECT_TRUE(sameCorners(s.shapes[4], {4, 0, 0}, {5, 0, 0}, {4, 1, 0}));
    // 3: int16 positions, normalized uint8 UVs (51 / 255 = 0.2).
    EXPECT_TRUE(sameCorners(s.shapes[5], {6, 0, 0}, {7, 0, 0}, {6, 1, 0}));
    const TriangleVertices& t5 = s.triangleVertices.at(s.shapes[5].attributes);
    EXPECT_EQ(s.vertices.uv.at(t5.v[2]), glm::vec2(0, 0.2f));
    // Primitives without UVs get zeros, so that uv stays as long as normal.
    EXPECT_EQ(s.vertices.uv.size(), s.vertices.normal.size());
    EXPECT_EQ(s.triangleVertices.at(s.shapes[4].attributes).flags, 0u);
}

// ---- Cameras -----------------------------------------------------------------------------

TEST(GltfLoader, FirstPerspectiveCameraOrTheChosenOne) {
    const Scene s = vkp::test::inFileFrame(loadSceneGltf(gltfScene("cameras.gltf")));
    // camera 1 under a parent turned 90 degrees about +y: at (5,1,0) looking along -x.
    expectVec(s.camera.lookfrom, {5, 1, 0}, 1e-5f, "lookfrom");
    expectVec(glm::normalize(s.camera.lookat - s.camera.lookfrom), {-1, 0, 0}, 1e-6f, "view direction");
    expectVec(s.camera.vup, {0, 1, 0}, 1e-6f, "vup");
    EXPECT_NEAR(s.camera.vfov, 0.5 * 180.0 / std::numbers::pi, 1e-4);
    EXPECT_EQ(s.camera.width, 512u);  // aspectRatio 2
    EXPECT_EQ(s.camera.height, 256u);

    GltfOptions o;
    o.camera = 2;
    const Scene s2 = vkp::test::inFileFrame(loadSceneGltf(gltfScene("cameras.gltf"), o));
    expectVec(s2.camera.lookfrom, {0, 0, 10}, 1e-6f, "lookfrom");
    expectVec(glm::normalize(s2.camera.lookat - s2.camera.lookfrom), {0, 0, -1}, 1e-6f, "view direction");
    EXPECT_NEAR(s2.camera.vfov, 180.0 / std::numbers::pi, 1e-4);
    EXPECT_EQ(s2.camera.width, 512u);  // no aspectRatio: square
    EXPECT_EQ(s2.camera.height, 512u);

    GltfOptions h;
    h.height = 100;  // width follows the aspect ratio 2
    EXPECT_EQ(loadSceneGltf(gltfScene("cameras.gltf"), h).camera.width, 200u);
    GltfOptions both;
    both.width = 30;
    both.height = 40;
    const Scene sb = vkp::test::inFileFrame(loadSceneGltf(gltfScene("cameras.gltf"), both));
    EXPECT_EQ(sb.camera.width, 30u);
    EXPECT_EQ(sb.camera.height, 40u);

    for (std::uint32_t bad : {0u, 7u}) {
        GltfOptions b;
        b.camera = bad;
        try {
            loadSceneGltf(gltfScene("cameras.gltf"), b);
            FAIL() << "no error for camera " << bad;
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(bad == 0 ? "camera 0 (\"ortho\"): is orthographic" : "--camera 7: the file has 3 cameras"),
                      std::string::npos) << what;
        }
    }
}

TEST(GltfLoader, WithoutCameraFramesTheBounds) {
    const Scene s = vkp::test::inFileFrame(loadSceneGltf(gltfScene("no-camera.gltf")));
    ASSERT_EQ(s.shapes.size(), 12u);
    const glm::vec3 centre(3, 2, 1);
    for (const Shape& sh : s.shapes) {  // the cube's faces point outwards
        EXPECT_GT(glm::dot(faceNormal(sh), (sh.p0 + sh.p1 + sh.p2) / 3.0f - centre), 0.0f);
    }
    expectVec(s.camera.lookat, centre, 1e-5f, "looks at the centre");
    EXPECT_GT(s.camera.lookfrom.z, centre.z);
    // Every corner of the cube is inside the image.
    const glm::vec3 w = glm::normalize(s.camera.lookfrom - s.camera.lookat);
    const glm::vec3 u = glm::normalize(glm::cross(s.camera.vup, w)), v = glm::cross(w, u);
    const float tanV = std::tan(glm::radians(s.camera.vfov) / 2.0f);
    const float tanH = tanV * float(s.camera.width) / float(s.camera.height);
    for (const Shape& sh : s.shapes) {
        for (const glm::vec3& p : {sh.p0, sh.p1, sh.p2}) {
            const glm::vec3 d = p - s.camera.lookfrom;
            const float depth = -glm::dot(d, w);
            ASSERT_GT(depth, 0.0f);
            EXPECT_LT(std::abs(glm::dot(d, u)) / depth, tanH);
            EXPECT_LT(std::abs(glm::dot(d, v)) / depth, tanV);
        }
    }
}

// ---- Extensions --------------------------------------------------------------------------

TEST(GltfLoader, AnExtensionOnlyUsedGivesOneWarningNamingIt) {
    const Scene s = vkp::test::inFileFrame(loadSceneGltf(gltfScene("extensions.gltf")));
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("extension KHR_materials_variants is not supported"), std::string::npos) << s.warnings[0];
    EXPECT_EQ(s.warnings[0].rfind(gltfScene("extensions.gltf").string() + ": extensionsUsed: ", 0), 0u) << s.warnings[0];
    EXPECT_EQ(s.shapes.size(), 1u);
}

// ---- glTF inside a JSON scene ------------------------------------------------------------

TEST(GltfLoader, IncludedInAJsonSceneWithTransformAndMaterialOverride) {
    const Scene s = vkp::test::inFileFrame(loadSceneJson(gltfScene("include.json")));
    ASSERT_EQ(s.shapes.size(), 1u + 3u + 14u);
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.materials.size(), 3u);  // grey, ground, and hierarchy.gltf's default material
    EXPECT_EQ(s.materials[2].type, MaterialType::Pbr);
    EXPECT_EQ(s.shapes[0].type, ShapeType::Quad);
    EXPECT_EQ(s.shapes[0].attributes, Shape::kNoAttributes);
    // hierarchy.gltf moved by (-5, 0, -2): its "child" triangle.
    EXPECT_TRUE(sameCorners(s.shapes[2], {6, 0, 1}, {7, 0, 1}, {6, 1, 1}));
    for (int i = 1; i <= 3; ++i) EXPECT_EQ(s.shapes[std::size_t(i)].material, 2u);
    // modes.gltf scaled by 0.5, moved by (0,-1,2), every triangle "grey".
    EXPECT_TRUE(sameCorners(s.shapes[4], {0, -1, 2}, {0.5f, -1, 2}, {0.5f, -0.5f, 2}));
    for (std::size_t i = 4; i < s.shapes.size(); ++i) EXPECT_EQ(s.shapes[i].material, 0u);
}

TEST(GltfLoader, IncludeErrorsNameTheJsonPointer) {
    const auto dir = test::scratchDir("gltf_include_errors");
    std::filesystem::copy_file(gltfScene("modes.gltf"), dir / "modes.gltf", std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(gltfScene("modes.bin"), dir / "modes.bin", std::filesystem::copy_options::overwrite_existing);
    const std::string head =
        R"({"camera":{"lookfrom":[0,0,5],"lookat":[0,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8},)"
        R"("materials":{"m":{"type":"lambertian","albedo":[0.5,0.5,0.5]}},"objects":[)";
    struct Case {
        std::string object, fragment;
    };
    const Case cases[] = {
        {R"({"type":"gltf","file":"nope.gltf"})", "/objects/0/file: cannot read"},
        {R"({"type":"gltf","file":"modes.gltf","material":"x"})", "/objects/0/material: unknown material \"x\""},
        {R"({"type":"gltf","file":"modes.gltf","sample":true})", "/objects/0/sample: unknown key"},
        {R"({"type":"gltf"})", "/objects/0/file: missing required key"},
        {R"({"type":"gltf","file":"modes.gltf","transform":[{"scale":0}]})", "/objects/0/transform/0/scale: must not be 0"},
    };
    for (const Case& c : cases) {
        const auto file = dir / "scene.json";
        try {
            parseSceneJson(head + c.object + "]}", file);
            ADD_FAILURE() << "no error for " << c.object;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
        }
    }
    // A relative file is found next to the JSON file.
    const Scene ok = vkp::test::inFileFrame(parseSceneJson(head + R"({"type":"gltf","file":"modes.gltf"}]})", dir / "scene.json"));
    EXPECT_EQ(ok.shapes.size(), 14u);
}

}  // namespace
