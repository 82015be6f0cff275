// Compressed glTF meshes, decoded into plain buffers right after the file is read, so that every
// later stage (accessors, primitives) sees an ordinary glTF file:
//   EXT_meshopt_compression (Khronos glTF extension registry, vendor/EXT_meshopt_compression),
//     decoded with Debian's meshoptimizer (meshopt_decodeVertexBuffer / IndexBuffer / IndexSequence
//     and the three filters);
//   KHR_draco_mesh_compression (registry, Khronos/KHR_draco_mesh_compression), decoded with
//     Debian's libdraco. Debian's tinygltf is built without Draco, so vkpath does it here.
// Every size a stream claims is checked against the file before anything is allocated for it
// (meshopt); Draco's decoder allocates what its stream describes, and the total decoded is then
// bounded by the distinct streams' size.
#include <algorithm>
#include <cstring>
#include <optional>
#include <set>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "draco/draco_decode.h"
#include "scene/gltf_parts.h"

namespace vkp::gltf {

namespace {

using tinygltf::Value;

/// A meshopt stream decodes to at most this many times its own size (the vertex codec's best case
/// is about 64:1, the index codec's 24:1); a larger claim is a broken or hostile file.
constexpr std::uint64_t kMaxMeshoptRatio = 256;
/// Placeholder for a fallback buffer (no uri) while tinygltf reads the file: one zero byte.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";

/// A non-negative integer member (def when absent and optional).
std::uint64_t count(const Value& object, const char* key, const std::string& file, const std::string& place,
                    std::optional<std::uint64_t> def = std::nullopt) {
    const Value* v = member(object, key);
    if (!v) {
        if (def) return *def;
        fail(file, place, std::string("needs \"") + key + "\"");
    }
    if (!v->IsNumber()) fail(file, place + "/" + key, "must be a non-negative integer");
    const double x = v->GetNumberAsDouble();
    if (!(x >= 0.0 && x <= 9007199254740992.0) || x != double(std::uint64_t(x))) {
        fail(file, place + "/" + key, "must be a non-negative integer");
    }
    return std::uint64_t(x);
}

std::string text(const Value& object, const char* key, const char* def, const std::string& file, const std::string& place) {
    const Value* v = member(object, key);
    if (!v) {
        if (def) return def;
        fail(file, place, std::string("needs \"") + key + "\"");
    }
    if (!v->IsString()) fail(file, place + "/" + key, "must be a string");
    return v->Get<std::string>();
}

/// The bytes [offset, offset + length) of buffer b, checked.
const std::uint8_t* bytesOf(const tinygltf::Model& m, std::uint64_t b, std::uint64_t offset, std::uint64_t length,
                            const std::string& file, const std::string& place) {
    if (b >= m.buffers.size()) {
        fail(file, place, "buffer " + std::to_string(b) + " does not exist (the file has " + std::to_string(m.buffers.size()) + ")");
    }
    const auto& data = m.buffers[b].data;
    if (offset > data.size() || length > data.size() - offset) {
        fail(file, place, "bytes " + std::to_string(offset) + " + " + std::to_string(length) + " are outside buffer " +
                              std::to_string(b) + " (" + std::to_string(data.size()) + " bytes)");
    }
    return data.data() + offset;
}

int typeComponents(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
    }
}

// ---- EXT_meshopt_compression -------------------------------------------------------------------

/// One compressed bufferView, read and checked.
struct MeshoptView {
    std::size_t view = 0;
    std::uint64_t source = 0, offset = 0, length = 0;  ///< the compressed bytes
    std::uint64_t stride = 0, count = 0;
    std::string mode, filter;
};

MeshoptView readMeshoptView(const tinygltf::Model& m, std::size_t v, const Value& ext, const std::string& file) {
    const std::string place = "bufferView " + std::to_string(v) + "/extensions/EXT_meshopt_compression";
    if (!ext.IsObject()) fail(file, place, "must be an object");
    MeshoptView s;
    s.view = v;
    s.source = count(ext, "buffer", file, place);
    s.offset = count(ext, "byteOffset", file, place, 0);
    s.length = count(ext, "byteLength", file, place);
    s.stride = count(ext, "byteStride", file, place);
    s.count = count(ext, "count", file, place);
    s.mode = text(ext, "mode", nullptr, file, place);
    s.filter = text(ext, "filter", "NONE", file, place);
    if (s.mode == "ATTRIBUTES") {
        if (s.stride == 0 || s.stride > 256 || s.stride % 4 != 0) {
            fail(file, place + "/byteStride", std::to_string(s.stride) + ": ATTRIBUTES need a multiple of 4 in [4, 256]");
        }
    } else if (s.mode == "TRIANGLES" || s.mode == "INDICES") {
        if (s.stride != 2 && s.stride != 4) fail(file, place + "/byteStride", std::to_string(s.stride) + ": indices are 2 or 4 bytes");
        if (s.mode == "TRIANGLES" && s.count % 3 != 0) {
            fail(file, place + "/count", std::to_string(s.count) + " indices do not make whole triangles");
        }
        if (s.filter != "NONE") fail(file, place + "/filter", "\"" + s.filter + "\": only ATTRIBUTES may have a filter");
    } else {
        fail(file, place + "/mode", "\"" + s.mode + "\" is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    if (s.filter == "OCTAHEDRAL") {
        if (s.stride != 4 && s.stride != 8) fail(file, place + "/byteStride", "OCTAHEDRAL needs 4 or 8 bytes per element");
    } else if (s.filter == "QUATERNION") {
        if (s.stride != 8) fail(file, place + "/byteStride", "QUATERNION needs 8 bytes per element");
    } else if (s.filter != "NONE" && s.filter != "EXPONENTIAL") {
        fail(file, place + "/filter", "\"" + s.filter + "\" is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    }
    (void)bytesOf(m, s.source, s.offset, s.length, file, place);  // the compressed bytes exist in the file
    const tinygltf::BufferView& bv = m.bufferViews[v];
    if (s.count > (std::uint64_t(1) << 32) || s.count * s.stride > bv.byteLength) {
        fail(file, place, std::to_string(s.count) + " elements of " + std::to_string(s.stride) +
                              " bytes do not fit the bufferView's byteLength " + std::to_string(bv.byteLength));
    }
    if (s.count * s.stride > kMaxMeshoptRatio * s.length + 4096) {
        fail(file, place, std::to_string(s.count * s.stride) + " bytes cannot come from " + std::to_string(s.length) +
                              " compressed bytes: not a meshopt stream");
    }
    return s;
}

void decodeMeshoptView(tinygltf::Model& m, const MeshoptView& s, const std::string& file) {
    const std::string place = "bufferView " + std::to_string(s.view) + "/extensions/EXT_meshopt_compression";
    const std::uint8_t* src = bytesOf(m, s.source, s.offset, s.length, file, place);
    const tinygltf::BufferView& bv = m.bufferViews[s.view];
    const std::size_t n = std::size_t(s.count * s.stride);
    std::uint8_t* dst = const_cast<std::uint8_t*>(bytesOf(m, std::uint64_t(bv.buffer), bv.byteOffset, n, file,
                                                          "bufferView " + std::to_string(s.view)));
    // Decoded into scratch first (its size bounded by the destination's, checked above): the
    // source may lie in the same buffer as the destination.
    std::vector<unsigned char> out(std::max<std::size_t>(n, 1));
    int rc = 0;
    if (s.mode == "ATTRIBUTES") rc = meshopt_decodeVertexBuffer(out.data(), s.count, s.stride, src, s.length);
    else if (s.mode == "TRIANGLES") rc = meshopt_decodeIndexBuffer(out.data(), s.count, s.stride, src, s.length);
    else rc = meshopt_decodeIndexSequence(out.data(), s.count, s.stride, src, s.length);
    if (rc != 0) fail(file, place, "the " + s.mode + " stream does not decode (meshoptimizer error " + std::to_string(rc) + ")");
    if (s.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), s.count, s.stride);
    else if (s.filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), s.count, s.stride);
    else if (s.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), s.count, s.stride);
    std::memcpy(dst, out.data(), n);
}

// ---- KHR_draco_mesh_compression ----------------------------------------------------------------

std::optional<draco_island::Component> dracoComponent(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return draco_island::Component::Float;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return draco_island::Component::Int8;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return draco_island::Component::Uint8;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return draco_island::Component::Int16;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return draco_island::Component::Uint16;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return draco_island::Component::Uint32;
    default: return std::nullopt;
    }
}

/// Append bytes as a new buffer, bufferView and accessor (a copy of accessor `like`, now pointing
/// at them); returns the new accessor's index.
int appendDecoded(tinygltf::Model& m, int like, std::vector<unsigned char> bytes) {
    tinygltf::Buffer b;
    b.data = std::move(bytes);
    tinygltf::BufferView bv;
    bv.buffer = int(m.buffers.size());
    bv.byteOffset = 0;
    bv.byteLength = b.data.size();
    m.buffers.push_back(std::move(b));
    tinygltf::Accessor a = m.accessors[std::size_t(like)];
    a.bufferView = int(m.bufferViews.size());
    a.byteOffset = 0;
    m.bufferViews.push_back(bv);
    m.accessors.push_back(a);
    return int(m.accessors.size()) - 1;
}

/// What the Draco primitives of one file have decoded: the bytes of the distinct streams read and
/// the bytes their decoding produced, which may not exceed kMaxDracoRatio times the former.
struct DracoBudget {
    std::set<std::uint64_t> streams;
    std::uint64_t streamBytes = 0, decodedBytes = 0;
};
/// A Draco stream decodes to at most this many times its size (quantised attributes and
/// connectivity compress to about 1:10-1:50 in practice); more is a broken or hostile file, or one
/// primitive's stream reused by thousands of primitives.
constexpr std::uint64_t kMaxDracoRatio = 1024;

void decodeDracoPrimitive(Document& doc, std::size_t mesh, std::size_t primitive, const Value& ext, DracoBudget& budget) {
    tinygltf::Model& m = doc.model;
    const std::string where = primitivePlace(doc, mesh, primitive);
    const std::string place = where + "/extensions/KHR_draco_mesh_compression";
    tinygltf::Primitive& p = m.meshes[mesh].primitives[primitive];
    if (!ext.IsObject()) fail(doc.file, place, "must be an object");
    if (p.mode != TINYGLTF_MODE_TRIANGLES) fail(doc.file, where, "a Draco-compressed primitive must be TRIANGLES (mode 4)");
    const std::uint64_t v = count(ext, "bufferView", doc.file, place);
    if (v >= m.bufferViews.size()) fail(doc.file, place + "/bufferView", std::to_string(v) + " does not exist");
    const tinygltf::BufferView& bv = m.bufferViews[v];
    const std::uint8_t* bytes = bytesOf(m, std::uint64_t(bv.buffer < 0 ? m.buffers.size() : std::size_t(bv.buffer)),
                                        bv.byteOffset, bv.byteLength, doc.file, "bufferView " + std::to_string(v));
    const Value* attributes = member(ext, "attributes");
    if (!attributes || !attributes->IsObject()) fail(doc.file, place + "/attributes", "must be an object");
    // Every accessor the decoded mesh fills, checked before decoding (their counts bound the work).
    auto accessorOf = [&](int index, const std::string& use) -> const tinygltf::Accessor& {
        if (index < 0 || std::size_t(index) >= m.accessors.size()) {
            fail(doc.file, where, use + " accessor " + std::to_string(index) + " does not exist");
        }
        return m.accessors[std::size_t(index)];
    };
    if (p.indices < 0) fail(doc.file, where, "a Draco-compressed primitive needs its indices accessor");

    std::string why;
    const std::unique_ptr<draco_island::Mesh> dm = draco_island::decode(bytes, bv.byteLength, why);
    if (!dm) fail(doc.file, place, "the Draco stream does not decode: " + why);
    const std::size_t points = dm->points(), faces = dm->faces();
    if (budget.streams.insert(v).second) budget.streamBytes += bv.byteLength;
    budget.decodedBytes += std::uint64_t(faces) * 12 + std::uint64_t(points) * 4 * (1 + attributes->Keys().size()) * 4;
    if (budget.decodedBytes > kMaxDracoRatio * budget.streamBytes + (std::uint64_t(1) << 20)) {
        fail(doc.file, place, "the Draco streams decode to more than " + std::to_string(kMaxDracoRatio) +
                                  " times their size: not a mesh vkpath will hold");
    }

    const tinygltf::Accessor& ia = accessorOf(p.indices, "indices");
    if (ia.count != faces * 3) {
        fail(doc.file, "accessor " + std::to_string(p.indices) + " (indices of " + where + ")",
             "count " + std::to_string(ia.count) + " but the Draco mesh has " + std::to_string(faces) + " triangles");
    }
    const std::size_t indexBytes = std::size_t(componentSize(ia.componentType));
    if (ia.type != TINYGLTF_TYPE_SCALAR || ia.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || indexBytes == 0 ||
        ia.componentType == TINYGLTF_COMPONENT_TYPE_BYTE || ia.componentType == TINYGLTF_COMPONENT_TYPE_SHORT) {
        fail(doc.file, "accessor " + std::to_string(p.indices) + " (indices of " + where + ")",
             "must be SCALAR unsigned byte, short or int");
    }
    std::vector<unsigned char> indexData(faces * 3 * indexBytes);
    for (std::size_t f = 0; f < faces; ++f) {
        const auto face = dm->face(f);
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t i = face[std::size_t(c)];
            if (indexBytes < 4 && i >> (8 * indexBytes)) {
                fail(doc.file, place, "vertex index " + std::to_string(i) + " does not fit the indices accessor's type");
            }
            std::memcpy(indexData.data() + (3 * f + std::size_t(c)) * indexBytes, &i, indexBytes);  // little-endian
        }
    }
    const int newIndices = appendDecoded(m, p.indices, std::move(indexData));

    for (const std::string& name : attributes->Keys()) {
        const Value& id = attributes->Get(name);
        const std::string idPlace = place + "/attributes/" + name;
        if (!id.IsNumber() || id.GetNumberAsDouble() < 0 || id.GetNumberAsDouble() > 4294967295.0) {
            fail(doc.file, idPlace, "must be a Draco attribute id (a non-negative integer)");
        }
        const auto it = p.attributes.find(name);
        if (it == p.attributes.end()) fail(doc.file, idPlace, "the primitive has no " + name + " attribute to decode into");
        const tinygltf::Accessor& a = accessorOf(it->second, name);
        const std::string use = "accessor " + std::to_string(it->second) + " (" + name + " of " + where + ")";
        const std::uint32_t uid = std::uint32_t(id.GetNumberAsDouble());
        const int dracoComponents = dm->components(uid);
        if (dracoComponents == 0) fail(doc.file, idPlace, "the Draco mesh has no attribute " + std::to_string(uid));
        const int components = typeComponents(a.type);
        const auto type = dracoComponent(a.componentType);
        if (components == 0 || !type) fail(doc.file, use, "must be SCALAR or VEC2..VEC4 of a glTF component type");
        if (a.count != points) {
            fail(doc.file, use, "count " + std::to_string(a.count) + " but the Draco mesh has " + std::to_string(points) + " points");
        }
        if (dracoComponents != components) {
            fail(doc.file, use, "has " + std::to_string(components) + " components, the Draco attribute " +
                                    std::to_string(dracoComponents));
        }
        // An integer accessor takes Draco's integers as they are (a normalized accessor normalizes
        // them when read), so their types must agree; a float accessor takes any.
        std::vector<unsigned char> data;
        if (!dm->values(uid, *type, components, data)) {
            fail(doc.file, use, "the Draco attribute's values cannot be converted to the accessor's component type");
        }
        const int newAccessor = appendDecoded(m, it->second, std::move(data));
        m.meshes[mesh].primitives[primitive].attributes[name] = newAccessor;
    }
    m.meshes[mesh].primitives[primitive].indices = newIndices;
}

}  // namespace

std::string rewriteForTinygltf(std::string_view json, const std::string& file, Rewritten& out) {
    const bool meshopt = json.find("EXT_meshopt_compression") != std::string_view::npos;
    const bool draco = json.find("KHR_draco_mesh_compression") != std::string_view::npos;
    if (!meshopt && !draco) return {};
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(json);
    } catch (const std::exception&) {
        return {};  // tinygltf reports invalid JSON
    }
    if (!doc.is_object()) return {};
    bool changed = false;
    if (meshopt && doc.contains("buffers") && doc["buffers"].is_array()) {
        nlohmann::json& buffers = doc["buffers"];
        for (std::size_t i = 0; i < buffers.size(); ++i) {
            nlohmann::json& b = buffers[i];
            if (!b.is_object() || b.contains("uri")) continue;
            const auto ext = b.find("extensions");
            if (ext == b.end() || !ext->is_object()) continue;
            const auto e = ext->find("EXT_meshopt_compression");
            if (e == ext->end() || !e->is_object()) continue;
            const auto fallback = e->find("fallback");
            if (fallback == e->end() || *fallback != true) continue;
            const auto length = b.find("byteLength");
            if (length == b.end() || !length->is_number_unsigned()) {
                fail(file, "buffers/" + std::to_string(i) + "/byteLength", "must be a non-negative integer");
            }
            out.fallbackLength[i] = length->get<std::uint64_t>();
            b["uri"] = kPlaceholderUri;
            b["byteLength"] = 1;
            changed = true;
        }
    }
    // A Draco primitive's indices accessor has no bufferView (the data is in the Draco stream),
    // which tinygltf 2.7 refuses: it borrows the stream's bufferView until decodeDraco.
    if (draco && doc.contains("meshes") && doc["meshes"].is_array() && doc.contains("accessors") && doc["accessors"].is_array()) {
        nlohmann::json& accessors = doc["accessors"];
        for (const nlohmann::json& mesh : doc["meshes"]) {
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (const nlohmann::json& p : mesh["primitives"]) {
                if (!p.is_object() || !p.contains("indices") || !p["indices"].is_number_unsigned()) continue;
                if (!p.contains("extensions") || !p["extensions"].is_object()) continue;
                const auto e = p["extensions"].find("KHR_draco_mesh_compression");
                if (e == p["extensions"].end() || !e->is_object() || !e->contains("bufferView")) continue;
                const std::size_t a = p["indices"].get<std::size_t>();
                if (a >= accessors.size() || !accessors[a].is_object() || accessors[a].contains("bufferView")) continue;
                accessors[a]["bufferView"] = (*e)["bufferView"];
                out.borrowedIndexViews.push_back(a);
                changed = true;
            }
        }
    }
    return changed ? doc.dump() : std::string{};
}

void decodeMeshopt(Document& doc, const Rewritten& rewritten) {
    tinygltf::Model& m = doc.model;
    std::vector<MeshoptView> views;
    for (std::size_t v = 0; v < m.bufferViews.size(); ++v) {
        const auto it = m.bufferViews[v].extensions.find("EXT_meshopt_compression");
        if (it != m.bufferViews[v].extensions.end()) views.push_back(readMeshoptView(m, v, it->second, doc.file));
    }
    // Everything decoded together stays within kMaxMeshoptRatio times the data the file holds
    // (views may share compressed bytes, so each view's own bound is not enough).
    std::uint64_t fileBytes = 0, decoded = 0;
    for (const tinygltf::Buffer& b : m.buffers) fileBytes += b.data.size();
    for (const MeshoptView& s : views) decoded += s.count * s.stride;
    if (decoded > kMaxMeshoptRatio * fileBytes + 4096) {
        fail(doc.file, "EXT_meshopt_compression", "the bufferViews decode to " + std::to_string(decoded) + " bytes, more than " +
                                                      std::to_string(kMaxMeshoptRatio) + " times the " + std::to_string(fileBytes) +
                                                      " bytes of data in the file: not meshopt streams");
    }
    // Fallback buffers hold no data in the file: give each the bytes its views cover (bounded by
    // what its compressed views decode to, checked above), then decode into them.
    for (const auto& [b, length] : rewritten.fallbackLength) {
        std::uint64_t end = 0, budget = 4096;
        for (std::size_t v = 0; v < m.bufferViews.size(); ++v) {
            const tinygltf::BufferView& bv = m.bufferViews[v];
            if (bv.buffer < 0 || std::size_t(bv.buffer) != b) continue;
            end = std::max<std::uint64_t>(end, std::uint64_t(bv.byteOffset) + bv.byteLength);
        }
        for (const MeshoptView& s : views) {
            if (std::size_t(m.bufferViews[s.view].buffer) == b) budget += s.count * s.stride + 16;  // + alignment
        }
        const std::string place = "buffer " + std::to_string(b);
        if (end > length) {
            fail(doc.file, place, "its bufferViews reach byte " + std::to_string(end) + ", past its byteLength " + std::to_string(length));
        }
        if (end > budget) {
            fail(doc.file, place, "a fallback buffer of " + std::to_string(end) +
                                      " bytes is more than its compressed bufferViews can fill");
        }
        m.buffers[b].data.assign(std::size_t(end), 0);
    }
    for (const MeshoptView& s : views) decodeMeshoptView(m, s, doc.file);
}

void decodeDraco(Document& doc, const Rewritten& rewritten) {
    for (std::size_t a : rewritten.borrowedIndexViews) doc.model.accessors.at(a).bufferView = -1;
    DracoBudget budget;
    for (std::size_t mesh = 0; mesh < doc.model.meshes.size(); ++mesh) {
        for (std::size_t p = 0; p < doc.model.meshes[mesh].primitives.size(); ++p) {
            const auto& ext = doc.model.meshes[mesh].primitives[p].extensions;
            const auto it = ext.find("KHR_draco_mesh_compression");
            if (it != ext.end()) decodeDracoPrimitive(doc, mesh, p, tinygltf::Value(it->second), budget);
        }
    }
}

}  // namespace vkp::gltf
