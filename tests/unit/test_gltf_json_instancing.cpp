// glTF files included by a JSON scene with instancing (SceneJsonOptions::instancing, `--instancing
// auto`): scenes/gltf/instances.gltf included twice without a material override (once through a
// different spelling of its path) and once with one. The file is read once per (file, material):
// its materials appended once; its non-emissive meshes drawn twice or more (the blob by 5 nodes x 2
// includes, the tetrahedron 2 x 2, the floor 1 x 2; with the override also the lamps, which then no
// longer emit) stored once, one instance per node and include with the include's transform applied
// after the node's world matrix; emitters (panel, lamps) placed per include and lit. The instances,
// placed by their maps, are exactly the `--instancing flatten` triangles with their materials.
#include <gtest/gtest.h>

#include "file_frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <string>

#include "core/errors.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace {

using namespace vkp;

std::filesystem::path instancesFile() { return test::scenesDir() / "gltf" / "instances.gltf"; }

/// The include transforms of the scene below, as matrices (column vectors).
glm::dmat4 translate(glm::dvec3 t) {
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(t, 1.0);
    return m;
}
glm::dmat4 scale(glm::dvec3 s) {
    glm::dmat4 m(1.0);
    m[0][0] = s.x;
    m[1][1] = s.y;
    m[2][2] = s.z;
    return m;
}
const glm::dmat4 kT0 = translate({10, 0, 0});
const glm::dmat4 kT1 = translate({-10, 0, 0}) * scale({1, 2, 1});
const glm::dmat4 kT2 = translate({0, 0, 10}) * scale({-1, 1, 1});

/// A JSON scene: a box, instances.gltf at T0, a quad, instances.gltf at T1 (its path spelled through
/// "gltf/../gltf/"), instances.gltf mirrored at T2 with every material "grey".
std::string sceneText() {
    const std::string f = instancesFile().string();
    const std::string g = (test::scenesDir() / "gltf" / ".." / "gltf" / "instances.gltf").string();
    return R"({"camera":{"lookfrom":[0,3,20],"lookat":[0,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8},)"
           R"("materials":{"grey":{"type":"lambertian","albedo":[0.5,0.5,0.5]},"red":{"type":"lambertian","albedo":[0.6,0.1,0.1]}},)"
           R"("objects":[{"type":"box","min":[-1,-1,-1],"max":[1,1,1],"material":"red"},)"
           R"({"type":"gltf","file":")" + f + R"(","transform":[{"translate":[10,0,0]}]},)"
           R"({"type":"quad","Q":[0,0,0],"u":[1,0,0],"v":[0,1,0],"material":"grey"},)"
           R"({"type":"gltf","file":")" + g + R"(","transform":[{"scale":[1,2,1]},{"translate":[-10,0,0]}]},)"
           R"({"type":"gltf","file":")" + f + R"(","material":"grey","transform":[{"scale":[-1,1,1]},{"translate":[0,0,10]}]}]})";
}

Scene load(bool instancing) {
    SceneJsonOptions o;
    o.instancing = instancing;
    o.allowPaths = {test::scenesDir()};  // the scenes are written in the scratch folder, the files are in scenes/
    // Camera-relative, as loaded: the flattened and the instanced triangles are placed by the same double matrices.
    return parseSceneJson(sceneText(), test::scratchDir("gltf_json_instancing") / "scene.json", o);
}

/// A triangle's corners rounded to 1e-4, rotated to start at the smallest corner (winding kept),
/// and its material.
using Key = std::pair<std::array<std::array<long, 3>, 3>, std::uint32_t>;
Key key(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, std::uint32_t material) {
    std::array<std::array<long, 3>, 3> k;
    const glm::vec3 p[3] = {a, b, c};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) k[i][j] = std::lround(double(p[i][j]) * 1e4);
    while (!(k[0] <= k[1] && k[0] <= k[2])) std::rotate(k.begin(), k.begin() + 1, k.end());
    return {k, material};
}

bool near(const glm::dmat4& a, const glm::dmat4& b) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (std::abs(a[c][r] - b[c][r]) > 1e-12 * (1.0 + std::abs(b[c][r]))) return false;
    return true;
}

TEST(GltfJsonInstancing, EachFileIsStoredOnceAndEveryIncludePlacesInstances) {
    const Scene s = vkp::test::inFileFrame(load(true));  // compared with matrices in the file's coordinates
    const Scene direct = vkp::test::inFileFrame(loadSceneGltf(instancesFile()));  // flattened: the file's own materials and lights
    // Materials: grey, red, then the file's once (the second include without override reuses them;
    // the override adds none).
    EXPECT_EQ(s.materials.size(), 2u + direct.materials.size());
    EXPECT_EQ(s.textures.size(), direct.textures.size());
    // Stored meshes: blob, tetrahedron, floor (for the two plain includes) and blob, tetrahedron,
    // lamp (grey: no longer emitting, used by two nodes); the grey floor and panel are used once.
    ASSERT_EQ(s.meshes.size(), 6u);
    std::map<std::string, int> names;
    for (const InstancedMesh& m : s.meshes) ++names[m.name];
    EXPECT_EQ(names, (std::map<std::string, int>{{"mesh 0 (\"blob\")", 2}, {"mesh 1 (\"tetrahedron\")", 2},
                                                  {"mesh 2 (\"floor\")", 1}, {"mesh 4 (\"lamp\")", 1}}));
    EXPECT_EQ(s.instances.size(), std::size_t((5 + 2 + 1) * 2 + (5 + 2 + 2)));
    const std::uint32_t grey = 0;
    for (const InstancedMesh& m : s.meshes) {
        const bool greyMesh = m.shapes.at(0).material == grey;
        for (const Shape& t : m.shapes) {
            EXPECT_EQ(t.material == grey, greyMesh);
            EXPECT_FALSE(t.sampled);
            EXPECT_FALSE(s.materials.at(t.material).emits());
        }
    }
    // Every node's world matrix under each include's transform is one instance of its mesh (with the
    // override's material for T2 and the file's for T0, T1).
    const Scene directInst = [] {
        GltfOptions o;
        o.instancing = true;
        return vkp::test::inFileFrame(loadSceneGltf(instancesFile(), o));
    }();
    ASSERT_EQ(directInst.instances.size(), 7u);
    for (const MeshInstance& d : directInst.instances) {
        const std::string& name = directInst.meshes[d.mesh].name;
        const glm::dmat4 transforms[3] = {kT0, kT1, kT2};
        for (int include = 0; include < 3; ++include) {
            const glm::dmat4& t = transforms[include];
            int found = 0;
            for (const MeshInstance& i : s.instances) {
                const InstancedMesh& m = s.meshes[i.mesh];
                const bool greyMesh = m.shapes.at(0).material == grey;
                found += m.name == name && greyMesh == (include == 2) && near(i.objectToWorld, t * d.objectToWorld);
            }
            EXPECT_EQ(found, 1) << name << ", include " << include;
        }
    }
    // Lights: the panel (2 triangles) and the two lamps (2 each) of the two includes with the file's
    // materials; the grey include has no emitter. Every light emits.
    EXPECT_EQ(s.lights.size(), 12u);
    for (std::uint32_t l : s.lights) EXPECT_TRUE(s.materials.at(s.shapes.at(l).material).emits());
    // World shapes: 6 box quads + 1 quad, the two panels and four lamps of the plain includes, the
    // grey floor, panel (2 triangles each).
    EXPECT_EQ(s.shapes.size(), 7u + 2 * (2 + 4) + 4);
}

TEST(GltfJsonInstancing, PlacedInstancesAreTheFlattenedTriangles) {
    const Scene inst = load(true);
    const Scene flat = load(false);
    EXPECT_TRUE(flat.meshes.empty());
    EXPECT_TRUE(flat.instances.empty());
    EXPECT_EQ(flat.materials.size(), inst.materials.size());  // once per file with flatten too
    EXPECT_EQ(flat.lights.size(), inst.lights.size());
    std::map<Key, int> flatTriangles;
    std::size_t flatQuads = 0;
    for (const Shape& t : flat.shapes) {
        if (t.type == ShapeType::Triangle) ++flatTriangles[key(t.p0, t.p1, t.p2, t.material)];
        else ++flatQuads;
    }
    std::size_t placed = 0, quads = 0;
    for (const Shape& t : inst.shapes) {
        if (t.type != ShapeType::Triangle) {
            ++quads;
            continue;
        }
        --flatTriangles[key(t.p0, t.p1, t.p2, t.material)];
        ++placed;
    }
    for (const MeshInstance& i : inst.instances) {
        const bool mirror = glm::determinant(glm::dmat3(i.objectToWorld)) < 0.0;
        for (const Shape& t : inst.meshes[i.mesh].shapes) {
            auto w = [&](const glm::vec3& p) { return glm::vec3(i.objectToWorld * glm::dvec4(glm::dvec3(p), 1.0)); };
            // Under a mirror the flattening loader swaps two corners to keep the front face.
            --flatTriangles[mirror ? key(w(t.p0), w(t.p2), w(t.p1), t.material) : key(w(t.p0), w(t.p1), w(t.p2), t.material)];
            ++placed;
        }
    }
    EXPECT_EQ(quads, 7u);
    EXPECT_EQ(flatQuads, 7u);
    EXPECT_EQ(placed + quads, flat.shapes.size());
    int unmatched = 0;
    for (const auto& [k, n] : flatTriangles) unmatched += std::abs(n);
    EXPECT_EQ(unmatched, 0);  // every flattened triangle, with winding and material, is one placed triangle
    // Stored once: the instanced scene keeps fewer triangles and vertex records than the flattened one.
    EXPECT_LT(inst.triangleVertices.size() * 2, flat.triangleVertices.size());
    EXPECT_LT(inst.vertices.size() * 2, flat.vertices.size());
}

TEST(GltfJsonInstancing, OneIncludePerFileInstancesOnlyMeshesOfSeveralNodes) {
    // include.json: hierarchy.gltf and modes.gltf once each: the same triangles drawn either way.
    SceneJsonOptions o;
    o.instancing = true;
    const Scene s = vkp::test::inFileFrame(loadSceneJson(test::scenesDir() / "gltf" / "include.json", o));
    const Scene f = vkp::test::inFileFrame(loadSceneJson(test::scenesDir() / "gltf" / "include.json"));
    EXPECT_TRUE(f.instances.empty());
    std::size_t drawn = s.shapes.size();
    for (const MeshInstance& i : s.instances) drawn += s.meshes[i.mesh].shapes.size();
    EXPECT_EQ(drawn, f.shapes.size());
    EXPECT_EQ(s.materials.size(), f.materials.size());
    // instances.gltf included once: as loaded directly (2 meshes, 7 instances, 8 world triangles).
    const std::string text =
        R"({"camera":{"lookfrom":[0,3,20],"lookat":[0,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8},)"
        R"("materials":{"m":{"type":"lambertian","albedo":[0.5,0.5,0.5]}},)"
        R"("objects":[{"type":"gltf","file":")" + instancesFile().string() + R"("}]})";
    o.allowPaths = {test::scenesDir()};  // once.json is in the scratch folder, instances.gltf in scenes/
    const Scene once = vkp::test::inFileFrame(parseSceneJson(text, test::scratchDir("gltf_json_instancing") / "once.json", o));
    EXPECT_EQ(once.meshes.size(), 2u);
    EXPECT_EQ(once.instances.size(), 7u);
    EXPECT_EQ(once.shapes.size(), 8u);
}

/// The error line of parseSceneJson on objects (the camera and a material "m" around them).
std::string errorOf(const std::string& objects, bool instancing) {
    const std::string text =
        R"({"camera":{"lookfrom":[0,3,20],"lookat":[0,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8},)"
        R"("materials":{"m":{"type":"lambertian","albedo":[0.5,0.5,0.5]}},"objects":[)" + objects + "]}";
    SceneJsonOptions o;
    o.instancing = instancing;
    o.allowPaths = {test::scenesDir()};  // the scenes are written in the scratch folder, the files are in scenes/
    try {
        parseSceneJson(text, test::scratchDir("gltf_json_instancing") / "errors.json", o);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(GltfJsonInstancing, BadIncludesAreOneLineNamingTheObjectAndTheFile) {
    const auto dir = test::scratchDir("gltf_json_instancing");
    const std::string good = R"({"type":"gltf","file":")" + instancesFile().string() + R"("})";
    std::ofstream(dir / "broken.gltf") << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":3}],"meshes":[]})";
    struct Case {
        std::string objects;
        std::vector<std::string> fragments;
    };
    const Case cases[] = {
        // The second include names a file that does not exist.
        {good + R"(,{"type":"gltf","file":"missing.gltf"})", {"errors.json: /objects/1/file: cannot read", "missing.gltf: no such file"}},
        // A broken file included twice: its first include reads it.
        {good + R"(,{"type":"gltf","file":"broken.gltf"},{"type":"gltf","file":"broken.gltf"})",
         {"errors.json: /objects/1: ", "broken.gltf: node 0/mesh: mesh 3 does not exist"}},
        // The second include of a good file places it beyond float range (the first did not).
        {good + "," + R"({"type":"gltf","file":")" + instancesFile().string() + R"(","transform":[{"scale":1e38}]})",
         {"errors.json: /objects/1: ", "instances.gltf: "}},
    };
    for (bool instancing : {true, false})
        for (const Case& c : cases) {
            const std::string m = errorOf(c.objects, instancing);
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
            for (const std::string& f : c.fragments) EXPECT_NE(m.find(f), std::string::npos) << "instancing " << instancing << ": " << m;
        }
    EXPECT_NE(errorOf(good + "," + R"({"type":"gltf","file":")" + instancesFile().string() + R"(","transform":[{"scale":1e38}]})", true)
                  .find("outside the range of 32-bit floats"),
              std::string::npos);
}

}  // namespace
