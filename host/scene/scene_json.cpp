// loadSceneJson: the top level, "camera", "render" and "materials" of the JSON scene format
// (scenes/README.md). "objects" is in scene_json_objects.cpp.
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "core/input_file.h"
#include "scene/gltf.h"
#include "scene/json_reader.h"
#include "scene/scene.h"
#include "scene/scene_json_parts.h"
#include "scene/solid_texture.h"
#include "shared/gpu_types.h"

namespace vkp {

namespace {
/// Emitted radiance the kernel's sums can hold (shared/gpu_types.h MAX_SAMPLE_RADIANCE): a larger
/// value would only give samples the kernel drops (issue 15, defect 5).
const json::Range kRadianceRange = json::Range::closed(0.0, 4e15);  // 4e15 = MAX_SAMPLE_RADIANCE, written as a double for messages

}  // namespace

namespace scenejson {

using json::Range;

bool parallelOrZero(glm::dvec3 a, glm::dvec3 b) {
    const double c = glm::length(glm::cross(a, b));
    return !(c > 1e-6 * glm::length(a) * glm::length(b));  // also true for NaN
}

Camera readCamera(const json::Value& v, glm::dvec3& origin) {
    json::Object o = v.object();
    Camera c;
    origin = o.dvec3("lookfrom");
    const glm::dvec3 lookat = o.dvec3("lookat");
    c.lookfrom = glm::vec3(0.0f);
    const bool vupGiven = o.has("vup");
    c.vup = o.vec3("vup", Range::any(), glm::vec3(0.0f, 1.0f, 0.0f));  // +y up unless given
    c.vfov = o.number("vfov", Range::open(0.0, 180.0));
    c.width = o.uint32("width", 1, kMaxImageSide);
    c.height = o.uint32("height", 1, kMaxImageSide);
    c.defocusAngle = o.number("defocus_angle", Range::closedOpen(0.0, 180.0), 0.0f);

    const glm::dvec3 view = lookat - origin;
    const double dist = glm::length(view);
    if (dist == 0.0) o.required("lookat").fail("must differ from lookfrom (the view direction is lookat - lookfrom)");
    c.lookat = glm::vec3(view);
    if (!std::isfinite(static_cast<float>(dist)) || !allFinite(c.lookat)) {
        o.required("lookat").fail("is too far from lookfrom (distance overflows a float)");
    }
    if (c.vup == glm::vec3(0.0f)) o.required("vup").fail("must not be zero");
    if (parallelOrZero(c.vup, glm::vec3(view))) {
        if (!vupGiven) o.fail("the view direction lookat - lookfrom is vertical: give \"vup\" (default [0, 1, 0])");
        o.required("vup").fail("must not be parallel to the view direction lookat - lookfrom");
    }
    c.focusDist = o.number("focus_dist", Range::above(0.0), static_cast<float>(dist));
    o.finish();
    return c;
}

RenderSettings readRender(const json::Value& v) {
    json::Object o = v.object();
    RenderSettings r;
    r.spp = o.uint32("spp", 1, kMaxSpp, 64);
    r.maxDepth = o.uint32("max_depth", 1, kMaxDepth, 50);
    r.rouletteDepth = o.uint32("roulette_depth", 1, kMaxDepth, 3);
    r.background = o.vec3("background", kRadianceRange, glm::vec3(0.0f));
    r.seed = o.uint32("seed", 0, std::numeric_limits<std::uint32_t>::max(), 0);
    o.finish();
    return r;
}

namespace {

/// A colour or a texture at key (required unless def is given): sets colour and returns the texture
/// index (-1: a plain colour).
std::int32_t colourOrTexture(json::Object& o, std::string_view key, const json::Range& range, TextureReader& textures,
                             glm::vec3& colour, std::optional<glm::vec3> def = std::nullopt) {
    if (def && !o.has(key)) {
        colour = *def;
        return -1;
    }
    return textures.colourOrTexture(o.required(key), range, colour);
}

/// With an emission texture, Material::emit holds its bound (scene.h): what emits() and the pick
/// of lights by power see.
void boundEmission(const Scene& scene, Material& m) {
    if (m.emitTexture >= 0)
        m.emit = solidTextureBound(scene.solidTextures, scene.images, scene.textures, std::uint32_t(m.emitTexture));
}

Material readMaterial(const std::string& name, const json::Value& v, const Scene& scene, TextureReader& textures) {
    const Range unit = Range::closed(0.0, 1.0);
    json::Object o = v.object();
    Material m;
    m.name = name;
    const std::string type = o.choice("type", {"lambertian", "metal", "dielectric", "diffuse_light"});
    if (type == "lambertian") {
        m.type = MaterialType::Lambertian;
        m.albedoTexture = colourOrTexture(o, "albedo", unit, textures, m.albedo);
        m.emitTexture = colourOrTexture(o, "emit", kRadianceRange, textures, m.emit, glm::vec3(0.0f));
        boundEmission(scene, m);
        m.twoSided = m.emits();  // an emitting lambertian surface emits from both faces
    } else if (type == "metal") {
        m.type = MaterialType::Metal;
        m.albedoTexture = colourOrTexture(o, "albedo", unit, textures, m.albedo);
        m.fuzz = o.number("fuzz", unit, 0.0f);
    } else if (type == "dielectric") {
        m.type = MaterialType::Dielectric;
        m.albedo = glm::vec3(1.0f);  // clear glass: the book's attenuation of 1
        m.ior = o.number("ior", Range::above(0.0));
        m.fresnelExact = o.choice("fresnel", {"schlick", "exact"}, "schlick") == "exact";
        m.absorption = o.vec3("absorption", Range::closed(0.0, 1e30), glm::vec3(0.0f));
    } else {
        m.type = MaterialType::DiffuseLight;
        m.emitTexture = colourOrTexture(o, "emit", kRadianceRange, textures, m.emit);
        boundEmission(scene, m);
        m.twoSided = o.boolean("two_sided", false);
    }
    o.finish();
    return m;
}

}  // namespace

void readMaterials(const json::Value& v, Scene& scene, std::map<std::string, std::uint32_t>& index, TextureReader& textures) {
    json::Object o = v.object();
    for (const auto& [name, value] : o.members()) {
        const std::uint32_t i = static_cast<std::uint32_t>(scene.materials.size());
        scene.materials.push_back(readMaterial(name, value, scene, textures));
        index.emplace(name, i);
    }
}

}  // namespace scenejson

Scene parseSceneJson(std::string_view text, const std::filesystem::path& file, const SceneJsonOptions& options) {
    const std::string name = file.string();
    const json::Json doc = json::parseDocument(std::string(text), name);
    json::Object top = json::Value(doc, "", name).object();
    // Every top-level key is known up front, so a misplaced key is reported before anything else.
    const auto description = top.optional("description");
    const auto camera = top.optional("camera");
    const auto render = top.optional("render");
    const auto textures = top.optional("textures");    // named textures (scenes/README.md "Textures")
    const auto materials = top.optional("materials");  // optional when no object names one
    const json::Value objects = top.required("objects");
    const auto environment = top.optional("environment");
    top.finish();

    // Everything but the camera, in the frame whose origin is `origin` (file coordinates).
    if (description) description->string();
    // The geometry (render settings, materials, objects) in the frame whose origin is `origin`
    // (file coordinates); what does not depend on the frame is read once, below.
    auto readGeometry = [&](glm::dvec3 origin) {
        Scene scene;
        scene.path = file;
        scene.origin = origin;
        if (render) scene.render = scenejson::readRender(*render);
        std::map<std::string, std::uint32_t> index;
        scenejson::TextureReader textureReader(scene, file, options.allowPaths, textures);
        if (materials) scenejson::readMaterials(*materials, scene, index, textureReader);
        scenejson::readObjects(objects, index, options, textureReader, scene);  // media have colours or textures too
        textureReader.finish();
        return scene;
    };
    Scene scene;
    if (camera) {
        // The camera first: its position is the origin of the frame every coordinate is expressed in.
        glm::dvec3 origin(0.0);
        const Camera cam = scenejson::readCamera(*camera, origin);
        scene = readGeometry(origin);
        scene.camera = cam;
    } else {
        // No camera: the framing camera of a glTF file without one (docs/gltf.md), square unless
        // the options give a size. The geometry is read twice, the second time relative to that
        // camera, so that every coordinate is still rounded to float once, relative to the camera.
        const auto [lo, hi] = sceneBounds(readGeometry(glm::dvec3(0.0)));
        const std::uint32_t width = options.width.value_or(options.height.value_or(kGltfDefaultImageSide));
        const std::uint32_t height = options.height.value_or(width);
        // Framed about the box's centre c (the scene's size decides the framing, not its distance
        // from the file's origin), then placed at c + that camera's position.
        const glm::dvec3 c = (lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z) ? 0.5 * (lo + hi) : glm::dvec3(0.0);
        glm::dvec3 position;
        const Camera cam = framingCamera(name, lo - c, hi - c, width, height, position);
        scene = readGeometry(c + position);
        scene.camera = cam;
    }
    if (environment) {  // directions only: the same in every frame, and the map is read once
        if (scene.render.background != glm::vec3(0.0f))
            environment->fail("cannot be combined with a non-zero render/background (the map replaces it)");
        scene.environment = scenejson::readEnvironment(*environment, file, options.allowPaths);
    }
    return scene;
}

Scene loadSceneJson(const std::filesystem::path& file, const SceneJsonOptions& options) {
    return parseSceneJson(readInputFile(file), file, options);
}

}  // namespace vkp
