// The glTF loader's instancing (GltfOptions::instancing, `--instancing auto`) on
// scenes/gltf/instances.gltf (tools/gen_gltf_scenes.py): a mesh used by five nodes (one of them a
// mirror, one a mirror under a rotated parent, one a non-uniform scale) and one used by two nodes
// are stored once each; an emissive mesh used by two nodes stays flattened (lights are sampled in
// world space); single-use meshes are flattened. The instances, placed by their maps, are exactly
// the triangles `--instancing flatten` produces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace {

using namespace vkp;

std::filesystem::path instancesFile() { return test::scenesDir() / "gltf" / "instances.gltf"; }

Scene load(bool instancing) {
    GltfOptions o;
    o.instancing = instancing;
    return loadSceneGltf(instancesFile(), o);
}

/// A triangle's corners rounded to 1e-4, rotated to start at the smallest corner (winding kept).
using Key = std::array<std::array<long, 3>, 3>;
Key key(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    std::array<std::array<long, 3>, 3> k;
    const glm::vec3 p[3] = {a, b, c};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) k[i][j] = std::lround(double(p[i][j]) * 1e4);
    while (!(k[0] <= k[1] && k[0] <= k[2])) std::rotate(k.begin(), k.begin() + 1, k.end());
    return k;
}

TEST(GltfInstancing, SharedMeshesAreStoredOnceWithOneInstancePerNode) {
    const Scene s = load(true);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.instances.size(), 7u);  // blob x 5, tetrahedron x 2
    std::map<std::uint32_t, int> uses;
    int mirrored = 0;
    for (const MeshInstance& i : s.instances) {
        ++uses[i.mesh];
        mirrored += glm::determinant(glm::dmat3(i.objectToWorld)) < 0.0;
    }
    EXPECT_EQ(mirrored, 3);
    std::vector<int> counts;
    for (auto [m, n] : uses) counts.push_back(n);
    std::sort(counts.begin(), counts.end());
    EXPECT_EQ(counts, (std::vector<int>{2, 5}));
    // Flattened: the floor, the light panel and the two lamps (2 triangles each); the lamps emit,
    // so they are lights, and no instanced mesh triangle is one.
    EXPECT_EQ(s.shapes.size(), 8u);
    EXPECT_EQ(s.lights.size(), 6u);
    for (const InstancedMesh& m : s.meshes)
        for (const Shape& t : m.shapes) {
            EXPECT_FALSE(t.sampled);
            EXPECT_FALSE(s.materials[t.material].emits());
        }
}

TEST(GltfInstancing, PlacedInstancesAreTheFlattenedTriangles) {
    const Scene inst = load(true);
    const Scene flat = load(false);
    EXPECT_TRUE(flat.meshes.empty());
    EXPECT_TRUE(flat.instances.empty());
    std::map<Key, int> flatTriangles;
    for (const Shape& t : flat.shapes) ++flatTriangles[key(t.p0, t.p1, t.p2)];
    std::size_t placed = inst.shapes.size();
    for (const Shape& t : inst.shapes) --flatTriangles[key(t.p0, t.p1, t.p2)];
    for (const MeshInstance& i : inst.instances) {
        const bool mirror = glm::determinant(glm::dmat3(i.objectToWorld)) < 0.0;
        for (const Shape& t : inst.meshes[i.mesh].shapes) {
            auto w = [&](const glm::vec3& p) { return glm::vec3(i.objectToWorld * glm::dvec4(glm::dvec3(p), 1.0)); };
            // Under a mirror the flattening loader swaps two corners to keep the front face.
            const Key k = mirror ? key(w(t.p0), w(t.p2), w(t.p1)) : key(w(t.p0), w(t.p1), w(t.p2));
            --flatTriangles[k];
            ++placed;
        }
    }
    EXPECT_EQ(placed, flat.shapes.size());
    int unmatched = 0;
    for (const auto& [k, n] : flatTriangles) unmatched += std::abs(n);
    EXPECT_EQ(unmatched, 0);  // every flattened triangle, with its winding, is one placed triangle
    // Object-space normals: unit length where the file has them (the kernel maps them at a hit).
    const Scene& s = inst;
    for (const InstancedMesh& m : s.meshes)
        for (const Shape& t : m.shapes) {
            const TriangleVertices& tv = s.triangleVertices.at(t.attributes);
            if (!(tv.flags & TriangleVertices::kHasNormal)) continue;
            for (std::uint32_t v : tv.v) EXPECT_NEAR(glm::length(s.vertices.normal.at(v)), 1.0f, 1e-5f);
        }
}

TEST(GltfInstancing, OffByDefaultInTheLibrary) {
    EXPECT_TRUE(loadSceneGltf(instancesFile()).instances.empty());
}

TEST(GltfInstancing, AnInstancePlacedBeyondFloatRangeIsOneErrorLine) {
    // instances.gltf with the stretched blob's node scaled by 1e39: its placed box leaves float range.
    std::ifstream in(instancesFile());
    nlohmann::json doc = nlohmann::json::parse(in);
    doc["nodes"][2]["scale"] = {1e39, 1e39, 1e39};
    const std::filesystem::path file = test::scratchDir("gltf_instancing") / "huge.gltf";
    std::ofstream(file) << doc.dump();
    for (bool instancing : {true, false}) {
        GltfOptions o;
        o.instancing = instancing;
        try {
            loadSceneGltf(file, o);
            ADD_FAILURE() << "no error with instancing " << instancing;
        } catch (const InputError& e) {
            const std::string m = e.what();
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
            if (instancing) EXPECT_NE(m.find("node 2 (\"blob stretched\")"), std::string::npos) << m;
            EXPECT_NE(m.find("outside the range of 32-bit floats"), std::string::npos) << m;
        }
    }
}

}  // namespace
