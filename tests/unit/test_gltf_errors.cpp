// The glTF loader on broken files, each made here from one valid triangle by one change: every
// case gives one InputError line "<file>: <place>: <message>" naming the part at fault, and no
// crash (run these under ASan + UBSan: the asan preset).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace {

using namespace vkp;
using Json = nlohmann::json;
using Bytes = std::vector<std::uint8_t>;

/// One triangle: POSITION (float3, bytes 0-35), NORMAL (36-71), uint16 indices (72-77), 80 bytes.
Json baseDoc() {
    return Json::parse(R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
      "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": 36},
        {"buffer": 0, "byteOffset": 36, "byteLength": 36},
        {"buffer": 0, "byteOffset": 72, "byteLength": 6}],
      "buffers": [{"byteLength": 80}]
    })");
}

Bytes baseBin() {
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::uint16_t idx[4] = {0, 1, 2, 0};
    Bytes b(80);
    std::memcpy(b.data(), pos, 36);
    std::memcpy(b.data() + 36, nrm, 36);
    std::memcpy(b.data() + 72, idx, 8);
    return b;
}

void setFloat(Bytes& b, std::size_t at, float x) { std::memcpy(b.data() + at, &x, 4); }

void writeFile(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::string le32(std::uint32_t x) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[std::size_t(i)] = char((x >> (8 * i)) & 0xff);
    return s;
}

/// The GLB container around a JSON text and a binary chunk.
std::string glb(std::string json, const Bytes& bin) {
    while (json.size() % 4) json += ' ';
    std::string body = le32(std::uint32_t(json.size())) + le32(0x4E4F534Au) + json;
    if (!bin.empty()) body += le32(std::uint32_t(bin.size())) + le32(0x004E4942u) + std::string(bin.begin(), bin.end());
    return "glTF" + le32(2) + le32(std::uint32_t(12 + body.size())) + body;
}

struct Case {
    std::string name;
    std::function<void(Json&, Bytes&)> change;
    std::string fragment;  ///< part of the message after "<file>: "
    bool binary = false;   ///< .glb instead of .gltf + .bin
};

/// Write the case's file(s) into the scratch folder; returns the scene file.
std::filesystem::path writeCase(const Case& c) {
    const auto dir = test::scratchDir("gltf_errors");
    Json doc = baseDoc();
    Bytes bin = baseBin();
    if (c.binary) {
        c.change(doc, bin);
        const auto path = dir / (c.name + ".glb");
        writeFile(path, glb(doc.dump(), bin));
        return path;
    }
    doc["buffers"][0]["uri"] = c.name + ".bin";
    c.change(doc, bin);
    const auto path = dir / (c.name + ".gltf");
    writeFile(path, doc.dump());
    writeFile(dir / (c.name + ".bin"), std::string(bin.begin(), bin.end()));
    return path;
}

void expectError(const std::filesystem::path& file, const std::string& fragment, const GltfOptions& o = {}) {
    try {
        const Scene s = loadSceneGltf(file, o);
        ADD_FAILURE() << file << ": no error (expected \"" << fragment << "\"), " << s.shapes.size() << " shapes";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(file.string() + ": ", 0), 0u) << what;
        EXPECT_NE(what.find(fragment), std::string::npos) << "expected \"" << fragment << "\" in: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

/// The base triangle with light `light` (named "l", KHR_lights_punctual) placed by a second node
/// ("lamp") that refers to it by `index` (any JSON value).
void withLight(Json& d, Json light, const Json& index) {
    light["name"] = "l";
    d["extensionsUsed"] = {"KHR_lights_punctual"};
    d["extensions"]["KHR_lights_punctual"]["lights"] = Json::array({light});
    d["nodes"].push_back({{"name", "lamp"}, {"translation", {0, 2, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}});
    d["scenes"][0]["nodes"].push_back(1);
}

/// A data URI holding the 12-byte KTX2 file identifier (what a KHR_texture_basisu image starts with).
const char* const kKtx2Uri = "data:application/octet-stream;base64,q0tUWCAyMLsNChoK";

const std::string kPos = "accessor 0 (POSITION of mesh 0 (\"tri\") primitive 0): ";
const std::string kIdx = "accessor 2 (indices of mesh 0 (\"tri\") primitive 0): ";
const std::string kPrim = "mesh 0 (\"tri\") primitive 0: ";

TEST(GltfErrors, TheBaseTriangleLoads) {
    const Scene s = loadSceneGltf(writeCase({"base", [](Json&, Bytes&) {}, ""}));
    EXPECT_EQ(s.shapes.size(), 1u);
    const Scene g = loadSceneGltf(writeCase({"base_glb", [](Json&, Bytes&) {}, "", true}));
    EXPECT_EQ(g.shapes.size(), 1u);
}

TEST(GltfErrors, EachBrokenFileGivesItsOwnLine) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<Case> cases = {
        // Accessors, buffer views, buffers.
        {"index_out_of_range", [](Json&, Bytes& b) { b[76] = 7; }, kIdx + "index 2 is 7, but POSITION has 3 vertices"},
        {"accessor_missing", [](Json& d, Bytes&) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 9; },
         "accessor 9 (NORMAL of mesh 0 (\"tri\") primitive 0): does not exist (the file has 3 accessors)"},
        {"accessor_past_view", [](Json& d, Bytes&) { d["accessors"][0]["byteOffset"] = 4; },
         kPos + "3 elements of 12 bytes, 12 apart, from offset 4 do not fit bufferView 0 (36 bytes)"},
        {"view_past_buffer", [](Json& d, Bytes&) { d["bufferViews"][1]["byteOffset"] = 60; },
         "bufferView 1 (offset 60, length 36) is outside buffer 0 (80 bytes)"},
        {"count_absurd", [](Json& d, Bytes&) { d["accessors"][0]["count"] = 1000000000; },
         "mesh 0 (\"tri\") primitive 0 of node 0: the scene would have more than 67108864 vertices (vkpath's limit)"},
        {"count_absurd_normal", [](Json& d, Bytes&) { d["accessors"][1]["count"] = 1000000000; },
         "accessor 1 (NORMAL of mesh 0 (\"tri\") primitive 0): count 1000000000 is larger than vkpath's limit"},
        {"count_too_big", [](Json& d, Bytes&) { d["accessors"][0]["count"] = 1000; }, kPos + "1000 elements"},
        {"count_zero", [](Json& d, Bytes&) { d["accessors"][0]["count"] = 0; }, kPos + "count must be >= 1"},
        {"stride_too_small", [](Json& d, Bytes&) { d["bufferViews"][0]["byteStride"] = 8; },
         kPos + "bufferView 0 byteStride 8 is not in [12, 252]"},
        {"index_type_float", [](Json& d, Bytes&) { d["accessors"][2]["componentType"] = 5126; },
         kIdx + "is SCALAR of float, expected SCALAR of unsigned byte, unsigned short, unsigned int"},
        {"position_vec2", [](Json& d, Bytes&) { d["accessors"][0]["type"] = "VEC2"; }, kPos + "is VEC2 of float, expected VEC3"},
        {"normal_count", [](Json& d, Bytes&) { d["accessors"][1]["count"] = 2; },
         "accessor 1 (NORMAL of mesh 0 (\"tri\") primitive 0): has 2 elements but POSITION has 3"},
        {"sparse_index_out_of_range",
         [](Json& d, Bytes& b) {
             d["bufferViews"].push_back(Json::parse(R"({"buffer": 0, "byteOffset": 78, "byteLength": 2})"));
             d["accessors"][0]["sparse"] = Json::parse(
                 R"({"count": 1, "indices": {"bufferView": 3, "componentType": 5123}, "values": {"bufferView": 0}})");
             b[78] = 5;
         },
         kPos + "sparse index 0 is 5 (the accessor has 3 elements)"},
        {"sparse_not_increasing",  // uint8 indices at bytes 74, 75: 1, 0
         [](Json& d, Bytes&) {
             d["accessors"][0]["sparse"] = Json::parse(
                 R"({"count": 2, "indices": {"bufferView": 2, "componentType": 5121, "byteOffset": 2}, "values": {"bufferView": 0}})");
         },
         kPos + "sparse index 1 is 0 (indices must increase strictly)"},
        // Values.
        {"nan_position", [nan](Json&, Bytes& b) { setFloat(b, 16, nan); }, kPos + "element 1 is not finite"},
        {"inf_normal", [inf](Json&, Bytes& b) { setFloat(b, 36 + 24, inf); },
         "accessor 1 (NORMAL of mesh 0 (\"tri\") primitive 0): element 2 is not finite"},
        // Relative to the camera (here the frame starts at the node's position: no camera in the file).
        {"overflow_by_node", [](Json& d, Bytes&) { d["nodes"][0]["scale"] = {1e39, 1e39, 1e39}; d["nodes"][0]["translation"] = {3e38, 0, 0}; },
         kPos + "element 1 is outside the range of 32-bit floats once placed by its node, relative to the camera (drawn by node 0)"},
        // Meshes, nodes, scenes.
        {"skin_without_joints",
         [](Json& d, Bytes&) {
             d["skins"] = Json::parse(R"([{"jointNames": ["a"]}])");
             d["nodes"][0]["skin"] = 0;
         },
         "skins/0/joints: required: the skin's joint nodes (\"jointNames\" is glTF 1.0: this is not a glTF 2.0 file)"},
        {"mode_unknown", [](Json& d, Bytes&) { d["meshes"][0]["primitives"][0]["mode"] = 9; },
         kPrim + "mode 9 (unknown) is not a glTF primitive mode"},
        {"not_whole_triangles", [](Json& d, Bytes&) { d["accessors"][2]["count"] = 2; }, kPrim + "2 indices do not make whole triangles"},
        {"no_position", [](Json& d, Bytes&) { d["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); },
         kPrim + "has no POSITION attribute"},
        {"node_cycle", [](Json& d, Bytes&) { d["nodes"][0]["children"] = {0}; }, "node 0: is reached twice"},
        {"node_missing_child", [](Json& d, Bytes&) { d["nodes"][0]["children"] = {5}; }, "node 0/children: node 5 does not exist"},
        {"node_missing_mesh", [](Json& d, Bytes&) { d["nodes"][0]["mesh"] = 3; }, "node 0/mesh: mesh 3 does not exist"},
        {"node_bad_rotation", [](Json& d, Bytes&) { d["nodes"][0]["rotation"] = {0, 0, 0, 0}; }, "node 0/rotation: must be a unit quaternion"},
        {"scene_missing", [](Json& d, Bytes&) { d["scene"] = 4; }, "scene: scene 4 does not exist (the file has 1 scene)"},
        {"too_many_triangles",
         [](Json& d, Bytes& b) {
             // 200,000 triangles (600,000 uint8 indices, all 0) on 3 vertices, instanced by 400 nodes: 80 million.
             b.resize(80 + 600000, 0);
             d["buffers"][0]["byteLength"] = b.size();
             d["bufferViews"].push_back(Json::parse(R"({"buffer": 0, "byteOffset": 80, "byteLength": 600000})"));
             d["accessors"].push_back(Json::parse(R"({"bufferView": 3, "componentType": 5121, "count": 600000, "type": "SCALAR"})"));
             d["meshes"].push_back(Json::parse(R"({"primitives": [{"attributes": {"POSITION": 0}, "indices": 3}]})"));
             for (int i = 0; i < 400; ++i) {
                 d["nodes"].push_back(Json{{"mesh", 1}});
                 d["scenes"][0]["nodes"].push_back(i + 1);
             }
         },
         "more than 67108864 triangles (vkpath's limit)"},
        // Materials and textures.
        {"material_missing", [](Json& d, Bytes&) { d["meshes"][0]["primitives"][0]["material"] = 2; }, "material 2: does not exist"},
        {"base_color_range",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"name": "m", "pbrMetallicRoughness": {"baseColorFactor": [2, 0, 0, 1]}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0 (\"m\")/pbrMetallicRoughness/baseColorFactor/0: must be in [0, 1] (got 2)"},
        {"texture_missing",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 5}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0/pbrMetallicRoughness/baseColorTexture/index: texture 5 does not exist"},
        {"texcoord1_without_attribute",
         [](Json& d, Bytes&) {
             d["images"] = Json::parse(R"([{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAAC0lEQVR42mP4DwQACfsD/Wj6HMwAAAAASUVORK5CYII="}])");
             d["textures"] = Json::parse(R"([{"source": 0}])");
             d["materials"] = Json::parse(R"([{"name": "m", "normalTexture": {"index": 0, "texCoord": 1}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         kPrim + "has no TEXCOORD_1, but its material \"m\" reads it (normalTexture.texCoord 1)"},
        {"texcoord1_accessor_missing", [](Json& d, Bytes&) { d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 7; },
         "accessor 7 (TEXCOORD_1 of mesh 0 (\"tri\") primitive 0): does not exist"},
        {"clearcoat_factor_range",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"name": "m", "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 2}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0 (\"m\")/extensions/KHR_materials_clearcoat/clearcoatFactor: must be in [0, 1] (got 2)"},
        {"sheen_color_range",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"name": "m", "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, -1, 0]}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0 (\"m\")/extensions/KHR_materials_sheen/sheenColorFactor/1: must be in [0, 1] (got -1)"},
        {"clearcoat_normal_texture_missing",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"name": "m", "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatNormalTexture": {"index": 4}}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0 (\"m\")/extensions/KHR_materials_clearcoat/clearcoatNormalTexture/index: texture 4 does not exist"},
        {"specular_texture_missing",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"name": "m", "extensions": {"KHR_materials_specular": {"specularColorTexture": {"index": 3}}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0 (\"m\")/extensions/KHR_materials_specular/specularColorTexture/index: texture 3 does not exist"},
        {"transmission_texture_missing",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"name": "m", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1, "transmissionTexture": {"index": 2}}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0 (\"m\")/extensions/KHR_materials_transmission/transmissionTexture/index: texture 2 does not exist"},
        {"texture_basisu_only",
         [](Json& d, Bytes&) {
             d["extensionsUsed"] = Json::parse(R"(["KHR_texture_basisu"])");
             d["images"] = Json::parse(std::string(R"([{"uri": ")") + kKtx2Uri + R"(", "mimeType": "image/ktx2"}])");
             d["textures"] = Json::parse(R"([{"extensions": {"KHR_texture_basisu": {"source": 0}}}])");
             d["materials"] = Json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "texture 0: its image is only given through KHR_texture_basisu, which vkpath cannot decode, and it has no PNG or "
         "JPEG \"source\" to fall back on"},
        {"texture_source_ktx2",
         [](Json& d, Bytes&) {
             d["images"] = Json::parse(std::string(R"([{"uri": ")") + kKtx2Uri + R"("}])");
             d["textures"] = Json::parse(R"([{"source": 0}])");
             d["materials"] = Json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "texture 0: image 0 is KTX2 (Basis Universal), which vkpath cannot decode"},
        {"image_file_missing",
         [](Json& d, Bytes&) {
             d["images"] = Json::parse(R"([{"uri": "missing.png"}])");
             d["textures"] = Json::parse(R"([{"source": 0}])");
         },
         "uri \"missing.png\": cannot read"},
        {"image_corrupt",
         [](Json& d, Bytes&) { d["images"] = Json::parse(R"([{"uri": "data:image/png;base64,iVBORw0KGgoAAAAA"}])"); },
         "image 0: cannot decode"},
        {"wrap_mode",
         [](Json& d, Bytes&) {
             d["images"] = Json::parse(R"([{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAAC0lEQVR42mP4DwQACfsD/Wj6HMwAAAAASUVORK5CYII="}])");
             d["samplers"] = Json::parse(R"([{"wrapS": 1234}])");
             d["textures"] = Json::parse(R"([{"source": 0, "sampler": 0}])");
             d["materials"] = Json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "sampler 0/wrapS: 1234 is not a wrap mode"},
        {"ior_range",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"extensions": {"KHR_materials_ior": {"ior": 0.5}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0/extensions/KHR_materials_ior/ior: must be 0 or >= 1"},
        {"alpha_cutoff_overflow",
         [](Json& d, Bytes&) {
             d["materials"] = Json::parse(R"([{"alphaMode": "MASK", "alphaCutoff": 1e300}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0/alphaCutoff: must be finite as a 32-bit float (got 1e+300)"},
        {"reach_by_node", [](Json& d, Bytes&) { d["nodes"][0]["scale"] = {2e38, 2e38, 2e38}; },
         "accessor 0 (POSITION of mesh 0 (\"tri\") primitive 0): element 1 reaches 2e+38 from the camera once placed by its "
         "node: its coordinates overflow 32-bit floats"},
        {"too_large_to_frame",  // each vertex within 1e38 of the first node, the two copies 2e38 apart
         [](Json& d, Bytes&) {
             d["nodes"][0]["scale"] = {1e38, 1e38, 1e38};
             d["nodes"].push_back({{"mesh", 0}, {"scale", {1e38, 1e38, 1e38}}, {"translation", {-1e38, 0, 0}}});
             d["scenes"][0]["nodes"].push_back(1);
         },
         "cameras: the file has no camera and its scene is too large to frame in 32-bit floats"},
        // Document level.
        {"required_extension", [](Json& d, Bytes&) { d["extensionsUsed"] = {"KHR_materials_variants"}; d["extensionsRequired"] = {"KHR_materials_variants"}; },
         "extensionsRequired: extension KHR_materials_variants is required by the file but vkpath does not implement it"},
        {"version_1", [](Json& d, Bytes&) { d["asset"]["version"] = "1.0"; }, "asset/version: \"1.0\": vkpath reads glTF 2.x"},
        {"no_asset", [](Json& d, Bytes&) { d.erase("asset"); }, "(document): invalid glTF"},
        {"deep_nesting",
         [](Json& d, Bytes&) {
             Json deep = Json::array();
             for (int i = 0; i < 300; ++i) deep = Json::array({deep});
             d["extras"] = deep;
         },
         "(document): JSON nested deeper than 256 levels"},
        {"bin_missing", [](Json& d, Bytes&) { d["buffers"][0]["uri"] = "nowhere.bin"; }, "uri \"nowhere.bin\": cannot read"},
        {"bin_short", [](Json& d, Bytes&) { d["buffers"][0]["byteLength"] = 800; }, "(document): invalid glTF: File size mismatch"},
        // GLB.
        {"glb_index_out_of_range", [](Json&, Bytes& b) { b[74] = 9; }, kIdx + "index 1 is 9", true},
        {"glb_image_view_outside",
         [](Json& d, Bytes&) {
             d["bufferViews"].push_back(Json::parse(R"({"buffer": 0, "byteOffset": 40, "byteLength": 1000})"));
             d["images"] = Json::parse(R"([{"bufferView": 3, "mimeType": "image/png"}])");
         },
         "image 0: bufferView 3 (bytes 40 + 1000) is outside buffer 0 (80 bytes)", true},
        {"glb_buffer_longer_than_chunk", [](Json& d, Bytes&) { d["buffers"][0]["byteLength"] = 84; },
         "(document): invalid glTF: Invalid `byteLength'", true},
        {"color_not_normalized", [](Json& d, Bytes&) {
             d["accessors"].push_back({{"bufferView", 0}, {"componentType", 5121}, {"count", 3}, {"type", "VEC4"}});
             d["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 3; },
         "accessor 3 (COLOR_0 of mesh 0 (\"tri\") primitive 0): integer colours must be normalized"},
        {"color_vec2", [](Json& d, Bytes&) {
             d["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
             d["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 3; },
         "accessor 3 (COLOR_0 of mesh 0 (\"tri\") primitive 0): is not VEC3 or VEC4"},
        // KHR_lights_punctual: the light and the node that places it.
        {"light_index_missing", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "point"})"), 3); },
         "node 1 (\"lamp\")/extensions/KHR_lights_punctual/light: light 3 does not exist (the file has 1 lights)"},
        {"light_index_fraction", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "point"})"), 0.5); },
         "node 1 (\"lamp\")/extensions/KHR_lights_punctual/light: light 0.5 does not exist"},
        {"light_index_string", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "point"})"), "0"); },
         "node 1 (\"lamp\")/extensions/KHR_lights_punctual/light: must be the index of a light"},
        {"light_type", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "area"})"), 0); },
         "KHR_lights_punctual light 0 (\"l\")/type: \"area\" is not a light type (point, spot or directional)"},
        {"light_intensity_negative", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "point", "intensity": -1})"), 0); },
         "KHR_lights_punctual light 0 (\"l\")/intensity: must be finite and >= 0"},
        {"light_color_short", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "point", "color": [1, 1]})"), 0); },
         "KHR_lights_punctual light 0 (\"l\")/color: must have 3 numbers (got 2)"},
        {"light_color_negative", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "point", "color": [1, -1, 1]})"), 0); },
         "KHR_lights_punctual light 0 (\"l\")/color/1: must be finite and >= 0"},
        {"spot_without_spot", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "spot"})"), 0); },
         "KHR_lights_punctual light 0/spot: a spot light needs its \"spot\" object"},
        {"spot_without_spot_glb", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"type": "spot"})"), 0); },
         "KHR_lights_punctual light 0/spot: a spot light needs its \"spot\" object", true},
        {"light_without_type", [](Json& d, Bytes&) { withLight(d, Json::parse(R"({"intensity": 2})"), 0); },
         "KHR_lights_punctual light 0/type: must be a string"},
        {"light_not_object", [](Json& d, Bytes&) {
             withLight(d, Json::parse(R"({"type": "point"})"), 0);
             d["extensions"]["KHR_lights_punctual"]["lights"][0] = 3; },
         "KHR_lights_punctual light 0: must be an object"},
        {"spot_outer_wide", [](Json& d, Bytes&) {
             withLight(d, Json::parse(R"({"type": "spot", "spot": {"outerConeAngle": 2}})"), 0); },
         "KHR_lights_punctual light 0 (\"l\")/spot/outerConeAngle: must be in (0, pi/2]"},
        {"spot_inner_outer", [](Json& d, Bytes&) {
             withLight(d, Json::parse(R"({"type": "spot", "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.5}})"), 0); },
         "KHR_lights_punctual light 0 (\"l\")/spot/innerConeAngle: must be >= 0 and at most outerConeAngle"},
        {"spot_node_flattened", [](Json& d, Bytes&) {
             withLight(d, Json::parse(R"({"type": "spot", "spot": {}})"), 0);
             d["nodes"][1]["scale"] = {1, 1, 0}; },
         "KHR_lights_punctual light 0 (\"l\") of node 1 (\"lamp\"): its direction is zero or not finite"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        expectError(writeCase(c), c.fragment);
    }
}

TEST(GltfErrors, TexCoordAboveOneIsAWarningNamingMaterialAndTexture) {
    const Scene s = loadSceneGltf(writeCase({"texcoord2", [](Json& d, Bytes&) {
        d["images"] = Json::parse(R"([{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAAC0lEQVR42mP4DwQACfsD/Wj6HMwAAAAASUVORK5CYII="}])");
        d["textures"] = Json::parse(R"([{"source": 0}])");
        d["materials"] = Json::parse(R"([{"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 2}}}])");
        d["meshes"][0]["primitives"][0]["material"] = 0;
    }, ""}));
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("texcoord2.gltf: material 0 (\"m\")/pbrMetallicRoughness/baseColorTexture: texture 0 uses "
                                 "TEXCOORD_2: vkpath reads TEXCOORD_0 and TEXCOORD_1 only and uses TEXCOORD_0 instead"),
              std::string::npos) << s.warnings[0];
    EXPECT_EQ(s.materials.at(0).pbr.baseColorTexture.texCoord, 0u);
}

// KHR_texture_basisu with the PNG fallback the extension allows: the PNG is used, the KTX2 image
// is kept undecoded, and the extension is named in one warning.
TEST(GltfErrors, BasisuTextureWithAPngFallbackUsesThePng) {
    const Scene s = loadSceneGltf(writeCase({"basisu_fallback", [](Json& d, Bytes&) {
        d["extensionsUsed"] = Json::parse(R"(["KHR_texture_basisu"])");
        d["images"] = Json::parse(std::string(R"([{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAAC0lEQVR42mP4DwQACfsD/Wj6HMwAAAAASUVORK5CYII="}, {"uri": ")") +
                                 kKtx2Uri + R"(", "mimeType": "image/ktx2"}])");
        d["textures"] = Json::parse(R"([{"source": 0, "extensions": {"KHR_texture_basisu": {"source": 1}}}])");
        d["materials"] = Json::parse(R"([{"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
        d["meshes"][0]["primitives"][0]["material"] = 0;
    }, ""}));
    ASSERT_EQ(s.images.size(), 1u);
    EXPECT_EQ(s.images[0].width, 1u);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("extension KHR_texture_basisu is not supported by vkpath: ignored"), std::string::npos)
        << s.warnings[0];
}

// COLOR_0 is read: no warning; the POSITION accessor as colours (float VEC3: alpha 1, negative
// values clamped to 0).
TEST(GltfErrors, VertexColoursAreReadWithoutAWarning) {
    const Scene s = loadSceneGltf(writeCase({"color0", [](Json& d, Bytes&) {
        d["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 0;  // a float VEC3 accessor
    }, ""}));
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.vertices.color.size(), 3u);
    EXPECT_EQ(s.vertices.color[1], glm::vec4(1, 0, 0, 1));
    EXPECT_TRUE(s.triangleVertices.at(0).flags & TriangleVertices::kHasColor);
}

// Points and lines (glTF modes 0-3) are skipped with one warning each, naming the primitive; the
// triangles of the same mesh are still drawn.
TEST(GltfErrors, PointsAndLinesAreSkippedWithAWarning) {
    const Scene s = loadSceneGltf(writeCase({"lines_and_triangle", [](Json& d, Bytes&) {
        Json lines = d["meshes"][0]["primitives"][0];
        lines["mode"] = 1;
        lines.erase("indices");
        Json points = lines;
        points["mode"] = 0;
        d["meshes"][0]["primitives"].push_back(lines);
        d["meshes"][0]["primitives"].push_back(points);
    }, ""}));
    EXPECT_EQ(s.shapes.size(), 1u);  // the triangle
    ASSERT_EQ(s.warnings.size(), 2u);
    EXPECT_NE(s.warnings[0].find("mesh 0 (\"tri\") primitive 1: mode 1 (LINES): points and lines are not rendered"),
              std::string::npos) << s.warnings[0];
    EXPECT_NE(s.warnings[1].find("primitive 2: mode 0 (POINTS)"), std::string::npos) << s.warnings[1];
}

// An unlit material renders as an emitter: its alphaMode and the COLOR_0 of its meshes are ignored,
// each with one warning naming the place, not silently.
TEST(GltfErrors, WhatAnUnlitMaterialIgnoresIsAWarning) {
    const Scene s = loadSceneGltf(writeCase({"unlit_mask", [](Json& d, Bytes&) {
        d["extensionsUsed"] = {"KHR_materials_unlit"};
        d["materials"] = Json::parse(R"([{"name": "u", "alphaMode": "MASK", "extensions": {"KHR_materials_unlit": {}}}])");
        d["meshes"][0]["primitives"][0]["material"] = 0;
        d["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 0;
    }, ""}));
    ASSERT_EQ(s.warnings.size(), 2u);
    EXPECT_NE(s.warnings[0].find("material 0 (\"u\")/alphaMode: ignored for an unlit material"), std::string::npos) << s.warnings[0];
    EXPECT_NE(s.warnings[1].find("mesh 0 (\"tri\") primitive 0: COLOR_0 ignored: its material \"u\" renders as an emitter"),
              std::string::npos) << s.warnings[1];
}

// KHR_materials_volume (github.com/KhronosGroup/glTF, extensions/2.0/Khronos/KHR_materials_volume):
// with thicknessFactor > 0 the glass that transmission becomes absorbs -ln(attenuationColor) /
// attenuationDistance per unit length; thin-walled (thickness 0) it does not; bad values are one
// line naming the place.
TEST(GltfErrors, VolumeAbsorptionIsReadAndChecked) {
    auto volume = [](const char* name, const char* ext) {
        return writeCase({name, [ext](Json& d, Bytes&) {
            d["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume"};
            d["materials"] = Json::array({{{"name", "glass"},
                                           {"extensions",
                                            {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                             {"KHR_materials_volume", Json::parse(ext)}}}}});
            d["meshes"][0]["primitives"][0]["material"] = 0;
        }, ""});
    };
    const Scene s = loadSceneGltf(volume("volume", R"({"thicknessFactor": 1, "attenuationColor": [0.5, 0.25, 1], "attenuationDistance": 2})"));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    const Material k = kernelMaterial(s.materials.at(0));
    EXPECT_EQ(k.type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(k.absorption.x, float(std::log(2.0) / 2.0));
    EXPECT_FLOAT_EQ(k.absorption.y, float(std::log(4.0) / 2.0));
    EXPECT_EQ(k.absorption.z, 0.0f);
    const Scene thin = loadSceneGltf(volume("volume_thin", R"({"thicknessFactor": 0, "attenuationColor": [0.5, 0.5, 0.5], "attenuationDistance": 1})"));
    EXPECT_EQ(kernelMaterial(thin.materials.at(0)).absorption, glm::vec3(0.0f));
    const Scene clear = loadSceneGltf(volume("volume_default", R"({"thicknessFactor": 3})"));  // distance +inf: clear
    EXPECT_EQ(kernelMaterial(clear.materials.at(0)).absorption, glm::vec3(0.0f));
    expectError(volume("volume_distance", R"({"thicknessFactor": 1, "attenuationDistance": 0})"),
                "material 0 (\"glass\")/extensions/KHR_materials_volume/attenuationDistance: must be > 0");
    expectError(volume("volume_colour", R"({"thicknessFactor": 1, "attenuationColor": [2, 0, 0]})"),
                "KHR_materials_volume/attenuationColor");
}

TEST(GltfErrors, BrokenContainersAndFiles) {
    const auto dir = test::scratchDir("gltf_errors");
    const std::string good = glb(baseDoc().dump(), baseBin());
    auto withBytes = [&](const std::string& name, std::string bytes) {
        const auto p = dir / name;
        writeFile(p, bytes);
        return p;
    };
    expectError(dir / "does-not-exist.gltf", "cannot read: no such file");
    expectError(withBytes("empty.gltf", ""), "(document): invalid glTF");
    std::string text = baseDoc().dump();
    expectError(withBytes("truncated.gltf", text.substr(0, text.size() / 2)), "(document): invalid JSON: [json.exception.parse_error");
    expectError(withBytes("truncated.glb", good.substr(0, good.size() - 10)), "GLB header: truncated: the header gives");
    expectError(withBytes("header-only.glb", good.substr(0, 16)), "GLB header: truncated: 16 bytes");
    std::string v1 = good;
    v1[4] = 1;
    expectError(withBytes("version1.glb", v1), "GLB header: container version 1");
    std::string longJson = good;
    longJson.replace(12, 4, le32(0x7ffffff0u));
    expectError(withBytes("json-chunk.glb", longJson), "GLB chunk 0: JSON chunk length 2147483632 does not fit");
    std::string longBin = good;
    std::uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, good.data() + 12, 4);
    const std::size_t binHeader = 20 + jsonLength;
    longBin.replace(binHeader, 4, le32(88));  // 8 bytes more than there are
    expectError(withBytes("bin-chunk.glb", longBin), "GLB chunk 1: BIN chunk length 88 runs past the end of the file");
    std::string notBin = good;
    notBin.replace(binHeader + 4, 4, "XXXX");
    expectError(withBytes("bin-type.glb", notBin), "GLB chunk 1: the second chunk must be BIN");
}

TEST(GltfErrors, CameraChoices) {
    const auto file = writeCase({"cameras", [](Json& d, Bytes&) {
                                     d["cameras"] = Json::parse(R"([{"type": "perspective", "perspective": {"yfov": 0, "znear": 1}}])");
                                     d["nodes"].push_back(Json{{"camera", 0}});
                                     d["scenes"][0]["nodes"].push_back(1);
                                 },
                                 ""});
    expectError(file, "camera 0/perspective/yfov: must be in (0, pi) radians (got 0");
    GltfOptions o;
    o.scene = 3;
    expectError(file, "--gltf-scene 3: scene 3 does not exist", o);
}

}  // namespace
