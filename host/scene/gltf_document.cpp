// Reading a glTF file into a tinygltf::Model, with the checks tinygltf 2.7 leaves out: the GLB
// container (glTF 2.0 sec. 4.4), JSON nesting depth, file access only through our callbacks (so a
// missing .bin or image is an error naming it), images decoded by scene/ldr_image.h (bounds of a GLB
// image's bufferView checked first), the asset version and the required / used extensions.

#include <algorithm>
#include <cstring>
#include <exception>
#include <map>
#include <set>
#include <string_view>
#include <system_error>

#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "core/input_file.h"
#include "scene/gltf_parts.h"
#include "scene/json_reader.h"
#include "scene/ldr_image.h"

namespace vkp::gltf {

namespace {

constexpr std::size_t kMaxJsonNesting = 256;
constexpr int kMaxImageSide = 16384;

/// What the callbacks tinygltf calls need, and what they found wrong.
struct LoadContext {
    const tinygltf::Model* model = nullptr;
    std::map<std::string, ExternalFile> files;       ///< the only files tinygltf may read (externalFiles)
    std::map<std::string, std::string> unreadable;  ///< path tinygltf asked for -> reason
    std::set<int> ktx2;                              ///< images kept undecoded: KTX2 (KHR_texture_basisu)
    std::pair<std::string, std::string> imageError;  ///< the first image that cannot be used: place, message
};

bool fileExists(const std::string& path, void* user) {
    // tinygltf tries <base dir>/<uri>, then ./<uri>: only the first is ours, and only for a uri
    // that externalFiles checked.
    auto* ctx = static_cast<LoadContext*>(user);
    const auto f = ctx->files.find(path);
    if (f == ctx->files.end()) return false;
    std::error_code ec;
    if (std::filesystem::is_regular_file(f->second.file, ec)) return true;
    ctx->unreadable.emplace(path, std::filesystem::exists(f->second.file, ec) ? "not a regular file" : "no such file");
    return false;
}

std::string expandFilePath(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* ctx = static_cast<LoadContext*>(user);
    const auto f = ctx->files.find(path);
    if (f == ctx->files.end()) {  // not reached: fileExists said no
        if (err) *err += "not a file the document names";
        return false;
    }
    const std::string name = f->second.file.string();
    try {
        *out = readInputBytes(f->second.file);
    } catch (const InputError& e) {
        // "<path>: cannot read: <reason>": the reason, for the line that names the uri.
        const std::string what = e.what();
        const std::string prefix = name + ": cannot read: ";
        ctx->unreadable.emplace(path, what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
        if (err) *err += "cannot read";
        return false;
    }
    return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "vkpath never writes glTF files";
    return false;
}

/// tinygltf's image callback: decode with stb_image to RGBA8. A GLB image's bufferView is checked
/// against its buffer here, before bytes is read (tinygltf 2.7 does not check it).
bool loadImage(tinygltf::Image* image, int index, std::string* err, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    auto* ctx = static_cast<LoadContext*>(user);
    // The first image that fails is reported by readDocument as "<file>: image <i>: <message>".
    auto refuse = [&](const std::string& message) {
        if (ctx->imageError.first.empty()) ctx->imageError = {"image " + std::to_string(index), message};
        *err += "image " + std::to_string(index) + ": " + message;
        return false;
    };
    if (image->bufferView >= 0) {
        const auto& views = ctx->model->bufferViews;
        const auto& view = views.at(static_cast<std::size_t>(image->bufferView));  // tinygltf checked both
        const auto& buffer = ctx->model->buffers.at(static_cast<std::size_t>(view.buffer));
        if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset) {
            return refuse("bufferView " + std::to_string(image->bufferView) + " (bytes " + std::to_string(view.byteOffset) +
                          " + " + std::to_string(view.byteLength) + ") is outside buffer " + std::to_string(view.buffer) +
                          " (" + std::to_string(buffer.data.size()) + " bytes)");
        }
    }
    if (size <= 0) return refuse("no image data");
    // KTX2 (KHR_texture_basisu): no Debian package decodes it. Kept undecoded (no pixels), so a
    // file that also gives a PNG or JPEG fallback loads; a texture that would use it is refused
    // by name (gltf_material.cpp).
    static constexpr unsigned char kKtx2[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    if (size >= 12 && std::equal(kKtx2, kKtx2 + 12, bytes)) {
        ctx->ktx2.insert(index);
        image->width = image->height = 0;
        image->image.clear();
        return true;
    }
    Rgba8Image decoded;
    const std::string problem = decodeLdrImage({bytes, static_cast<std::size_t>(size)}, kMaxImageSide, decoded);
    if (!problem.empty()) return refuse(problem);
    image->width = int(decoded.width);
    image->height = int(decoded.height);
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(decoded.rgba);
    return true;
}

std::uint32_t le32(const std::string& b, std::size_t at) {
    const auto* p = reinterpret_cast<const unsigned char*>(b.data()) + at;
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

/// Check the GLB container (header, JSON chunk, optional BIN chunk) so that tinygltf only sees
/// consistent lengths. Returns the JSON chunk's offset and length.
std::pair<std::size_t, std::size_t> checkGlb(const std::string& bytes, const std::string& file) {
    const std::size_t size = bytes.size();
    if (size < 20) fail(file, "GLB header", "truncated: " + std::to_string(size) + " bytes, a GLB needs at least 20");
    const std::uint32_t version = le32(bytes, 4), length = le32(bytes, 8);
    if (version != 2) fail(file, "GLB header", "container version " + std::to_string(version) + " (vkpath reads 2)");
    if (length != size) {
        fail(file, "GLB header", length > size ? "truncated: the header gives " + std::to_string(length) +
                                                     " bytes, the file has " + std::to_string(size)
                                               : "the header gives " + std::to_string(length) +
                                                     " bytes but the file has " + std::to_string(size));
    }
    const std::uint64_t jsonLength = le32(bytes, 12);
    if (le32(bytes, 16) != 0x4E4F534Au) fail(file, "GLB chunk 0", "the first chunk must be JSON");
    if (jsonLength == 0 || 20 + jsonLength > length) {
        fail(file, "GLB chunk 0", "JSON chunk length " + std::to_string(jsonLength) + " does not fit the file (" +
                                      std::to_string(length) + " bytes)");
    }
    if (jsonLength % 4 != 0) fail(file, "GLB chunk 0", "JSON chunk length " + std::to_string(jsonLength) +
                                                          " is not a multiple of 4");
    const std::uint64_t bin = 20 + jsonLength;
    if (bin < length) {
        if (bin + 8 > length) fail(file, "GLB chunk 1", "truncated chunk header");
        const std::uint64_t binLength = le32(bytes, bin);
        if (le32(bytes, bin + 4) != 0x004E4942u) fail(file, "GLB chunk 1", "the second chunk must be BIN");
        if (bin + 8 + binLength > length) {
            fail(file, "GLB chunk 1", "BIN chunk length " + std::to_string(binLength) + " runs past the end of the file");
        }
        if (binLength == 0 || binLength % 4 != 0) {
            fail(file, "GLB chunk 1", "BIN chunk length " + std::to_string(binLength) + " is not a positive multiple of 4");
        }
    }
    return {20, static_cast<std::size_t>(jsonLength)};
}

/// The GLB bytes with its JSON chunk (at, n) replaced by json (padded with spaces to 4 bytes, as
/// glTF 2.0 sec. 4.4.3.1 asks), the BIN chunk kept as it is.
std::string withJsonChunk(const std::string& bytes, std::size_t at, std::size_t n, std::string json) {
    while (json.size() % 4 != 0) json += ' ';
    const std::string rest = bytes.substr(at + n);
    const std::uint64_t total = 20 + json.size() + rest.size();
    if (total >= (1ull << 32)) throw InputError("GLB too large after rewriting");  // not reached: < 4 GiB input, small growth
    auto le = [](std::uint32_t v) {
        std::string s(4, '\0');
        for (int i = 0; i < 4; ++i) s[std::size_t(i)] = char((v >> (8 * i)) & 0xff);
        return s;
    };
    return bytes.substr(0, 8) + le(std::uint32_t(total)) + le(std::uint32_t(json.size())) + bytes.substr(16, 4) + json + rest;
}

/// Refuse JSON nested deeper than kMaxJsonNesting (tinygltf converts extras and extensions recursively).
void checkNesting(const char* text, std::size_t n, const std::string& file) {
    std::size_t depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < n; ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonNesting) {
                fail(file, "(document)", "JSON nested deeper than " + std::to_string(kMaxJsonNesting) + " levels");
            }
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
}

/// KHR_lights_punctual's lights as tinygltf needs them (it refuses the others with a message that
/// names no light): each an object with a string "type", and a spot with its "spot" object. Only
/// for documents that mention the extension; invalid JSON is left to tinygltf to report.
void checkLights(const char* text, std::size_t n, const std::string& file) {
    const std::string_view view(text, n);
    if (view.find("KHR_lights_punctual") == std::string_view::npos) return;
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(view);
    } catch (const std::exception&) {
        return;
    }
    if (!doc.is_object() || !doc.contains("extensions") || !doc["extensions"].is_object()) return;
    const nlohmann::json& ext = doc["extensions"];
    if (!ext.contains("KHR_lights_punctual")) return;
    const nlohmann::json& khr = ext["KHR_lights_punctual"];
    if (!khr.is_object()) fail(file, "extensions/KHR_lights_punctual", "must be an object");
    if (!khr.contains("lights")) return;
    if (!khr["lights"].is_array()) fail(file, "extensions/KHR_lights_punctual/lights", "must be an array");
    for (std::size_t i = 0; i < khr["lights"].size(); ++i) {
        const nlohmann::json& l = khr["lights"][i];
        const std::string place = "KHR_lights_punctual light " + std::to_string(i);
        if (!l.is_object()) fail(file, place, "must be an object");
        if (!l.contains("type") || !l["type"].is_string()) fail(file, place + "/type", "must be a string (point, spot or directional)");
        if (l["type"] == "spot" && (!l.contains("spot") || !l["spot"].is_object()))
            fail(file, place + "/spot", "a spot light needs its \"spot\" object (the specification requires it)");
    }
}

/// Skins as tinygltf 2.7 needs them: it refuses a skin without "joints" (glTF 1.0 files name
/// "jointNames" instead) and gives no reason. vkpath draws skinned meshes in their bind pose, but
/// the file must still be glTF 2.0. Only for documents that mention skins.
void checkSkins(const char* text, std::size_t n, const std::string& file) {
    const std::string_view view(text, n);
    if (view.find("\"skins\"") == std::string_view::npos) return;
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(view);
    } catch (const std::exception&) {
        return;
    }
    if (!doc.is_object() || !doc.contains("skins") || !doc["skins"].is_array()) return;
    for (std::size_t i = 0; i < doc["skins"].size(); ++i) {
        const nlohmann::json& s = doc["skins"][i];
        const std::string place = "skins/" + std::to_string(i);
        if (!s.is_object()) fail(file, place, "must be an object");
        if (!s.contains("joints") || !s["joints"].is_array() || s["joints"].empty()) {
            fail(file, place + "/joints", std::string("required: the skin's joint nodes") +
                                              (s.contains("jointNames") ? " (\"jointNames\" is glTF 1.0: this is not a glTF 2.0 file)" : ""));
        }
    }
}

/// tinygltf's error text (possibly several lines) as one clause.
std::string oneLine(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    std::string out;
    for (char c : s) out += c == '\n' ? std::string("; ") : std::string(1, c);
    return out;
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

void checkAsset(const Document& doc) {
    const auto& a = doc.model.asset;
    auto major = [](const std::string& v) { return v.substr(0, v.find('.')); };
    if (major(a.version) != "2") fail(doc.file, "asset/version", "\"" + a.version + "\": vkpath reads glTF 2.x");
    if (!a.minVersion.empty() && a.minVersion != "2.0") {
        fail(doc.file, "asset/minVersion", "\"" + a.minVersion + "\": vkpath reads glTF 2.0");
    }
}

}  // namespace

void fail(const std::string& file, const std::string& place, const std::string& message) {
    throw InputError(json::formatError(file, place, message));
}

std::string line(const std::string& file, const std::string& place, const std::string& message) {
    return json::formatError(file, place, message);
}

void warnOnce(Scene& scene, std::string warning) {
    if (std::find(scene.warnings.begin(), scene.warnings.end(), warning) == scene.warnings.end())
        scene.warnings.push_back(std::move(warning));
}

bool extensionImplemented(const std::string& name) {
    static const char* const kImplemented[] = {
        "KHR_materials_emissive_strength", "KHR_materials_specular", "KHR_materials_transmission",
        "KHR_materials_ior", "KHR_texture_transform", "KHR_mesh_quantization", "KHR_lights_punctual", "KHR_materials_unlit",
        "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_materials_clearcoat", "KHR_materials_sheen",
        "KHR_materials_volume",
    };
    return std::any_of(std::begin(kImplemented), std::end(kImplemented), [&](const char* e) { return name == e; });
}

Document readDocument(const std::filesystem::path& path, const AllowedPaths& allowed) {
    Document doc;
    doc.file = path.string();
    const std::string bytes = readInputFile(path);
    if (bytes.size() >= (1ull << 32) - 1) fail(doc.file, "(document)", "4 GiB or larger: not a glTF file vkpath can read");

    std::error_code ec;
    std::filesystem::path base = std::filesystem::absolute(path, ec).parent_path();
    LoadContext ctx;
    ctx.model = &doc.model;
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &ctx});
    loader.SetImageLoader(&loadImage, &ctx);

    std::string err, warn;
    bool ok = false;
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    Rewritten rewritten;
    try {
        if (binary) {
            const auto [at, n] = checkGlb(bytes, doc.file);
            checkNesting(bytes.data() + at, n, doc.file);
            ctx.files = externalFiles(std::string_view(bytes.data() + at, n), doc.file, base, allowed);
            checkLights(bytes.data() + at, n, doc.file);
            checkSkins(bytes.data() + at, n, doc.file);
            const std::string json = rewriteForTinygltf(std::string_view(bytes.data() + at, n), doc.file, rewritten);
            const std::string glb = json.empty() ? std::string() : withJsonChunk(bytes, at, n, json);
            const std::string& in = json.empty() ? bytes : glb;
            ok = loader.LoadBinaryFromMemory(&doc.model, &err, &warn, reinterpret_cast<const unsigned char*>(in.data()),
                                             static_cast<unsigned int>(in.size()), base.string());
        } else {
            checkNesting(bytes.data(), bytes.size(), doc.file);
            ctx.files = externalFiles(bytes, doc.file, base, allowed);
            checkLights(bytes.data(), bytes.size(), doc.file);
            checkSkins(bytes.data(), bytes.size(), doc.file);
            const std::string json = rewriteForTinygltf(bytes, doc.file, rewritten);
            const std::string& in = json.empty() ? bytes : json;
            ok = loader.LoadASCIIFromString(&doc.model, &err, &warn, in.data(), static_cast<unsigned int>(in.size()),
                                            base.string());
        }
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        fail(doc.file, "(document)", "out of memory while reading the file");
    } catch (const std::exception& e) {
        fail(doc.file, "(document)", std::string("invalid glTF: ") + e.what());
    }
    if (!ctx.unreadable.empty()) {
        const auto& [p, why] = *ctx.unreadable.begin();
        const ExternalFile& f = ctx.files.at(p);
        fail(doc.file, f.place, "cannot read " + f.file.string() + ": " + why);
    }
    if (!ctx.imageError.first.empty()) fail(doc.file, ctx.imageError.first, ctx.imageError.second);
    if (!ok) {
        const std::string what = oneLine(err);
        if (startsWith(what, "[json.exception")) fail(doc.file, "(document)", "invalid JSON: " + what);
        fail(doc.file, "(document)", "invalid glTF: " + (what.empty() ? std::string("tinygltf gave no reason") : what));
    }
    // tinygltf only warns about images it could not read (and we saw every read above): refuse them.
    for (std::size_t i = 0; i < doc.model.images.size(); ++i) {
        if (doc.model.images[i].image.empty() && !ctx.ktx2.count(int(i))) {
            fail(doc.file, "image " + std::to_string(i), "no image data (" + oneLine(warn) + ")");
        }
    }
    checkAsset(doc);
    for (const std::string& e : doc.model.extensionsRequired) {
        if (!extensionImplemented(e)) {
            fail(doc.file, "extensionsRequired", "extension " + e + " is required by the file but vkpath does not implement it");
        }
    }
    for (const std::string& e : doc.model.extensionsUsed) {
        if (!extensionImplemented(e)) {
            doc.warnings.push_back(line(doc.file, "extensionsUsed", "extension " + e + " is not supported by vkpath: ignored"));
        }
    }
    decodeMeshopt(doc, rewritten);
    decodeDraco(doc, rewritten);
    return doc;
}

}  // namespace vkp::gltf
