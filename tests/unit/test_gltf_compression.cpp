// Compressed glTF meshes (EXT_meshopt_compression, KHR_draco_mesh_compression): files written
// here with the libraries' own encoders (meshoptimizer, Draco), loaded, and compared with the
// uncompressed file triangle by triangle: identical where the codec is lossless, within the
// quantisation step where a filter or Draco's quantisation is lossy.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "draco_encode.h"
#include "scene/gltf.h"
#include "test_paths.h"

namespace {

using Json = nlohmann::json;
using Bytes = std::vector<std::uint8_t>;

/// A torus (radii 1 and 0.4 about y, rings x segments quads, seams duplicated for the UVs) with
/// normals and UVs: no degenerate triangle (Draco drops those), so every codec keeps them all.
struct Mesh {
    std::vector<float> pos, nrm, uv;
    std::vector<std::uint32_t> idx;
    std::size_t vertices() const { return pos.size() / 3; }
};

Mesh torus(int rings, int segments) {
    Mesh m;
    const double pi = 3.14159265358979323846, R = 1.0, r = 0.4;
    for (int i = 0; i <= rings; ++i) {
        for (int j = 0; j <= segments; ++j) {
            const double u = 2 * pi * i / rings, v = 2 * pi * j / segments;
            const double n[3] = {std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)};
            const double c[3] = {R * std::cos(u), 0.0, R * std::sin(u)};
            for (int k = 0; k < 3; ++k) {
                m.pos.push_back(float(c[k] + r * n[k]));
                m.nrm.push_back(float(n[k]));
            }
            m.uv.push_back(float(i) / float(rings));
            m.uv.push_back(float(j) / float(segments));
        }
    }
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = std::uint32_t(i * (segments + 1) + j), b = a + std::uint32_t(segments + 1);
            for (std::uint32_t k : {a, a + 1, b, a + 1, b + 1, b}) m.idx.push_back(k);
        }
    }
    return m;
}

std::string base64(const Bytes& b) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < b.size(); i += 3) {
        const std::uint32_t n = std::uint32_t(b[i]) << 16 | (i + 1 < b.size() ? std::uint32_t(b[i + 1]) << 8 : 0) |
                                (i + 2 < b.size() ? b[i + 2] : 0);
        out += t[n >> 18 & 63];
        out += t[n >> 12 & 63];
        out += i + 1 < b.size() ? t[n >> 6 & 63] : '=';
        out += i + 2 < b.size() ? t[n & 63] : '=';
    }
    return out;
}
std::string dataUri(const Bytes& b) { return "data:application/octet-stream;base64," + base64(b); }

void append(Bytes& to, const void* p, std::size_t n) {
    const auto* c = static_cast<const std::uint8_t*>(p);
    to.insert(to.end(), c, c + n);
    while (to.size() % 4 != 0) to.push_back(0);
}

void writeFile(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << p;
}

std::string glb(std::string json, const Bytes& bin) {
    while (json.size() % 4 != 0) json += ' ';
    auto le = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::uint32_t total = std::uint32_t(12 + 8 + json.size() + 8 + bin.size());
    return std::string("glTF") + le(2) + le(total) + le(std::uint32_t(json.size())) + "JSON" + json +
           le(std::uint32_t(bin.size())) + "BIN" + std::string(1, '\0') + std::string(bin.begin(), bin.end());
}

/// The uncompressed layout: positions, normals, UVs, 16-bit indices, one after the other.
struct Layout {
    Bytes bytes;
    std::size_t offset[4] = {}, length[4] = {}, stride[4] = {12, 12, 8, 2}, count[4] = {};
};

Layout plainLayout(const Mesh& m) {
    Layout l;
    std::vector<std::uint16_t> idx16(m.idx.begin(), m.idx.end());
    const void* src[4] = {m.pos.data(), m.nrm.data(), m.uv.data(), idx16.data()};
    const std::size_t n[4] = {m.vertices(), m.vertices(), m.vertices(), m.idx.size()};
    for (int i = 0; i < 4; ++i) {
        l.offset[i] = l.bytes.size();
        l.count[i] = n[i];
        l.length[i] = n[i] * l.stride[i];
        append(l.bytes, src[i], l.length[i]);
    }
    return l;
}

/// A camera of the file's own, so that the positions the loader gives (relative to the camera) do
/// not depend on the mesh's bounds, which a lossy codec moves.
void addCamera(Json& d) {
    d["cameras"] = Json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}});
    d["nodes"] = Json::array({{{"mesh", 0}}, {{"camera", 0}, {"translation", {0, 0, 5}}}});
    d["scenes"] = Json::array({{{"nodes", {0, 1}}}});
}

/// The glTF document around the layout's views 0..3 (accessors 0..3 on them) in buffer `buffer`.
Json document(const Layout& l, int buffer, const Json& buffers) {
    Json d;
    d["asset"] = {{"version", "2.0"}};
    d["buffers"] = buffers;
    d["bufferViews"] = Json::array();
    for (int i = 0; i < 4; ++i) {
        Json v = {{"buffer", buffer}, {"byteOffset", l.offset[i]}, {"byteLength", l.length[i]}};
        if (i < 3) v["byteStride"] = l.stride[i];
        d["bufferViews"].push_back(v);
    }
    d["accessors"] = Json::array({
        {{"bufferView", 0}, {"componentType", 5126}, {"count", l.count[0]}, {"type", "VEC3"}, {"min", {-1.4, -0.4, -1.4}}, {"max", {1.4, 0.4, 1.4}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", l.count[1]}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", l.count[2]}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5123}, {"count", l.count[3]}, {"type", "SCALAR"}},
    });
    d["meshes"] = Json::array({{{"name", "torus"},
                                {"primitives", Json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                                                             {"indices", 3}}})}}});
    addCamera(d);
    return d;
}

/// How the meshopt file encodes its views.
struct MeshoptOptions {
    std::string indexMode = "TRIANGLES";  ///< or INDICES
    bool octahedralNormals = false;        ///< normals as 8-bit octahedral (a lossy filter)
    bool exponentialPositions = false;     ///< positions with the exponential filter (lossy)
    bool binary = false;                   ///< GLB: the compressed data in the BIN chunk
};

std::string meshoptFile(const Mesh& m, const MeshoptOptions& o) {
    Layout l = plainLayout(m);
    Bytes compressed;
    Json views = Json::array();
    const std::size_t n = m.vertices();
    // The bytes each view holds before compression (filters applied).
    std::vector<Bytes> raw(4);
    std::string filter[4] = {"NONE", "NONE", "NONE", "NONE"};
    for (int i = 0; i < 4; ++i) raw[std::size_t(i)].assign(l.bytes.begin() + long(l.offset[i]), l.bytes.begin() + long(l.offset[i] + l.length[i]));
    if (o.exponentialPositions) {
        meshopt_encodeFilterExp(raw[0].data(), n, 12, 15, m.pos.data());
        filter[0] = "EXPONENTIAL";
    }
    if (o.octahedralNormals) {
        std::vector<float> n4;
        for (std::size_t i = 0; i < n; ++i) n4.insert(n4.end(), {m.nrm[3 * i], m.nrm[3 * i + 1], m.nrm[3 * i + 2], 0.0f});
        raw[1].assign(n * 4, 0);
        meshopt_encodeFilterOct(raw[1].data(), n, 4, 8, n4.data());
        filter[1] = "OCTAHEDRAL";
        l.stride[1] = 4;
    }
    // The uncompressed (fallback) buffer's layout follows the raw sizes.
    std::size_t at = 0;
    for (int i = 0; i < 4; ++i) {
        l.offset[i] = at;
        l.length[i] = raw[std::size_t(i)].size();
        at += (l.length[i] + 3) / 4 * 4;
    }
    for (int i = 0; i < 4; ++i) {
        Bytes out;
        if (i < 3) {
            out.resize(meshopt_encodeVertexBufferBound(n, l.stride[i]));
            out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), raw[std::size_t(i)].data(), n, l.stride[i]));
        } else if (o.indexMode == "TRIANGLES") {
            out.resize(meshopt_encodeIndexBufferBound(m.idx.size(), n));
            out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), m.idx.data(), m.idx.size()));
        } else {
            out.resize(meshopt_encodeIndexSequenceBound(m.idx.size(), n));
            out.resize(meshopt_encodeIndexSequence(out.data(), out.size(), m.idx.data(), m.idx.size()));
        }
        EXPECT_GT(out.size(), 0u);
        views.push_back({{"buffer", 0}, {"byteOffset", compressed.size()}, {"byteLength", out.size()}, {"byteStride", l.stride[i]},
                         {"count", l.count[i]}, {"mode", i < 3 ? "ATTRIBUTES" : o.indexMode}, {"filter", filter[i]}});
        append(compressed, out.data(), out.size());
    }
    Json buffer0 = {{"byteLength", compressed.size()}};
    if (!o.binary) buffer0["uri"] = dataUri(compressed);
    const Json buffers = Json::array({buffer0, {{"byteLength", at}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
    Json d = document(l, 1, buffers);
    for (int i = 0; i < 4; ++i) d["bufferViews"][std::size_t(i)]["extensions"]["EXT_meshopt_compression"] = views[std::size_t(i)];
    if (o.octahedralNormals) d["accessors"][1] = {{"bufferView", 1}, {"componentType", 5120}, {"normalized", true}, {"count", n}, {"type", "VEC3"}};
    d["extensionsUsed"] = {"EXT_meshopt_compression"};
    d["extensionsRequired"] = {"EXT_meshopt_compression"};
    return o.binary ? glb(d.dump(), compressed) : d.dump();
}

std::string plainFile(const Mesh& m) {
    const Layout l = plainLayout(m);
    return document(l, 0, Json::array({{{"byteLength", l.bytes.size()}, {"uri", dataUri(l.bytes)}}})).dump();
}

/// A Draco-compressed file: quantBits 0 keeps every attribute exact, else positions get
/// quantBits bits, normals 10, UVs 12 (typical exporter settings).
std::string dracoFile(const Mesh& m, int quantBits, int method = -1) {
    const vkp::draco_test::Encoded e =
        vkp::draco_test::encode(m.pos.data(), m.nrm.data(), m.uv.data(), m.idx.data(), m.idx.size() / 3, quantBits, method);
    EXPECT_EQ(e.error, "");
    const Bytes& bytes = e.bytes;
    Json d;
    d["asset"] = {{"version", "2.0"}};
    d["buffers"] = Json::array({{{"byteLength", bytes.size()}, {"uri", dataUri(bytes)}}});
    d["bufferViews"] = Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", bytes.size()}}});
    const std::size_t points = e.points;
    d["accessors"] = Json::array({
        {{"componentType", 5126}, {"count", points}, {"type", "VEC3"}, {"min", {-1.4, -0.4, -1.4}}, {"max", {1.4, 0.4, 1.4}}},
        {{"componentType", 5126}, {"count", points}, {"type", "VEC3"}},
        {{"componentType", 5126}, {"count", points}, {"type", "VEC2"}},
        {{"componentType", 5123}, {"count", m.idx.size()}, {"type", "SCALAR"}},
    });
    const Json ext = {{"bufferView", 0},
                      {"attributes",
                       {{"POSITION", e.position}, {"NORMAL", e.normal}, {"TEXCOORD_0", e.uv}}}};
    d["meshes"] = Json::array({{{"name", "torus"},
                                {"primitives", Json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                                                             {"indices", 3},
                                                             {"extensions", {{"KHR_draco_mesh_compression", ext}}}}})}}});
    addCamera(d);
    d["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    d["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    return d.dump();
}

/// One triangle corner as the renderer sees it: position, normal, UV.
using Corner = std::array<float, 8>;
using Triangle = std::array<Corner, 3>;

/// The scene's triangles, each rotated to start at its smallest corner (winding kept), sorted:
/// equal for two files that describe the same surface, whatever their vertex and face order.
std::vector<Triangle> triangles(const std::filesystem::path& file) {
    const vkp::Scene s = vkp::loadSceneGltf(file);
    std::vector<Triangle> out;
    for (const vkp::Shape& sh : s.shapes) {
        const vkp::TriangleVertices& tv = s.triangleVertices.at(sh.attributes);
        const glm::vec3 p[3] = {sh.p0, sh.p1, sh.p2};
        Triangle t;
        for (int c = 0; c < 3; ++c) {
            const glm::vec3 n = s.vertices.normal[tv.v[c]];
            const glm::vec2 uv = s.vertices.uv[tv.v[c]];
            t[std::size_t(c)] = {p[c].x, p[c].y, p[c].z, n.x, n.y, n.z, uv.x, uv.y};
        }
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// Largest difference of positions, normals and UVs between two files' triangles, each triangle
/// of a matched to the nearest unmatched one of b, over all eight numbers of its corners and the
/// three rotations of its corners (lossy codecs move corners, so the smallest-corner rotation and
/// the sort order may differ; seam and pole vertices share positions).
std::array<double, 3> largestDifference(const std::vector<Triangle>& a, const std::vector<Triangle>& b) {
    std::array<double, 3> d = {0, 0, 0};
    std::vector<char> used(b.size(), 0);
    auto distance = [](const Triangle& x, const Triangle& y, std::size_t r) {
        double s = 0;
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t k = 0; k < 8; ++k) s += std::abs(double(x[c][k]) - double(y[(c + r) % 3][k]));
        return s;
    };
    for (const Triangle& ta : a) {
        std::size_t best = 0, rotation = 0;
        double bestDist = HUGE_VAL;
        for (std::size_t j = 0; j < b.size(); ++j) {
            for (std::size_t r = 0; r < 3 && !used[j]; ++r) {
                const double dist = distance(ta, b[j], r);
                if (dist < bestDist) bestDist = dist, best = j, rotation = r;
            }
        }
        used[best] = 1;
        for (std::size_t c = 0; c < 3; ++c) {
            for (std::size_t k = 0; k < 8; ++k) {
                double& slot = d[k < 3 ? 0 : k < 6 ? 1 : 2];
                slot = std::max(slot, std::abs(double(ta[c][k]) - double(b[best][(c + rotation) % 3][k])));
            }
        }
    }
    return d;
}

class GltfCompression : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = vkp::test::scratchDir("gltf_compression");
        mesh_ = torus(16, 12);
        writeFile(dir_ / "plain.gltf", plainFile(mesh_));
        reference_ = triangles(dir_ / "plain.gltf");
        ASSERT_EQ(reference_.size(), mesh_.idx.size() / 3);
    }
    std::filesystem::path write(const std::string& name, const std::string& bytes) {
        writeFile(dir_ / name, bytes);
        return dir_ / name;
    }
    std::filesystem::path dir_;
    Mesh mesh_;
    std::vector<Triangle> reference_;
};

TEST_F(GltfCompression, MeshoptTrianglesIsIdenticalToTheUncompressedFile) {
    EXPECT_EQ(triangles(write("meshopt.gltf", meshoptFile(mesh_, {}))), reference_);
}

TEST_F(GltfCompression, MeshoptIndexSequenceIsIdenticalToTheUncompressedFile) {
    MeshoptOptions o;
    o.indexMode = "INDICES";
    EXPECT_EQ(triangles(write("meshopt-indices.gltf", meshoptFile(mesh_, o))), reference_);
}

TEST_F(GltfCompression, MeshoptGlbWithFallbackBufferIsIdenticalToTheUncompressedFile) {
    MeshoptOptions o;
    o.binary = true;
    EXPECT_EQ(triangles(write("meshopt.glb", meshoptFile(mesh_, o))), reference_);
}

TEST_F(GltfCompression, MeshoptFiltersDecodeWithinTheirQuantisation) {
    MeshoptOptions o;
    o.octahedralNormals = true;
    o.exponentialPositions = true;
    const std::vector<Triangle> t = triangles(write("meshopt-filters.gltf", meshoptFile(mesh_, o)));
    ASSERT_EQ(t.size(), reference_.size());
    const auto d = largestDifference(t, reference_);
    // Exponential, 15-bit mantissa shared by a vector (signed: 14 bits of magnitude): steps of
    // 2^-14 times the power of two at or above the largest component (<= 1.4, so 2), half a step
    // of rounding: 2^-14. 8-bit octahedral normals: about 1/127 per component (with the
    // renormalisation, under 2/127). 1e-6: float rounding of positions relative to the camera.
    EXPECT_LT(d[0], 1.0 / 16384.0 + 1e-6);
    EXPECT_GT(d[1], 0.0);  // lossy indeed: the filter was applied and decoded
    EXPECT_LT(d[1], 2.0 / 127.0);
    EXPECT_EQ(d[2], 0.0);  // UVs are not filtered
}

TEST_F(GltfCompression, DracoLosslessIsIdenticalToTheUncompressedFile) {
    EXPECT_EQ(triangles(write("draco.gltf", dracoFile(mesh_, 0))), reference_);
    EXPECT_EQ(triangles(write("draco-sequential.gltf", dracoFile(mesh_, 0, vkp::draco_test::sequentialMethod()))), reference_);
}

TEST_F(GltfCompression, DracoQuantisedIsWithinItsQuantisationStep) {
    const std::vector<Triangle> t = triangles(write("draco-quantised.gltf", dracoFile(mesh_, 14)));
    ASSERT_EQ(t.size(), reference_.size());
    const auto d = largestDifference(t, reference_);
    // Positions: 14 bits over the largest extent 2.8 (half a step: 2.8 / (2^14 - 1) / 2);
    // normals: Draco's octahedral 10 bits; UVs: 12 bits over the range 1.
    EXPECT_LT(d[0], 2.8 / 16383.0 * 0.5 + 1e-6);
    EXPECT_LT(d[1], 0.01);
    EXPECT_LT(d[2], 1.0 / 4095.0 * 0.5 * 1.01);
}

/// The one line a broken file gets.
std::string errorOf(const std::filesystem::path& file) {
    try {
        (void)vkp::loadSceneGltf(file);
    } catch (const vkp::InputError& e) {
        return e.what();
    }
    return "(loaded without an error)";
}

TEST_F(GltfCompression, BrokenStreamsAreRefusedNamingThePlace) {
    // A meshopt stream cut short.
    Json d = Json::parse(meshoptFile(mesh_, {}));
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 20;
    const std::string cut = errorOf(write("meshopt-cut.gltf", d.dump()));
    EXPECT_NE(cut.find("bufferView 0/extensions/EXT_meshopt_compression: the ATTRIBUTES stream does not decode"), std::string::npos) << cut;

    // A decoded size no stream of that length can give (a bomb), refused before any allocation.
    d = Json::parse(meshoptFile(mesh_, {}));
    d["bufferViews"][0]["byteLength"] = 12 * 100000000;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 100000000;
    d["buffers"][1]["byteLength"] = 12ull * 100000000 + 4096;
    const std::string bomb = errorOf(write("meshopt-bomb.gltf", d.dump()));
    EXPECT_NE(bomb.find("cannot come from"), std::string::npos) << bomb;

    // Many views citing the same compressed bytes: each within its own bound, together far beyond
    // what the file's data can decode to (a decompression bomb by repetition).
    d = Json::parse(meshoptFile(mesh_, {}));
    {
        const Json view = d["bufferViews"][0];
        const std::uint64_t each = view["byteLength"].get<std::uint64_t>();
        for (int i = 0; i < 2000; ++i) {
            Json v = view;
            v["byteOffset"] = each * std::uint64_t(i + 1);
            d["bufferViews"].push_back(v);
        }
        d["buffers"][1]["byteLength"] = each * 2001;
    }
    const std::string many = errorOf(write("meshopt-many.gltf", d.dump()));
    EXPECT_NE(many.find("EXT_meshopt_compression: the bufferViews decode to"), std::string::npos) << many;

    // An unknown mode.
    d = Json::parse(meshoptFile(mesh_, {}));
    d["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["mode"] = "STRIPS";
    const std::string mode = errorOf(write("meshopt-mode.gltf", d.dump()));
    EXPECT_NE(mode.find("bufferView 3/extensions/EXT_meshopt_compression/mode: \"STRIPS\""), std::string::npos) << mode;

    // A Draco stream of garbage.
    d = Json::parse(dracoFile(mesh_, 0));
    d["buffers"][0]["uri"] = dataUri(Bytes(64, 0x5a));
    d["buffers"][0]["byteLength"] = 64;
    d["bufferViews"][0]["byteLength"] = 64;
    const std::string garbage = errorOf(write("draco-garbage.gltf", d.dump()));
    EXPECT_NE(garbage.find("mesh 0 (\"torus\") primitive 0/extensions/KHR_draco_mesh_compression: the Draco stream does not decode"),
              std::string::npos)
        << garbage;

    // Accessor counts that disagree with the decoded mesh.
    d = Json::parse(dracoFile(mesh_, 0));
    d["accessors"][1]["count"] = 7;
    const std::string count = errorOf(write("draco-count.gltf", d.dump()));
    EXPECT_NE(count.find("accessor 1 (NORMAL of mesh 0 (\"torus\") primitive 0): count 7 but the Draco mesh has"), std::string::npos)
        << count;

    // An attribute id the stream does not have.
    d = Json::parse(dracoFile(mesh_, 0));
    d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
    const std::string id = errorOf(write("draco-id.gltf", d.dump()));
    EXPECT_NE(id.find("attributes/NORMAL: the Draco mesh has no attribute 9"), std::string::npos) << id;
}

}  // namespace
