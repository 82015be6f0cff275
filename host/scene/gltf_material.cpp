// glTF materials -> MaterialType::Pbr (glTF 2.0 sec. 3.9; KHR_materials_emissive_strength,
// KHR_materials_specular, KHR_materials_transmission, KHR_materials_ior, KHR_materials_unlit,
// KHR_texture_transform),
// textures and samplers (sec. 3.8) -> Scene::textures / Scene::images.
#include <cmath>
#include <cstdio>

#include "scene/gltf_parts.h"

namespace vkp::gltf {

namespace {

using tinygltf::Value;

/// A number as short as "%g" writes it ("0", "1", "inf", "0.5").
std::string fmt(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

std::string rangeMessage(double x, double lo, double hi) {
    if (x >= lo && x <= hi) return "must be finite as a 32-bit float (got " + fmt(x) + ")";
    return "must be in [" + fmt(lo) + ", " + fmt(hi) + "] (got " + fmt(x) + ")";
}

/// The extension object named name in extensions, or null; refuses a non-object.
const Value* extension(const tinygltf::ExtensionMap& extensions, const char* name, const std::string& file,
                       const std::string& place) {
    const auto it = extensions.find(name);
    if (it == extensions.end()) return nullptr;
    if (!it->second.IsObject()) fail(file, place + "/extensions/" + name, "must be an object");
    return &it->second;
}

double number(const Value* object, const char* key, double def, double lo, double hi, const std::string& file,
              const std::string& place) {
    const Value* v = object ? member(*object, key) : nullptr;
    if (!v) return def;
    if (!v->IsNumber()) fail(file, place + "/" + key, "must be a number");
    const double x = v->GetNumberAsDouble();
    if (!(x >= lo && x <= hi) || !std::isfinite(float(x))) {
        fail(file, place + "/" + key, rangeMessage(x, lo, hi));
    }
    return x;
}

/// A numeric array of n entries in [lo, hi] (a factor from the core material or an extension).
template <int N>
glm::vec<N, float> factor(const std::vector<double>& v, double lo, double hi, const std::string& file, const std::string& place) {
    if (v.size() != std::size_t(N)) fail(file, place, "must have " + std::to_string(N) + " numbers (got " + std::to_string(v.size()) + ")");
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) {
        const double x = v[std::size_t(i)];
        if (!(x >= lo && x <= hi) || !std::isfinite(float(x))) {
            fail(file, place + "/" + std::to_string(i), rangeMessage(x, lo, hi));
        }
        out[i] = float(x);
    }
    return out;
}

/// One number of the core material in [lo, hi], as a float.
float scalar(double x, double lo, double hi, const std::string& file, const std::string& place) {
    if (!(x >= lo && x <= hi) || !std::isfinite(float(x))) fail(file, place, rangeMessage(x, lo, hi));
    return float(x);
}

std::vector<double> numbers(const Value* object, const char* key, std::vector<double> def, const std::string& file,
                            const std::string& place) {
    const Value* v = object ? member(*object, key) : nullptr;
    if (!v) return def;
    if (!v->IsArray()) fail(file, place + "/" + key, "must be an array of numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < v->ArrayLen(); ++i) {
        const Value& e = v->Get(int(i));
        if (!e.IsNumber()) fail(file, place + "/" + key + "/" + std::to_string(i), "must be a number");
        out.push_back(e.GetNumberAsDouble());
    }
    return out;
}

TextureWrap wrap(int mode, const std::string& file, const std::string& place) {
    switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
    default: fail(file, place, std::to_string(mode) + " is not a wrap mode (10497, 33071 or 33648)");
    }
}

constexpr double kInf = HUGE_VAL;

}  // namespace

const Value* member(const Value& object, const char* key) {
    if (!object.IsObject() || !object.Has(key)) return nullptr;
    return &object.Get(key);
}

MaterialMapper::MaterialMapper(const Document& doc, Scene& scene, std::optional<std::uint32_t> override)
    : doc_(doc), scene_(scene), override_(override), materialIndex_(doc.model.materials.size() + 1, -1),
      imageIndex_(doc.model.images.size(), -1), textureIndex_(2 * doc.model.textures.size(), -1) {}

std::uint32_t MaterialMapper::material(int m) {
    if (override_) return *override_;
    if (m < -1 || m >= int(doc_.model.materials.size())) {
        fail(doc_.file, "material " + std::to_string(m), "does not exist (the file has " +
                                                           std::to_string(doc_.model.materials.size()) + " materials)");
    }
    const std::size_t slot = m < 0 ? doc_.model.materials.size() : std::size_t(m);
    if (materialIndex_[slot] < 0) {
        materialIndex_[slot] = std::int64_t(scene_.materials.size());
        scene_.materials.push_back(convert(m));
    }
    return std::uint32_t(materialIndex_[slot]);
}

std::uint32_t MaterialMapper::texture(int index, bool srgb, const std::string& place) {
    const tinygltf::Model& model = doc_.model;
    if (index < 0 || std::size_t(index) >= model.textures.size()) {
        fail(doc_.file, place + "/index", "texture " + std::to_string(index) + " does not exist (the file has " +
                                              std::to_string(model.textures.size()) + " textures)");
    }
    std::int64_t& slot = textureIndex_[2 * std::size_t(index) + (srgb ? 1 : 0)];
    if (slot >= 0) return std::uint32_t(slot);
    const tinygltf::Texture& t = model.textures[std::size_t(index)];
    const std::string tplace = "texture " + std::to_string(index);
    if (t.source < 0 && !t.extensions.empty()) {
        // KHR_texture_basisu, EXT_texture_webp, ...: the image only in a form vkpath cannot decode
        // (Debian has no KTX2 / Basis Universal decoder); a file may give a PNG or JPEG "source"
        // as well, which is then used (and the extension is warned about as unsupported).
        std::string names;
        for (const auto& [name, unused] : t.extensions) names += (names.empty() ? "" : ", ") + name;
        fail(doc_.file, tplace, "its image is only given through " + names +
                                    ", which vkpath cannot decode, and it has no PNG or JPEG \"source\" to fall back on");
    }
    if (t.source < 0 || std::size_t(t.source) >= model.images.size()) {
        fail(doc_.file, tplace, "has no image vkpath can read (source " + std::to_string(t.source) + "; the file has " +
                                    std::to_string(model.images.size()) + " images)");
    }
    Texture out;
    out.srgb = srgb;
    if (t.sampler >= 0) {
        if (std::size_t(t.sampler) >= model.samplers.size()) {
            fail(doc_.file, tplace, "sampler " + std::to_string(t.sampler) + " does not exist");
        }
        const tinygltf::Sampler& s = model.samplers[std::size_t(t.sampler)];
        const std::string splace = "sampler " + std::to_string(t.sampler);
        out.wrapS = wrap(s.wrapS, doc_.file, splace + "/wrapS");
        out.wrapT = wrap(s.wrapT, doc_.file, splace + "/wrapT");
        out.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    }
    if (model.images[std::size_t(t.source)].image.empty()) {
        fail(doc_.file, tplace, "image " + std::to_string(t.source) +
                                    " is KTX2 (Basis Universal), which vkpath cannot decode; give a PNG or JPEG \"source\"");
    }
    std::int64_t& image = imageIndex_[std::size_t(t.source)];
    if (image < 0) {
        const tinygltf::Image& src = model.images[std::size_t(t.source)];
        TextureImage img;
        img.name = !src.name.empty() ? src.name : !src.uri.empty() && src.uri.rfind("data:", 0) != 0 ? src.uri
                                                                                                     : "image " + std::to_string(t.source);
        img.width = std::uint32_t(src.width);
        img.height = std::uint32_t(src.height);
        img.rgba8 = src.image;  // RGBA8, decoded by the loader's stb_image callback
        image = std::int64_t(scene_.images.size());
        scene_.images.push_back(std::move(img));
    }
    out.image = std::uint32_t(image);
    slot = std::int64_t(scene_.textures.size());
    scene_.textures.push_back(out);
    return std::uint32_t(slot);
}

TextureRef MaterialMapper::textureRef(int index, int texCoord, const tinygltf::ExtensionMap& extensions, bool srgb,
                                      const std::string& place) {
    TextureRef r;
    if (index < 0) return r;  // absent
    r.texture = std::int32_t(texture(index, srgb, place));
    r.texCoord = std::uint32_t(texCoord < 0 ? 0 : texCoord);
    if (const Value* tt = extension(extensions, "KHR_texture_transform", doc_.file, place)) {
        const std::string tp = place + "/extensions/KHR_texture_transform";
        r.offset = factor<2>(numbers(tt, "offset", {0.0, 0.0}, doc_.file, tp), -kInf, kInf, doc_.file, tp + "/offset");
        r.rotation = float(number(tt, "rotation", 0.0, -kInf, kInf, doc_.file, tp));
        r.scale = factor<2>(numbers(tt, "scale", {1.0, 1.0}, doc_.file, tp), -kInf, kInf, doc_.file, tp + "/scale");
        r.texCoord = std::uint32_t(number(tt, "texCoord", double(r.texCoord), 0, 255, doc_.file, tp));
    }
    if (r.texCoord > 1) {  // glTF 2.0 textureInfo.texCoord: the attribute TEXCOORD_<texCoord>
        scene_.warnings.push_back(line(doc_.file, place, "texture " + std::to_string(index) + " uses TEXCOORD_" +
                                                             std::to_string(r.texCoord) +
                                                             ": vkpath reads TEXCOORD_0 and TEXCOORD_1 only and uses TEXCOORD_0 instead"));
        r.texCoord = 0;
    }
    return r;
}

TextureRef MaterialMapper::textureRef(const tinygltf::TextureInfo& info, bool srgb, const std::string& place) {
    return textureRef(info.index, info.texCoord, info.extensions, srgb, place);
}

TextureRef MaterialMapper::extensionTexture(const Value* object, const char* key, bool srgb, const std::string& place) {
    const Value* info = object ? member(*object, key) : nullptr;
    if (!info) return {};
    const std::string tp = place + "/" + key;
    if (!info->IsObject()) fail(doc_.file, tp, "must be an object");
    const double index = number(info, "index", -1.0, 0.0, 2147483647.0, doc_.file, tp);
    if (index < 0.0) fail(doc_.file, tp, "missing required key \"index\"");
    const int texCoord = int(number(info, "texCoord", 0.0, 0.0, 255.0, doc_.file, tp));
    tinygltf::ExtensionMap extensions;
    if (const Value* e = member(*info, "extensions")) {
        if (!e->IsObject()) fail(doc_.file, tp + "/extensions", "must be an object");
        extensions = e->Get<Value::Object>();
    }
    return textureRef(int(index), texCoord, extensions, srgb, tp);
}

Material MaterialMapper::convert(int m) {
    Material out;
    out.type = MaterialType::Pbr;
    PbrParams& p = out.pbr;
    if (m < 0) {  // glTF 2.0 sec. 3.9.1: the default material (white, metallic 1, roughness 1)
        out.name = "glTF default material";
        out.albedo = glm::vec3(1.0f);
        return out;
    }
    const tinygltf::Material& g = doc_.model.materials[std::size_t(m)];
    const std::string& f = doc_.file;
    const std::string place = "material " + std::to_string(m) + (g.name.empty() ? "" : " (\"" + g.name + "\")");
    out.name = g.name.empty() ? "material " + std::to_string(m) : g.name;
    const auto& pbr = g.pbrMetallicRoughness;
    p.baseColor = factor<4>(pbr.baseColorFactor, 0.0, 1.0, f, place + "/pbrMetallicRoughness/baseColorFactor");
    out.albedo = glm::vec3(p.baseColor);
    p.metallic = scalar(pbr.metallicFactor, 0.0, 1.0, f, place + "/pbrMetallicRoughness/metallicFactor");
    p.roughness = scalar(pbr.roughnessFactor, 0.0, 1.0, f, place + "/pbrMetallicRoughness/roughnessFactor");
    p.baseColorTexture = textureRef(pbr.baseColorTexture, true, place + "/pbrMetallicRoughness/baseColorTexture");
    p.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture, false, place + "/pbrMetallicRoughness/metallicRoughnessTexture");
    p.normalTexture = textureRef(g.normalTexture.index, g.normalTexture.texCoord, g.normalTexture.extensions, false,
                                 place + "/normalTexture");
    p.normalScale = scalar(g.normalTexture.scale, -kInf, kInf, f, place + "/normalTexture/scale");
    p.emissiveTexture = textureRef(g.emissiveTexture, true, place + "/emissiveTexture");
    const glm::vec3 emissive = factor<3>(g.emissiveFactor, 0.0, 1.0, f, place + "/emissiveFactor");

    const std::string ext = place + "/extensions/";
    const Value* strength = extension(g.extensions, "KHR_materials_emissive_strength", f, place);
    out.emit = emissive * float(number(strength, "emissiveStrength", 1.0, 0.0, kInf, f, ext + "KHR_materials_emissive_strength"));
    if (!std::isfinite(out.emit.x) || !std::isfinite(out.emit.y) || !std::isfinite(out.emit.z)) {
        fail(f, ext + "KHR_materials_emissive_strength", "emissiveFactor x emissiveStrength overflows 32-bit floats");
    }
    if (const Value* s = extension(g.extensions, "KHR_materials_specular", f, place)) {
        const std::string sp = ext + "KHR_materials_specular";
        p.specular = float(number(s, "specularFactor", 1.0, 0.0, 1.0, f, sp));
        p.specularColor = factor<3>(numbers(s, "specularColorFactor", {1.0, 1.0, 1.0}, f, sp), 0.0, kInf, f,
                                    sp + "/specularColorFactor");
        p.specularTexture = extensionTexture(s, "specularTexture", false, sp);
        p.specularColorTexture = extensionTexture(s, "specularColorTexture", true, sp);
    }
    if (const Value* t = extension(g.extensions, "KHR_materials_transmission", f, place)) {
        const std::string tp = ext + "KHR_materials_transmission";
        p.transmission = float(number(t, "transmissionFactor", 0.0, 0.0, 1.0, f, tp));
        p.transmissionTexture = extensionTexture(t, "transmissionTexture", false, tp);
    }
    if (const Value* v = extension(g.extensions, "KHR_materials_volume", f, place)) {
        // A volume behind the surface (thicknessFactor > 0; 0 means thin-walled): absorption
        // -ln(attenuationColor) / attenuationDistance. The thickness itself is a rasteriser's
        // stand-in for the distance a path tracer measures (docs/gltf.md).
        const std::string vp = ext + "KHR_materials_volume";
        const double thickness = number(v, "thicknessFactor", 0.0, 0.0, kInf, f, vp);
        const glm::vec3 colour = factor<3>(numbers(v, "attenuationColor", {1.0, 1.0, 1.0}, f, vp), 0.0, 1.0, f, vp + "/attenuationColor");
        const double distance = number(v, "attenuationDistance", kInf, 0.0, kInf, f, vp);
        if (!(distance > 0.0)) fail(f, vp + "/attenuationDistance", "must be > 0 (got " + fmt(float(distance)) + ")");
        if (thickness > 0.0 && std::isfinite(distance))
            for (int c = 0; c < 3; ++c)
                p.volumeAbsorption[c] = colour[c] > 0.0f ? float(-std::log(double(colour[c])) / distance) : 1e30f;
        if (thickness > 0.0 && p.transmissionTexture.valid() && p.volumeAbsorption != glm::vec3(0.0f))
            scene_.warnings.push_back(line(f, vp, "absorption ignored: the transmission is textured (decided per hit, as clear glass)"));
    }
    if (const Value* c = extension(g.extensions, "KHR_materials_clearcoat", f, place)) {
        const std::string cp = ext + "KHR_materials_clearcoat";
        p.clearcoat = float(number(c, "clearcoatFactor", 0.0, 0.0, 1.0, f, cp));
        p.clearcoatTexture = extensionTexture(c, "clearcoatTexture", false, cp);
        p.clearcoatRoughness = float(number(c, "clearcoatRoughnessFactor", 0.0, 0.0, 1.0, f, cp));
        p.clearcoatRoughnessTexture = extensionTexture(c, "clearcoatRoughnessTexture", false, cp);
        p.clearcoatNormalTexture = extensionTexture(c, "clearcoatNormalTexture", false, cp);
        if (const Value* nt = member(*c, "clearcoatNormalTexture"))
            p.clearcoatNormalScale = float(number(nt, "scale", 1.0, -kInf, kInf, f, cp + "/clearcoatNormalTexture"));
    }
    if (const Value* s = extension(g.extensions, "KHR_materials_sheen", f, place)) {
        const std::string sp = ext + "KHR_materials_sheen";
        p.sheenColor = factor<3>(numbers(s, "sheenColorFactor", {0.0, 0.0, 0.0}, f, sp), 0.0, 1.0, f, sp + "/sheenColorFactor");
        p.sheenColorTexture = extensionTexture(s, "sheenColorTexture", true, sp);
        p.sheenRoughness = float(number(s, "sheenRoughnessFactor", 0.0, 0.0, 1.0, f, sp));
        p.sheenRoughnessTexture = extensionTexture(s, "sheenRoughnessTexture", false, sp);
    }
    out.ior = 1.5f;
    if (const Value* i = extension(g.extensions, "KHR_materials_ior", f, place)) {
        out.ior = float(number(i, "ior", 1.5, 0.0, kInf, f, ext + "KHR_materials_ior"));
        if (out.ior != 0.0f && out.ior < 1.0f) fail(f, ext + "KHR_materials_ior/ior", "must be 0 or >= 1 (got " + fmt(out.ior) + ")");
    }
    if (g.alphaMode == "OPAQUE") p.alphaMode = AlphaMode::Opaque;
    else if (g.alphaMode == "MASK") p.alphaMode = AlphaMode::Mask;
    else if (g.alphaMode == "BLEND") p.alphaMode = AlphaMode::Blend;
    else fail(f, place + "/alphaMode", "\"" + g.alphaMode + "\" is not OPAQUE, MASK or BLEND");
    p.alphaCutoff = scalar(g.alphaCutoff, 0.0, kInf, f, place + "/alphaCutoff");
    out.twoSided = g.doubleSided;
    if (extension(g.extensions, "KHR_materials_unlit", f, place)) {
        // Unlit (docs/gltf.md): the surface shows its base colour whatever light falls on it. In a
        // path tracer: an emitter of radiance = base colour (x its texture, through the emissive
        // slot), reflecting nothing; the other properties are ignored, as the extension says.
        p.unlit = true;
        if (p.alphaMode != AlphaMode::Opaque) {
            scene_.warnings.push_back(line(f, place + "/alphaMode", "ignored for an unlit material (it renders as an emitter: docs/gltf.md)"));
        }
        out.emit = glm::vec3(p.baseColor);
        p.emissiveTexture = p.baseColorTexture;
        p.metallic = 0.0f;
        p.specular = 0.0f;
        p.baseColor = glm::vec4(0.0f, 0.0f, 0.0f, p.baseColor.w);  // black where it does not emit
        out.albedo = glm::vec3(0.0f);
        p.baseColorTexture = TextureRef{};
        p.metallicRoughnessTexture = TextureRef{};
        p.normalTexture = TextureRef{};
        p.specularTexture = TextureRef{};
        p.specularColorTexture = TextureRef{};
        p.transmission = 0.0f;
        p.transmissionTexture = TextureRef{};
        p.clearcoat = 0.0f;
        p.sheenColor = glm::vec3(0.0f);
    }
    return out;
}

}  // namespace vkp::gltf

namespace vkp {

glm::vec2 TextureRef::transform(glm::vec2 uv) const {
    const float c = std::cos(rotation), s = std::sin(rotation);
    const glm::vec2 scaled = uv * scale;
    // KHR_texture_transform: T * R * S with R = [cos sin; -sin cos] (row-major, as in its README).
    return glm::vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + offset;
}

}  // namespace vkp
