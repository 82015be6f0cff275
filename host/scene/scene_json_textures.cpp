// Textures of the JSON scene format (scenes/README.md "Textures"): "textures" (named ones) and
// every colour that may be a texture (a material's albedo and emit). Kernel side:
// shaders/shared/solid_texture.h.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "core/errors.h"
#include "core/image_io.h"
#include "core/input_file.h"
#include "scene/ldr_image.h"
#include "scene/scene_json_parts.h"
#include "scene/solid_texture.h"

namespace vkp::scenejson {

using json::Range;

TextureReader::TextureReader(Scene& scene, std::filesystem::path sceneFile, AllowedPaths allowed,
                             std::optional<json::Value> named)
    : scene_(scene), sceneFile_(std::move(sceneFile)), allowed_(std::move(allowed)) {
    if (!named) return;
    json::Object o = named->object();
    for (auto& [name, value] : o.members()) named_.emplace(name, value);
}

std::int32_t TextureReader::colourOrTexture(const json::Value& v, const Range& range, glm::vec3& colour) {
    if (v.json().is_array()) {
        colour = v.vec3(range);
        return -1;
    }
    colour = glm::vec3(1.0f);
    return std::int32_t(texture(v, range));
}

std::uint32_t TextureReader::texture(const json::Value& v, const Range& range) {
    if (v.json().is_array()) {  // a colour where a texture may be (a checker's side)
        SolidTexture t;
        t.colour = v.vec3(range);
        return add(t);
    }
    if (v.json().is_string()) return named(v, range);
    json::Object o = v.object();
    SolidTexture t;
    const std::string type = o.choice("type", {"solid", "checker", "image", "noise", "turbulence", "marble"});
    if (type == "solid") {
        t.kind = gpu::STEX_SOLID;
        t.colour = o.vec3("color", range);
    } else if (type == "checker") {
        t.kind = gpu::STEX_CHECKER;
        const float cell = o.number("scale", Range::above(0.0));
        t.scale = 1.0f / cell;  // the kernel keeps 1 / cell size
        if (!std::isfinite(t.scale)) o.required("scale").fail("is too small (1 / scale overflows a float)");
        t.even = texture(o.required("even"), range);
        t.odd = texture(o.required("odd"), range);
        // Checkers on the way from this one to a colour (the kernel follows at most STEX_MAX_DEPTH).
        if (std::max(depth_[t.even], depth_[t.odd]) + 1 > gpu::STEX_MAX_DEPTH)
            o.fail("checkers nest more than " + std::to_string(gpu::STEX_MAX_DEPTH) + " deep");
    } else if (type == "image") {
        t.kind = gpu::STEX_IMAGE;
        t.colour = o.vec3("color", range, glm::vec3(1.0f));
        const bool nearest = o.choice("filter", {"linear", "nearest"}, "linear") == "nearest";
        t.texture = image(o.required("file"), nearest);
    } else {
        t.kind = type == "noise" ? gpu::STEX_NOISE : type == "turbulence" ? gpu::STEX_TURBULENCE : gpu::STEX_MARBLE;
        t.colour = o.vec3("color", range, glm::vec3(1.0f));
        t.scale = o.number("scale", Range::above(0.0), 1.0f);
    }
    o.finish();
    return add(t);
}

std::uint32_t TextureReader::named(const json::Value& v, const Range& range) {
    const std::string name = v.string();
    const auto it = named_.find(name);
    if (it == named_.end()) v.fail("no texture named \"" + name + "\" in /textures");
    // One copy per range its colours were checked against (an albedo's [0, 1], a radiance's).
    const auto key = std::make_pair(name, std::make_pair(range.lo, range.hi));
    if (const auto done = done_.find(key); done != done_.end()) return done->second;
    if (resolving_.count(name)) v.fail("texture \"" + name + "\" refers to itself");
    resolving_.insert(name);
    const std::uint32_t t = texture(it->second, range);
    resolving_.erase(name);
    done_.emplace(key, t);
    return t;
}

void TextureReader::finish() {
    // A texture no material names is still read, so that its mistakes are found; what it added
    // is dropped again (nothing refers to it).
    const std::size_t textures = scene_.solidTextures.size(), images = scene_.images.size(), samplers = scene_.textures.size();
    std::set<std::string> used;
    for (const auto& [key, index] : done_) used.insert(key.first);
    for (const auto& [name, value] : named_)
        if (!used.count(name)) (void)texture(value, Range::closed(0.0, 4e15));  // any colour a texture may hold
    scene_.solidTextures.resize(textures);
    scene_.images.resize(images);
    scene_.textures.resize(samplers);
}

std::uint32_t TextureReader::add(SolidTexture t) {
    depth_.push_back(t.kind == gpu::STEX_CHECKER ? std::max(depth_[t.even], depth_[t.odd]) + 1 : 0u);
    scene_.solidTextures.push_back(std::move(t));
    return std::uint32_t(scene_.solidTextures.size() - 1);
}

std::uint32_t TextureReader::image(const json::Value& fileValue, bool nearest) {
    const std::string name = fileValue.string();
    if (name.empty()) fileValue.fail("must not be empty");
    std::string problem;
    const std::filesystem::path resolved = resolveReference(sceneFile_.parent_path(), name, allowed_, problem);
    if (!problem.empty()) fileValue.fail(problem);
    const auto key = std::make_pair(resolved.string(), nearest);
    if (const auto it = images_.find(key); it != images_.end()) return it->second;

    const std::filesystem::path path(name);
    const std::filesystem::path file = path.is_absolute() ? path : sceneFile_.parent_path() / path;  // as messages name it
    TextureImage img;
    img.name = name;
    Texture tex;
    tex.wrapS = TextureWrap::Repeat;       // around the sphere: the seam at u = 0 blends both edges
    tex.wrapT = TextureWrap::ClampToEdge;  // the poles: no blending of the top row with the bottom
    tex.nearest = nearest;
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    try {
        if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") {
            const std::vector<unsigned char> bytes = readInputBytes(file);
            Rgba8Image decoded;
            const std::string bad = decodeLdrImage(bytes, kMaxImageSide, decoded);
            if (!bad.empty()) throw InputError(file.string() + ": " + bad);
            img.width = decoded.width;
            img.height = decoded.height;
            img.rgba8 = std::move(decoded.rgba);
            tex.srgb = true;  // colour data, sRGB-encoded
        } else if (ext == ".hdr" || ext == ".exr" || ext == ".pfm") {
            const Image linear = readImage(file);
            if (linear.empty()) throw InputError(file.string() + ": the image has no pixels");
            if (linear.width > kMaxImageSide || linear.height > kMaxImageSide)
                throw InputError(file.string() + ": " + std::to_string(linear.width) + "x" + std::to_string(linear.height) +
                                 " pixels: each side must be in [1, " + std::to_string(kMaxImageSide) + "]");
            img.width = std::uint32_t(linear.width);
            img.height = std::uint32_t(linear.height);
            img.rgb9e5 = true;
            img.rgba8.resize(std::size_t(img.width) * img.height * 4);
            for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i) {
                const glm::vec3 c(linear.rgb[3 * i], linear.rgb[3 * i + 1], linear.rgb[3 * i + 2]);
                for (int k = 0; k < 3; ++k)
                    if (!std::isfinite(c[k]) || c[k] < 0.0f)
                        throw InputError(file.string() + ": pixel " + std::to_string(i % img.width) + "," +
                                         std::to_string(i / img.width) + " is negative, NaN or infinite");
                const std::uint32_t p = packRgb9e5(c);
                for (int k = 0; k < 4; ++k) img.rgba8[4 * i + std::size_t(k)] = std::uint8_t(p >> (8 * k));
            }
        } else {
            throw InputError(file.string() + ": unknown image extension '" + ext +
                             "' (textures: .png .jpg .jpeg, or .hdr .exr .pfm for linear high dynamic range)");
        }
    } catch (const InputError& e) {
        fileValue.fail(e.what());
    }
    tex.image = std::uint32_t(scene_.images.size());
    scene_.images.push_back(std::move(img));
    scene_.textures.push_back(tex);
    const std::uint32_t t = std::uint32_t(scene_.textures.size() - 1);
    images_.emplace(key, t);
    return t;
}

}  // namespace vkp::scenejson
