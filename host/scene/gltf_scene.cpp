// The node hierarchy of a glTF scene (glTF 2.0 sec. 3.5): world matrices, mesh and camera
// instances; loadSceneGltf, and the placement shared with JSON includes (gltf_include.cpp).
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/errors.h"
#include "scene/gltf_parts.h"

namespace vkp::gltf {

namespace {

std::vector<double> checked(const std::vector<double>& v, std::size_t n, const Document& doc, const std::string& place) {
    if (v.empty()) return v;
    if (v.size() != n) fail(doc.file, place, "must have " + std::to_string(n) + " numbers (got " + std::to_string(v.size()) + ")");
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(v[i])) fail(doc.file, place + "/" + std::to_string(i), "must be finite");
    }
    return v;
}

/// A light index as the file wrote it, for messages.
std::string light_index_text(double index) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", index);
    return buf;
}

/// The node's local matrix: "matrix" (column-major) or T * R * S (sec. 3.5.3).
glm::dmat4 localMatrix(const Document& doc, std::size_t n) {
    const tinygltf::Node& node = doc.model.nodes[n];
    const std::string place = nodePlace(doc, n);
    const std::vector<double> m = checked(node.matrix, 16, doc, place + "/matrix");
    if (!m.empty()) {
        glm::dmat4 out;
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) out[c][r] = m[std::size_t(4 * c + r)];
        }
        return out;
    }
    const std::vector<double> t = checked(node.translation, 3, doc, place + "/translation");
    const std::vector<double> q = checked(node.rotation, 4, doc, place + "/rotation");
    const std::vector<double> s = checked(node.scale, 3, doc, place + "/scale");
    glm::dmat4 out(1.0);
    if (!s.empty()) {
        out[0][0] = s[0];
        out[1][1] = s[1];
        out[2][2] = s[2];
    }
    if (!q.empty()) {
        glm::dvec4 v(q[0], q[1], q[2], q[3]);  // x, y, z, w
        const double len = glm::length(v);
        if (!(len > 0.0)) fail(doc.file, place + "/rotation", "must be a unit quaternion (got length 0)");
        v /= len;
        const double x = v.x, y = v.y, z = v.z, w = v.w;
        glm::dmat3 r;  // columns of the rotation matrix of the unit quaternion (x, y, z, w)
        r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)};
        r[1] = {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)};
        r[2] = {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)};
        out = glm::dmat4(r) * out;
    }
    if (!t.empty()) out[3] = glm::dvec4(t[0], t[1], t[2], 1.0);
    return out;
}

}  // namespace

Instances traverse(const Document& doc, std::optional<std::uint32_t> sceneIndex, const glm::dmat4& root, Scene& out) {
    const tinygltf::Model& model = doc.model;
    std::vector<int> roots;
    if (model.scenes.empty()) {
        if (sceneIndex) fail(doc.file, "scenes", "the file has no scenes (--gltf-scene " + std::to_string(*sceneIndex) + ")");
        // No scene: every node that is nobody's child.
        std::vector<char> child(model.nodes.size(), 0);
        for (const auto& n : model.nodes) {
            for (int c : n.children) {
                if (c >= 0 && std::size_t(c) < child.size()) child[std::size_t(c)] = 1;
            }
        }
        for (std::size_t i = 0; i < model.nodes.size(); ++i) {
            if (!child[i]) roots.push_back(int(i));
        }
    } else {
        const std::size_t s = sceneIndex ? *sceneIndex : model.defaultScene >= 0 ? std::size_t(model.defaultScene) : 0;
        if (s >= model.scenes.size()) {
            fail(doc.file, sceneIndex ? "--gltf-scene " + std::to_string(s) : std::string("scene"),
                 "scene " + std::to_string(s) + " does not exist (the file has " + std::to_string(model.scenes.size()) +
                     (model.scenes.size() == 1 ? " scene)" : " scenes)"));
        }
        roots = model.scenes[s].nodes;
    }
    Instances found;
    std::vector<char> visited(model.nodes.size(), 0);
    std::vector<std::pair<int, glm::dmat4>> stack;
    auto push = [&](int n, const glm::dmat4& parent, const std::string& from) {
        if (n < 0 || std::size_t(n) >= model.nodes.size()) {
            fail(doc.file, from, "node " + std::to_string(n) + " does not exist (the file has " +
                                     std::to_string(model.nodes.size()) + " nodes)");
        }
        stack.emplace_back(n, parent);
    };
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) push(*it, root, "scene");
    while (!stack.empty()) {
        const auto [n, parent] = stack.back();
        stack.pop_back();
        const std::size_t i = std::size_t(n);
        const tinygltf::Node& node = model.nodes[i];
        if (visited[i]) {
            fail(doc.file, nodePlace(doc, i), "is reached twice in the scene's hierarchy (a node has at most one parent: a cycle?)");
        }
        visited[i] = 1;
        const glm::dmat4 world = parent * localMatrix(doc, i);
        if (node.mesh >= 0) {
            if (std::size_t(node.mesh) >= model.meshes.size()) {
                fail(doc.file, nodePlace(doc, i) + "/mesh", "mesh " + std::to_string(node.mesh) + " does not exist (the file has " +
                                                                std::to_string(model.meshes.size()) + " meshes)");
            }
            found.meshes.push_back({i, std::size_t(node.mesh), world});
            if (node.skin >= 0) {
                out.warnings.push_back(line(doc.file, nodePlace(doc, i), "skin ignored: the mesh is drawn in its bind pose, placed by the node"));
            }
        }
        if (const auto ext = node.extensions.find("KHR_lights_punctual"); ext != node.extensions.end()) {
            const tinygltf::Value& light = ext->second.Get("light");
            const std::string place = nodePlace(doc, i) + "/extensions/KHR_lights_punctual/light";
            if (!light.IsInt() && !light.IsNumber()) fail(doc.file, place, "must be the index of a light");
            const double index = light.IsInt() ? double(light.Get<int>()) : light.Get<double>();
            if (!(index >= 0.0) || index != std::floor(index) || index >= double(model.lights.size())) {
                fail(doc.file, place, "light " + light_index_text(index) + " does not exist (the file has " +
                                          std::to_string(model.lights.size()) + " lights)");
            }
            found.lights.push_back({i, std::size_t(index), world});
        }
        if (node.camera >= 0) {
            if (std::size_t(node.camera) >= model.cameras.size()) {
                fail(doc.file, nodePlace(doc, i) + "/camera", "camera " + std::to_string(node.camera) + " does not exist (the file has " +
                                                                  std::to_string(model.cameras.size()) + " cameras)");
            }
            found.cameras.push_back({i, std::size_t(node.camera), world});
        }
        for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) push(*it, world, nodePlace(doc, i) + "/children");
    }
    return found;
}

namespace {

/// Determinant of the linear part of a node's world matrix: 0 or not finite = hidden (scaled to
/// nothing), negative = mirrored.
double linearDeterminant(const glm::dmat4& world) { return glm::determinant(glm::dmat3(world)); }

/// Which meshes are stored once for instancing: drawn at least twice (nodes x includes), every
/// primitive's material non-emissive (lights are sampled in world space). materials: the scene
/// index of each primitive's material, per mesh; includes: how often the file is placed.
std::vector<char> sharedMeshes(const tinygltf::Model& model, const Instances& inst,
                               const std::vector<std::vector<std::uint32_t>>& materials, const Scene& scene,
                               std::uint32_t includes) {
    std::vector<std::uint32_t> uses(model.meshes.size(), 0);
    for (const MeshInstance& mi : inst.meshes) {
        const double det = linearDeterminant(mi.world);
        if (std::abs(det) > 0.0 && std::isfinite(det)) ++uses[mi.mesh];
    }
    std::vector<char> shared(model.meshes.size(), 0);
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        if (std::uint64_t(uses[m]) * includes < 2) continue;
        bool emits = false;
        for (std::uint32_t mat : materials[m]) emits = emits || scene.materials[mat].emits();
        shared[m] = !emits;
    }
    return shared;
}

/// The world box of an object-space box under an affine map (its eight corners, in double).
void growTransformedBox(const glm::dmat4& world, glm::dvec3 blo, glm::dvec3 bhi, glm::dvec3& lo, glm::dvec3& hi) {
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? bhi.x : blo.x, (c & 2) ? bhi.y : blo.y, (c & 4) ? bhi.z : blo.z);
        const glm::dvec3 w = glm::dvec3(world * glm::dvec4(p, 1.0));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
}

}  // namespace

std::pair<glm::dvec3, glm::dvec3> appendInstances(const Document& doc, const Instances& inst, PlacementState& state,
                                                  bool instancing, std::uint32_t includes, Scene& scene) {
    const tinygltf::Model& model = doc.model;
    MaterialMapper& materials = state.materials;
    const bool first = !state.decided;
    if (first) {
        // Each primitive's scene material, per mesh (mapped once, in the order the flattening loader maps them).
        state.meshMaterials.assign(model.meshes.size(), {});
        state.shared.assign(model.meshes.size(), 0);
        state.meshSlot.assign(model.meshes.size(), -1);
        if (instancing) {
            std::vector<char> mapped(model.meshes.size(), 0);
            for (const MeshInstance& mi : inst.meshes) {
                if (mapped[mi.mesh]) continue;
                mapped[mi.mesh] = 1;
                for (const auto& prim : model.meshes[mi.mesh].primitives)
                    state.meshMaterials[mi.mesh].push_back(materials.material(prim.material));
            }
            state.shared = sharedMeshes(model, inst, state.meshMaterials, scene, includes);
        }
        state.decided = true;
    }
    const std::vector<char>& shared = state.shared;
    std::vector<std::int64_t>& meshSlot = state.meshSlot;  // index into scene.meshes
    // Count first: refuse absurd totals before reading anything, and allocate once. A shared mesh
    // counts once, when it is stored (not again for a later include of the same file).
    std::uint64_t triangles = 0, vertices = 0, uvVertices = 0, worldTriangles = 0;
    std::vector<char> counted(model.meshes.size(), 0);
    for (const MeshInstance& mi : inst.meshes) {
        const auto& mesh = model.meshes[mi.mesh];
        if (shared[mi.mesh] && (counted[mi.mesh] || meshSlot[mi.mesh] >= 0)) continue;
        counted[mi.mesh] = 1;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const PrimitiveSize size = primitiveSize(doc, mi.mesh, p);
            if (!size.drawn) {
                const int mode = mesh.primitives[p].mode;
                warnOnce(scene, line(doc.file, primitivePlace(doc, mi.mesh, p),
                                     "mode " + std::to_string(mode) + " (" + primitiveModeName(mode) +
                                         "): points and lines are not rendered (vkpath renders surfaces): skipped"));
            }
            triangles += size.triangles;
            if (!shared[mi.mesh]) worldTriangles += size.triangles;
            vertices += size.vertices;
            if (mesh.primitives[p].attributes.count("TEXCOORD_0")) uvVertices += size.vertices;
            if (triangles > kGltfMaxTriangles || vertices > kGltfMaxVertices) {
                fail(doc.file, primitivePlace(doc, mi.mesh, p) + " of " + nodePlace(doc, mi.node),
                     "the scene would have more than " + std::to_string(triangles > kGltfMaxTriangles ? kGltfMaxTriangles : kGltfMaxVertices) +
                         (triangles > kGltfMaxTriangles ? " triangles" : " vertices") + " (vkpath's limit)");
            }
        }
        if (first && !mesh.weights.empty()) {
            scene.warnings.push_back(line(doc.file, "mesh " + std::to_string(mi.mesh), "morph targets ignored: the base shape is drawn"));
        }
    }
    const std::size_t firstShape = scene.shapes.size();
    scene.shapes.reserve(firstShape + worldTriangles);
    scene.triangleVertices.reserve(scene.triangleVertices.size() + triangles);
    scene.vertices.normal.reserve(scene.vertices.size() + vertices);
    if (uvVertices) scene.vertices.uv.reserve(scene.vertices.size() + vertices);

    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const MeshInstance& mi : inst.meshes) {
        const auto& mesh = model.meshes[mi.mesh];
        if (!shared[mi.mesh]) {
            for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
                const std::uint32_t m = materials.material(mesh.primitives[p].material);
                try {
                    appendPrimitive(doc, mi.mesh, p, mi.world, m, scene);
                } catch (const InputError& e) {  // a mesh drawn by several nodes: say which one
                    throw InputError(std::string(e.what()) + " (drawn by " + nodePlace(doc, mi.node) + ")");
                }
            }
            continue;
        }
        if (meshSlot[mi.mesh] < 0) {  // first use: its triangles once, in object space
            const std::size_t before = scene.shapes.size();
            for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
                appendPrimitive(doc, mi.mesh, p, glm::dmat4(1.0), state.meshMaterials[mi.mesh][p], scene);
            InstancedMesh im;
            im.name = "mesh " + std::to_string(mi.mesh) + (mesh.name.empty() ? "" : " (\"" + mesh.name + "\")");
            im.shapes.assign(scene.shapes.begin() + std::ptrdiff_t(before), scene.shapes.end());
            scene.shapes.resize(before);
            meshSlot[mi.mesh] = std::int64_t(scene.meshes.size());
            scene.meshes.push_back(std::move(im));
        }
        const double det = linearDeterminant(mi.world);
        if (!(std::abs(det) > 0.0) || !std::isfinite(det)) continue;  // hidden: nothing to draw
        const InstancedMesh& im = scene.meshes[std::size_t(meshSlot[mi.mesh])];
        glm::dvec3 blo(std::numeric_limits<double>::infinity()), bhi(-std::numeric_limits<double>::infinity());
        for (const Shape& s : im.shapes) {
            for (const glm::vec3& p : {s.p0, s.p1, s.p2}) {
                blo = glm::min(blo, glm::dvec3(p));
                bhi = glm::max(bhi, glm::dvec3(p));
            }
        }
        if (im.shapes.empty()) continue;
        glm::dvec3 wlo(std::numeric_limits<double>::infinity()), whi(-std::numeric_limits<double>::infinity());
        growTransformedBox(mi.world, blo, bhi, wlo, whi);
        const double big = double(std::numeric_limits<float>::max()) * 0.5;
        if (!(glm::all(glm::lessThan(glm::abs(wlo), glm::dvec3(big))) && glm::all(glm::lessThan(glm::abs(whi), glm::dvec3(big)))))
            fail(doc.file, nodePlace(doc, mi.node), "places " + im.name + " outside the range of 32-bit floats relative to the camera");
        lo = glm::min(lo, wlo);
        hi = glm::max(hi, whi);
        scene.instances.push_back({std::uint32_t(meshSlot[mi.mesh]), mi.world});
    }
    if (first && !model.animations.empty()) {
        scene.warnings.push_back(line(doc.file, "animations", "ignored: the scene is drawn at rest"));
    }
    for (std::size_t i = firstShape; i < scene.shapes.size(); ++i) {
        for (const glm::vec3& p : {scene.shapes[i].p0, scene.shapes[i].p1, scene.shapes[i].p2}) {
            lo = glm::min(lo, glm::dvec3(p));
            hi = glm::max(hi, glm::dvec3(p));
        }
    }
    return {lo, hi};
}

std::string nodePlace(const Document& doc, std::size_t node) {
    const std::string& name = doc.model.nodes.at(node).name;
    return "node " + std::to_string(node) + (name.empty() ? "" : " (\"" + name + "\")");
}

}  // namespace vkp::gltf

namespace vkp {

Scene loadSceneGltf(const std::filesystem::path& file, const GltfOptions& options) {
    gltf::Document doc = gltf::readDocument(file, options.allowPaths);
    Scene scene;
    scene.path = file;
    scene.warnings = std::move(doc.warnings);
    gltf::Instances inst = gltf::traverse(doc, options.scene, glm::dmat4(1.0), scene);

    const gltf::CameraInstance* chosen = nullptr;
    if (options.camera) {
        if (*options.camera >= doc.model.cameras.size()) {
            gltf::fail(doc.file, "--camera " + std::to_string(*options.camera),
                       "the file has " + std::to_string(doc.model.cameras.size()) + " cameras");
        }
        for (const auto& c : inst.cameras) {
            if (c.camera == *options.camera) {
                chosen = &c;
                break;
            }
        }
        if (!chosen) {
            gltf::fail(doc.file, "--camera " + std::to_string(*options.camera), "no node of the scene uses this camera");
        }
    } else {
        for (const auto& c : inst.cameras) {
            if (doc.model.cameras[c.camera].type == "perspective") {
                chosen = &c;
                break;
            }
        }
    }
    // Camera-relative space (docs/design.md): every node matrix, in double, is moved so that the
    // camera's node sits at the origin before a vertex becomes float. Without a camera, the frame
    // starts at the first mesh node's position (near the geometry, so the floats keep their
    // digits) and moves to the framing camera once the bounds are known.
    if (chosen) {
        scene.origin = glm::dvec3(chosen->world[3]);
    } else if (!inst.meshes.empty()) {
        scene.origin = glm::dvec3(inst.meshes.front().world[3]);
    }
    for (gltf::MeshInstance& mi : inst.meshes) mi.world[3] -= glm::dvec4(scene.origin, 0.0);
    for (gltf::LightInstance& li : inst.lights) li.world[3] -= glm::dvec4(scene.origin, 0.0);
    glm::dmat4 cameraWorld = chosen ? chosen->world : glm::dmat4(1.0);
    cameraWorld[3] -= glm::dvec4(scene.origin, 0.0);

    gltf::PlacementState state{gltf::MaterialMapper(doc, scene, std::nullopt)};
    const auto [lo, hi] = gltf::appendInstances(doc, inst, state, options.instancing, 1, scene);
    gltf::appendLights(doc, inst, scene);
    if (chosen) {
        scene.camera = gltf::cameraFromGltf(doc, chosen->camera, cameraWorld, options);
    } else {
        glm::dvec3 position;
        scene.camera = gltf::framingCamera(doc.file, lo, hi, options, position);
        moveOrigin(scene, position, "the framing camera");
    }
    return scene;
}

}  // namespace vkp
