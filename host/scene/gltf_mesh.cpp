// glTF mesh primitives -> world-space triangles (Shape), their vertex attributes and the light
// list (glTF 2.0 sec. 3.7.2 "Meshes"). Strips and fans are converted to triangle lists.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene/gltf_parts.h"
#include "scene/scene_json_parts.h"

namespace vkp::gltf {

namespace {

const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
    default: return "unknown";
    }
}

const tinygltf::Primitive& primitiveAt(const Document& doc, std::size_t mesh, std::size_t primitive) {
    return doc.model.meshes.at(mesh).primitives.at(primitive);
}

/// Accessor index of an attribute, or -1.
int attribute(const tinygltf::Primitive& p, const char* name) {
    const auto it = p.attributes.find(name);
    return it == p.attributes.end() ? -1 : it->second;
}

bool finite(const float* v, int n) {
    for (int i = 0; i < n; ++i) {
        if (!std::isfinite(v[i])) return false;
    }
    return true;
}

/// An optional vertex attribute: read, checked finite, one element per vertex.
std::vector<float> readAttribute(const Document& doc, const tinygltf::Primitive& p, const char* name,
                                 const std::string& where, int components, std::initializer_list<int> types,
                                 std::size_t vertices) {
    const int index = attribute(p, name);
    if (index < 0) return {};
    const Accessor a(doc, index, std::string(name) + " of " + where, components, types);
    if (a.count() != vertices) {
        a.fail("has " + std::to_string(a.count()) + " elements but POSITION has " + std::to_string(vertices));
    }
    std::vector<float> v = a.floats();
    for (std::size_t i = 0; i < vertices; ++i) {
        if (!finite(&v[i * std::size_t(components)], components)) a.fail("element " + std::to_string(i) + " is not finite");
    }
    return v;
}

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;

/// The corners of a primitive's triangles, in the file's winding, read from its indices (or
/// 0, 1, 2, ... when it has none) on the fly: no second copy of a large index buffer.
struct Corners {
    int mode = TINYGLTF_MODE_TRIANGLES;
    const std::vector<std::uint32_t>* indices = nullptr;  ///< empty: not indexed
    std::uint32_t vertex(std::size_t i) const { return indices->empty() ? std::uint32_t(i) : (*indices)[i]; }
    glm::uvec3 operator()(std::size_t t) const {
        if (mode == TINYGLTF_MODE_TRIANGLES) return {vertex(3 * t), vertex(3 * t + 1), vertex(3 * t + 2)};
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // p_i, p_{i+1+(i%2)}, p_{i+2-(i%2)} (glTF 2.0 sec. 3.7.2.1)
            return {vertex(t), vertex(t + 1 + t % 2), vertex(t + 2 - t % 2)};
        }
        return {vertex(t + 1), vertex(t + 2), vertex(0)};  // fan: p_{i+1}, p_{i+2}, p_0
    }
};

/// Per-vertex tangents from UV derivatives (Lengyel, "Computing Tangent Space Basis Vectors for
/// an Arbitrary Mesh", 2001), orthogonalised against the normal (Gram-Schmidt); w = the
/// handedness of the UV frame. Used when a normal-mapped primitive has no TANGENT (glTF 2.0 sec.
/// 3.7.2.1: "client implementations SHOULD calculate tangents"). normal may hold zeros (no NORMAL):
/// then the area-weighted face normals are used.
std::vector<glm::vec4> generateTangents(const glm::vec3* pos, const glm::vec3* normal, const glm::vec2* uv, std::size_t n,
                                        const Corners& corners, std::size_t triangles) {
    std::vector<glm::dvec3> sdir(n, glm::dvec3(0.0)), tdir(n, glm::dvec3(0.0)), face(n, glm::dvec3(0.0));
    for (std::size_t k = 0; k < triangles; ++k) {
        const glm::uvec3 t = corners(k);
        const glm::dvec3 e1 = glm::dvec3(pos[t.y]) - glm::dvec3(pos[t.x]), e2 = glm::dvec3(pos[t.z]) - glm::dvec3(pos[t.x]);
        const glm::dvec2 d1 = glm::dvec2(uv[t.y]) - glm::dvec2(uv[t.x]), d2 = glm::dvec2(uv[t.z]) - glm::dvec2(uv[t.x]);
        const glm::dvec3 ng = glm::cross(e1, e2);
        const double r = d1.x * d2.y - d2.x * d1.y;
        for (int c = 0; c < 3; ++c) face[t[c]] += ng;
        if (!(std::abs(r) > 1e-20)) continue;  // no UV frame on this triangle
        const glm::dvec3 s = (e1 * d2.y - e2 * d1.y) / r, u = (e2 * d1.x - e1 * d2.x) / r;
        for (int c = 0; c < 3; ++c) {
            sdir[t[c]] += s;
            tdir[t[c]] += u;
        }
    }
    std::vector<glm::vec4> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 nn = glm::dvec3(normal[i]);
        if (glm::dot(nn, nn) == 0.0) nn = glm::dot(face[i], face[i]) > 0.0 ? glm::normalize(face[i]) : glm::dvec3(0, 0, 1);
        glm::dvec3 t = sdir[i] - nn * glm::dot(nn, sdir[i]);
        if (!(glm::dot(t, t) > 1e-30)) {  // any direction perpendicular to the normal
            t = std::abs(nn.x) < 0.9 ? glm::cross(nn, glm::dvec3(1, 0, 0)) : glm::cross(nn, glm::dvec3(0, 1, 0));
        }
        t = glm::normalize(t);
        const double w = glm::dot(glm::cross(nn, t), tdir[i]) < 0.0 ? -1.0 : 1.0;
        out[i] = glm::vec4(glm::vec3(t), float(w));
    }
    return out;
}

}  // namespace

std::string primitivePlace(const Document& doc, std::size_t mesh, std::size_t primitive) {
    const std::string& name = doc.model.meshes.at(mesh).name;
    return "mesh " + std::to_string(mesh) + (name.empty() ? "" : " (\"" + name + "\")") + " primitive " +
           std::to_string(primitive);
}

const char* primitiveModeName(int mode) { return modeName(mode); }

bool pointsOrLines(int mode) {
    return mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
           mode == TINYGLTF_MODE_LINE_STRIP;
}

PrimitiveSize primitiveSize(const Document& doc, std::size_t mesh, std::size_t primitive) {
    const tinygltf::Primitive& p = primitiveAt(doc, mesh, primitive);
    const std::string where = primitivePlace(doc, mesh, primitive);
    if (pointsOrLines(p.mode)) {
        PrimitiveSize none;
        none.drawn = false;
        return none;
    }
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP && p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        fail(doc.file, where, "mode " + std::to_string(p.mode) + " (" + modeName(p.mode) +
                                  ") is not a glTF primitive mode (0 POINTS ... 6 TRIANGLE_FAN)");
    }
    const int position = attribute(p, "POSITION");
    if (position < 0) fail(doc.file, where, "has no POSITION attribute");
    const auto& accessors = doc.model.accessors;
    auto countOf = [&](int a, const char* use) -> std::uint64_t {
        if (a < 0 || std::size_t(a) >= accessors.size()) {
            fail(doc.file, where, std::string(use) + " accessor " + std::to_string(a) + " does not exist (the file has " +
                                      std::to_string(accessors.size()) + " accessors)");
        }
        return accessors[std::size_t(a)].count;
    };
    PrimitiveSize s;
    s.vertices = countOf(position, "POSITION");
    const std::uint64_t n = p.indices >= 0 ? countOf(p.indices, "indices") : s.vertices;
    if (p.mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0) {
            fail(doc.file, where, std::to_string(n) + (p.indices >= 0 ? " indices" : " vertices") +
                                      " do not make whole triangles (not a multiple of 3)");
        }
        s.triangles = n / 3;
    } else {
        s.triangles = n >= 3 ? n - 2 : 0;
    }
    return s;
}

void appendPrimitive(const Document& doc, std::size_t mesh, std::size_t primitive, const glm::dmat4& world,
                     std::uint32_t material, Scene& scene) {
    const tinygltf::Primitive& p = primitiveAt(doc, mesh, primitive);
    const std::string where = primitivePlace(doc, mesh, primitive);
    const PrimitiveSize size = primitiveSize(doc, mesh, primitive);
    if (!size.drawn) return;  // points and lines: appendInstances warned
    const glm::dmat3 linear(world);
    const double det = glm::determinant(linear);
    // A node scaled to zero (a hidden object) has nothing to render; its data is still checked.
    const bool hidden = !(std::abs(det) > 0.0) || !std::isfinite(det);
    const bool mirror = det < 0.0;

    // Positions, placed in the world (the file's values are released as soon as they are placed).
    const Accessor positions(doc, attribute(p, "POSITION"), "POSITION of " + where, 3, {kFloat, kByte, kUByte, kShort, kUShort});
    const std::size_t nv = positions.count();
    std::vector<glm::vec3> pos(nv);
    {
        const std::vector<float> local = positions.floats();
        for (std::size_t i = 0; i < nv; ++i) {
            if (!finite(&local[3 * i], 3)) {
                positions.fail("element " + std::to_string(i) + " is not finite (" + std::to_string(local[3 * i]) + ", " +
                               std::to_string(local[3 * i + 1]) + ", " + std::to_string(local[3 * i + 2]) + ")");
            }
            pos[i] = glm::vec3(world * glm::dvec4(local[3 * i], local[3 * i + 1], local[3 * i + 2], 1.0));
            if (!hidden && !finite(&pos[i].x, 3)) {
                positions.fail("element " + std::to_string(i) +
                               " is outside the range of 32-bit floats once placed by its node, relative to the camera");
            }
            const double reach = std::max({std::abs(double(pos[i].x)), std::abs(double(pos[i].y)), std::abs(double(pos[i].z))});
            if (!hidden && !(reach <= kMaxSceneCoordinate)) {
                char text[32];
                std::snprintf(text, sizeof text, "%.3g", reach);
                positions.fail("element " + std::to_string(i) + " reaches " + text +
                               " from the camera once placed by its node: its coordinates overflow 32-bit floats " +
                               "(every vertex must lie within +-1e38 of the camera, float's largest value being 3.4e38)");
            }
        }
    }
    std::vector<std::uint32_t> indices;
    if (p.indices >= 0) {
        const Accessor a(doc, p.indices, "indices of " + where, 1, {kUByte, kUShort, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
        indices = a.uints();
        for (std::size_t i = 0; i < indices.size(); ++i) {
            if (indices[i] >= nv) {
                a.fail("index " + std::to_string(i) + " is " + std::to_string(indices[i]) + ", but POSITION has " +
                       std::to_string(nv) + " vertices");
            }
        }
    }
    const Corners corners{p.mode, &indices};

    MeshVertices& mv = scene.vertices;
    const std::size_t base = mv.size();
    const std::size_t mark[5] = {mv.normal.size(), mv.uv.size(), mv.tangent.size(), mv.uv1.size(), mv.color.size()};
    std::uint32_t flags = 0;
    // NORMAL: by the inverse transpose, unit length (zero where degenerate, or absent: flat).
    {
        const std::vector<float> normals = readAttribute(doc, p, "NORMAL", where, 3, {kFloat, kByte, kShort}, nv);
        const glm::dmat3 normalMatrix = hidden ? glm::dmat3(1.0) : glm::transpose(glm::inverse(linear));
        if (!normals.empty()) flags |= TriangleVertices::kHasNormal;
        mv.normal.resize(base + nv, glm::vec3(0.0f));
        for (std::size_t i = 0; i < nv && !normals.empty(); ++i) {
            const glm::dvec3 n = normalMatrix * glm::dvec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
            const double len = glm::length(n);
            if (len > 0.0 && std::isfinite(len)) mv.normal[base + i] = glm::vec3(n / len);
        }
    }
    // TEXCOORD_0 and TEXCOORD_1: float, or normalized unsigned byte / short (glTF 2.0 sec. 3.7.2.1;
    // byte and short: KHR_mesh_quantization). Returns the set's values (empty: absent).
    auto readUvSet = [&](const char* name, std::uint32_t flag, std::vector<glm::vec2>& dest) {
        std::vector<float> uvs = readAttribute(doc, p, name, where, 2, {kFloat, kByte, kUByte, kShort, kUShort}, nv);
        if (!uvs.empty()) {
            flags |= flag;
            dest.resize(base, glm::vec2(0.0f));
            for (std::size_t i = 0; i < nv; ++i) dest.emplace_back(uvs[2 * i], uvs[2 * i + 1]);
        } else if (!dest.empty()) {
            dest.resize(base + nv, glm::vec2(0.0f));
        }
        return uvs;
    };
    readUvSet("TEXCOORD_0", TriangleVertices::kHasUv, mv.uv);
    {
        const std::vector<float> uvs = readUvSet("TEXCOORD_1", TriangleVertices::kHasUv1, mv.uv1);
        // glTF 2.0 textureInfo.texCoord: "A mesh primitive MUST have the corresponding texture coordinate
        // attributes for the material to be applicable to it."
        if (uvs.empty()) {
            const Material& m = scene.materials.at(material);
            if (const char* slot = texCoord1Slot(m)) {
                fail(doc.file, where, "has no TEXCOORD_1, but its material \"" + m.name + "\" reads it (" + slot +
                                          ".texCoord 1)");
            }
        }
    }
    // COLOR_0: float, or normalized unsigned byte / short, VEC3 or VEC4 (glTF 2.0 sec. 3.7.2.1); it
    // multiplies the base colour (and its alpha). Floats are clamped to [0, 65504] (half-float range).
    if (const int index = attribute(p, "COLOR_0"); index >= 0) {
        const int type = std::size_t(index) < doc.model.accessors.size() ? doc.model.accessors[std::size_t(index)].type : 0;
        if (std::size_t(index) < doc.model.accessors.size() && type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
            fail(doc.file, "accessor " + std::to_string(index) + " (COLOR_0 of " + where + ")", "is not VEC3 or VEC4");
        const int components = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
        const std::vector<float> colors = readAttribute(doc, p, "COLOR_0", where, components, {kFloat, kUByte, kUShort}, nv);
        const auto& a = doc.model.accessors[std::size_t(index)];
        if (a.componentType != kFloat && !a.normalized) {
            fail(doc.file, "accessor " + std::to_string(index) + " (COLOR_0 of " + where + ")",
                 "integer colours must be normalized (glTF 2.0 sec. 3.7.2.1)");
        }
        flags |= TriangleVertices::kHasColor;
        if (const Material& m = scene.materials.at(material); kernelMaterial(m).type != MaterialType::Pbr) {
            // Vertex colours tint the glTF BRDF only (docs/gltf.md): say so once per primitive and material.
            warnOnce(scene, line(doc.file, where, "COLOR_0 ignored: its material \"" + m.name + "\" renders as " +
                                                      (m.emits() ? "an emitter" : "glass or a book material")));
        }
        mv.color.resize(base, glm::vec4(1.0f));
        for (std::size_t i = 0; i < nv; ++i) {
            const float* c = &colors[std::size_t(components) * i];
            constexpr float kHalfMax = 65504.0f;  // the device keeps colours as half floats
            mv.color.emplace_back(std::clamp(c[0], 0.0f, kHalfMax), std::clamp(c[1], 0.0f, kHalfMax), std::clamp(c[2], 0.0f, kHalfMax),
                                  components == 4 ? std::clamp(c[3], 0.0f, 1.0f) : 1.0f);
        }
    } else if (!mv.color.empty()) {
        mv.color.resize(base + nv, glm::vec4(1.0f));
    }
    // A normal map on the base or on the clear coat needs tangents (generated below without TANGENT).
    const Material& mat = scene.materials.at(material);
    const bool normalMapped = mat.type == MaterialType::Pbr &&
                              (mat.pbr.normalTexture.valid() || ((mat.pbr.layers() & gpu::LAYER_COAT) && mat.pbr.clearcoatNormalTexture.valid()));
    {
        const std::vector<float> tangents = readAttribute(doc, p, "TANGENT", where, 4, {kFloat, kByte, kShort}, nv);
        if (!tangents.empty()) {
            flags |= TriangleVertices::kHasTangent;
            mv.tangent.resize(base, glm::vec4(0.0f));
            for (std::size_t i = 0; i < nv; ++i) {
                glm::dvec3 t = linear * glm::dvec3(tangents[4 * i], tangents[4 * i + 1], tangents[4 * i + 2]);
                const double len = glm::length(t);
                t = len > 0.0 && std::isfinite(len) ? t / len : glm::dvec3(0.0);
                const float w = (tangents[4 * i + 3] < 0.0f ? -1.0f : 1.0f) * (mirror ? -1.0f : 1.0f);
                mv.tangent.emplace_back(glm::vec3(t), w);
            }
        } else if (normalMapped && (flags & TriangleVertices::kHasUv) && !hidden) {
            flags |= TriangleVertices::kHasTangent;
            mv.tangent.resize(base, glm::vec4(0.0f));
            const std::vector<glm::vec4> gen =
                generateTangents(pos.data(), mv.normal.data() + base, mv.uv.data() + base, nv, corners, size.triangles);
            mv.tangent.insert(mv.tangent.end(), gen.begin(), gen.end());
        } else if (!mv.tangent.empty()) {
            mv.tangent.resize(base + nv, glm::vec4(0.0f));
        }
    }
    if (hidden) {  // checked, but nothing to draw: take its vertices back
        mv.normal.resize(mark[0]);
        mv.uv.resize(mark[1]);
        mv.tangent.resize(mark[2]);
        mv.uv1.resize(mark[3]);
        mv.color.resize(mark[4]);
        return;
    }

    const bool emits = scene.materials[material].emits();
    for (std::size_t k = 0; k < size.triangles; ++k) {
        const glm::uvec3 t = corners(k);
        // Front faces are counter-clockwise in the node's frame; under a mirror they appear
        // clockwise in the world (glTF 2.0 sec. 3.7.4), so swap two corners to keep the front.
        const glm::uvec3 c = mirror ? glm::uvec3(t.x, t.z, t.y) : t;
        Shape s;
        s.type = ShapeType::Triangle;
        s.p0 = pos[c.x];
        s.p1 = pos[c.y];
        s.p2 = pos[c.z];
        s.material = material;
        // A zero-area triangle is never hit and has no area to sample: it is not a light.
        s.sampled = emits && !scenejson::parallelOrZero(s.p1 - s.p0, s.p2 - s.p0);
        s.attributes = std::uint32_t(scene.triangleVertices.size());
        TriangleVertices tv;
        tv.v[0] = std::uint32_t(base + c.x);
        tv.v[1] = std::uint32_t(base + c.y);
        tv.v[2] = std::uint32_t(base + c.z);
        tv.flags = flags;
        scene.triangleVertices.push_back(tv);
        if (s.sampled) scene.lights.push_back(std::uint32_t(scene.shapes.size()));
        scene.shapes.push_back(s);
    }
}

}  // namespace vkp::gltf
