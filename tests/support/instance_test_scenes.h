// Helpers for the two-level BVH tests: a scene with shared meshes placed by translating, rotating,
// non-uniformly scaling and mirroring instances (deterministic), and its flattened twin (every
// instance's triangles placed in the world as the glTF loader's --instancing flatten does: double
// precision, v1 and v2 swapped under a mirror).
#pragma once
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "bvh_test_scenes.h"
#include "scene/scene.h"

namespace vkp::test {

/// The maps of instancedScene's instances: identity-like, translated, rotated, non-uniform scale
/// (2, 0.5, 1.5), a mirror (x -> -x), a mirror with rotation and scale, a tiny and a flat scale, and a
/// small mirrored mesh 1e4 from the origin.
inline std::vector<glm::dmat4> testInstanceMaps() {
    using glm::dmat4;
    using glm::dvec3;
    std::vector<dmat4> m;
    m.push_back(glm::translate(dmat4(1.0), dvec3(-12, 0, 0)));
    m.push_back(glm::rotate(glm::translate(dmat4(1.0), dvec3(12, 1, -3)), 0.7, glm::normalize(dvec3(1, 2, 3))));
    m.push_back(glm::scale(glm::translate(dmat4(1.0), dvec3(0, 12, 0)), dvec3(2.0, 0.5, 1.5)));
    m.push_back(glm::scale(glm::translate(dmat4(1.0), dvec3(0, -12, 2)), dvec3(-1.0, 1.0, 1.0)));
    m.push_back(glm::scale(glm::rotate(glm::translate(dmat4(1.0), dvec3(6, -6, 9)), 2.1, dvec3(0, 1, 0)), dvec3(1.3, -0.7, 0.9)));
    m.push_back(glm::scale(glm::translate(dmat4(1.0), dvec3(-7, 8, -9)), dvec3(0.05, 0.05, 0.05)));
    m.push_back(glm::scale(glm::translate(dmat4(1.0), dvec3(0, 0, -30)), dvec3(3.0, 3.0, 0.3)));
    // Far from the origin and small: the transform's rounding (ulps of 1e4) is large against the mesh.
    m.push_back(glm::scale(glm::rotate(glm::translate(dmat4(1.0), dvec3(1.0e4, 3.0, -2.0)), 0.3, dvec3(0, 0, 1)), dvec3(0.02, -0.03, 0.02)));
    return m;
}

/// World shapes (triangles, spheres, quads) and two shared meshes (a sphere mesh of radius 4 and a
/// cloud of triangles), each used by every map of testInstanceMaps.
inline Scene instancedScene() {
    Scene s;
    s.materials.push_back(Material{});
    s.shapes = randomTriangles(300, 31, 20.0f);
    for (const Shape& sh : randomSpheres(40, 32, 20.0f)) s.shapes.push_back(sh);
    for (const Shape& sh : randomQuads(40, 33, 20.0f)) s.shapes.push_back(sh);
    InstancedMesh a;
    a.name = "sphere mesh";
    a.shapes = sphereMesh(24, 24, 4.0f);
    InstancedMesh b;
    b.name = "triangle cloud";
    b.shapes = randomTriangles(400, 34, 3.0f, 1.0f);
    s.meshes = {a, b};
    const std::vector<glm::dmat4> maps = testInstanceMaps();
    for (std::uint32_t mesh = 0; mesh < 2; ++mesh) {
        for (std::size_t k = 0; k < maps.size(); ++k) {
            glm::dmat4 m = maps[k];
            if (mesh == 1) m = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 15)) * m;
            s.instances.push_back({mesh, m});
        }
    }
    return s;
}

/// The world-space triangle of object-space triangle t under m, as the flattening loader makes it.
inline Shape placeTriangle(const Shape& t, const glm::dmat4& m) {
    auto place = [&](const glm::vec3& p) { return glm::vec3(m * glm::dvec4(glm::dvec3(p), 1.0)); };
    Shape w = t;
    w.p0 = place(t.p0);
    w.p1 = place(t.p1);
    w.p2 = place(t.p2);
    if (glm::determinant(glm::dmat3(m)) < 0.0) std::swap(w.p1, w.p2);
    return w;
}

/// The scene with every instance's triangles placed in the world after its shapes, in instance
/// order, and no meshes or instances.
inline Scene flattenedScene(const Scene& s) {
    Scene f = s;
    f.meshes.clear();
    f.instances.clear();
    for (const MeshInstance& inst : s.instances)
        for (const Shape& t : s.meshes[inst.mesh].shapes) f.shapes.push_back(placeTriangle(t, inst.objectToWorld));
    return f;
}

}  // namespace vkp::test
