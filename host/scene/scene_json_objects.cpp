// The "objects" section of the JSON scene format (scenes/README.md): spheres, quads, boxes,
// triangles, included glTF files and punctual lights, moved to world space by their "transform",
// and the light list.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <vector>

#include "core/errors.h"
#include "scene/gltf.h"
#include "scene/json_reader.h"
#include "scene/punctual_light.h"
#include "scene/scene_json_parts.h"
#include "scene/transform.h"

namespace vkp::scenejson {

namespace {

/// A shape as the file gives it, in double precision (Shape's fields, before the transform and the
/// move to the camera-relative frame).
struct LocalShape {
    ShapeType type = ShapeType::Sphere;
    glm::dvec3 p0{0.0}, p1{0.0}, p2{0.0};
    double radius = 0.0;
};

LocalShape makeQuad(glm::dvec3 q, glm::dvec3 u, glm::dvec3 v) { return {ShapeType::Quad, q, u, v, 0.0}; }

/// The six faces of an axis-aligned box, as box() of "The Next Week" (chapter "Instances") builds them, in its
/// order (front z=max, right x=max, back z=min, left x=min, top y=max, bottom y=min). Each face's
/// u x v points out of the box.
std::vector<LocalShape> boxFaces(glm::dvec3 a, glm::dvec3 b) {
    const glm::dvec3 dx(b.x - a.x, 0.0, 0.0), dy(0.0, b.y - a.y, 0.0), dz(0.0, 0.0, b.z - a.z);
    return {
        makeQuad({a.x, a.y, b.z}, dx, dy),   // front
        makeQuad({b.x, a.y, b.z}, -dz, dy),  // right
        makeQuad({b.x, a.y, a.z}, -dx, dy),  // back
        makeQuad({a.x, a.y, a.z}, dz, dy),   // left
        makeQuad({a.x, b.y, b.z}, dx, -dz),  // top
        makeQuad({a.x, a.y, a.z}, dx, dz),   // bottom
    };
}

}  // namespace

std::pair<glm::dvec3, glm::dvec3> readBoxCorners(json::Object& o) {
    const glm::dvec3 lo = o.dvec3("min");
    const json::Value maxValue = o.required("max");
    const glm::dvec3 hi = maxValue.dvec3();
    for (std::size_t i = 0; i < 3; ++i) {
        const int k = static_cast<int>(i);
        if (!(hi[k] > lo[k])) {
            maxValue.element(i).fail("must be > min[" + std::to_string(i) + "] (got " +
                                     json::describeValue(maxValue.json()[i]) + " <= " +
                                     json::describeValue(o.required("min").json()[i]) + ")");
        }
    }
    return {lo, hi};
}

namespace {

/// Apply the object's transform to one shape (spheres: centre moves, radius scales) in double,
/// then express its points relative to origin (the camera) and round to float: the only place
/// where a JSON object's coordinates become float (docs/design.md "Camera-relative space").
Shape transformed(const LocalShape& s, const ObjectTransform& xf, glm::dvec3 origin) {
    Shape out;
    out.type = s.type;
    auto point = [&](glm::dvec3 p) { return glm::vec3(xf.map.point(p) - origin); };
    switch (s.type) {
    case ShapeType::Sphere:
        out.p0 = point(s.p0);
        out.radius = static_cast<float>(s.radius * xf.uniformScale);
        break;
    case ShapeType::Quad:  // a mirror keeps u, v as mapped: the front face u x v turns over
        out.p0 = point(s.p0);
        out.p1 = glm::vec3(xf.map.vector(s.p1));
        out.p2 = glm::vec3(xf.map.vector(s.p2));
        break;
    case ShapeType::Triangle:
        out.p0 = point(s.p0);
        out.p1 = point(s.p1);
        out.p2 = point(s.p2);
        break;
    }
    return out;
}

/// "motion": {"translate": [x, y, z]} (motion blur, "Ray Tracing: The Next Week" sec. 2): the
/// object's displacement over the shutter interval, in world units, after its transform: at time
/// t in [0, 1) it is where its transform puts it, moved by t (x, y, z).
glm::dvec3 readMotion(const json::Value& v) {
    json::Object o = v.object();
    const glm::dvec3 translate = o.dvec3("translate");
    o.finish();
    return translate;
}

/// A shape's velocity (Shape::velocity) as a float, refused at `where` when it or the shape at
/// the end of the shutter interval does not fit 32-bit floats relative to the camera.
glm::vec3 checkedVelocity(const Shape& w, glm::dvec3 velocity, const json::Value& where, const std::string& type) {
    const glm::vec3 v(velocity);
    if (!allFinite(v)) where.fail("the " + type + "'s motion does not fit 32-bit floats (overflow)");
    Shape end = w;
    end.velocity = v;
    end = shapeAt(end, 1.0f);
    const double reach = allFinite(end.p0) && allFinite(end.p1) && allFinite(end.p2) ? shapeReach(end) : HUGE_VAL;
    if (!(reach <= kMaxSceneCoordinate)) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", reach);
        where.fail("moves the " + type + " to " + text + " from the camera: its coordinates overflow 32-bit floats " +
                   "(its bounding box must lie within +-1e38 of the camera at every time)");
    }
    return v;
}

/// One entry of "objects": its shapes in world space (a box gives six quads).
std::vector<Shape> readObject(const json::Value& v, const std::map<std::string, std::uint32_t>& index,
                              const Scene& scene) {
    json::Object o = v.object();
    const std::string type =
        o.choice("type", {"sphere", "quad", "box", "triangle", "gltf", "point_light", "spot_light", "directional_light",
                          "constant_medium"});

    const json::Value matValue = o.required("material");
    const std::string matName = matValue.string();
    const auto found = index.find(matName);
    if (found == index.end()) matValue.fail("unknown material \"" + matName + "\" (not a key of /materials)");
    const std::uint32_t material = found->second;
    const bool emits = scene.materials[material].emits();

    const auto sampleValue = o.optional("sample");
    const bool sample = sampleValue ? sampleValue->boolean() : false;
    if (sampleValue && !sample && emits) {
        sampleValue->fail("must not be false: an object whose material emits is always sampled (it is a light)");
    }

    ObjectTransform xf;
    if (auto t = o.optional("transform")) xf = readTransform(*t);
    // Motion blur: the displacement over the shutter interval, in world units (after the transform).
    glm::dvec3 velocity(0.0);
    std::optional<json::Value> center1Value;

    std::vector<LocalShape> local;
    if (type == "sphere") {
        LocalShape s;
        s.type = ShapeType::Sphere;
        s.p0 = o.dvec3("center");
        s.radius = o.number("radius", json::Range::above(0.0));
        if (!xf.nonUniformAt.empty()) {
            throw InputError(json::formatError(
                v.file(), xf.nonUniformAt, "a sphere cannot be scaled non-uniformly (|x|, |y|, |z| must be equal)"));
        }
        // The book's moving sphere: its centre goes from center (t = 0) to center1 (t = 1), both
        // through the transform; a "motion" adds its translation to that.
        center1Value = o.optional("center1");
        if (center1Value) velocity += xf.map.point(center1Value->dvec3()) - xf.map.point(s.p0);
        local.push_back(s);
    } else if (type == "quad") {
        LocalShape s = makeQuad(o.dvec3("Q"), o.dvec3("u"), o.dvec3("v"));
        if (s.p1 == glm::dvec3(0.0)) o.required("u").fail("must not be zero");
        if (parallelOrZero(s.p1, s.p2)) o.required("v").fail("must not be zero or parallel to u (u x v = 0)");
        local.push_back(s);
    } else if (type == "box") {
        const auto [lo, hi] = readBoxCorners(o);
        local = boxFaces(lo, hi);
    } else {
        LocalShape s;
        s.type = ShapeType::Triangle;
        s.p0 = o.dvec3("v0");
        s.p1 = o.dvec3("v1");
        s.p2 = o.dvec3("v2");
        local.push_back(s);
    }
    const std::optional<json::Value> motionValue = o.optional("motion");
    if (motionValue) velocity += readMotion(*motionValue);
    o.finish();

    const bool sampled = emits || sample;
    std::vector<Shape> out;
    for (const LocalShape& s : local) {
        Shape w = transformed(s, xf, scene.origin);
        w.material = material;
        w.sampled = sampled;
        if (!allFinite(w.p0) || !allFinite(w.p1) || !allFinite(w.p2) || !std::isfinite(w.radius) ||
            (w.type == ShapeType::Sphere && !(w.radius > 0.0f))) {
            v.fail("the transformed " + type + " does not fit 32-bit floats relative to the camera (overflow or underflow)");
        }
        if (const double reach = shapeReach(w); !(reach <= kMaxSceneCoordinate)) {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g", reach);
            v.fail("the " + type + " reaches " + text + " from the camera: its coordinates overflow 32-bit floats " +
                   "(its bounding box must lie within +-1e38 of the camera, float's largest value being 3.4e38)");
        }
        if (w.type == ShapeType::Quad && parallelOrZero(w.p1, w.p2)) {
            o.required("transform").fail("makes the " + type + " degenerate (u x v = 0 in 32-bit floats)");
        }
        if (motionValue || center1Value) w.velocity = checkedVelocity(w, velocity, motionValue ? *motionValue : *center1Value, type);
        // Zero-area triangles may exist (never hit), but a light of zero area has no pdf.
        if (w.type == ShapeType::Triangle && sampled && parallelOrZero(w.p1 - w.p0, w.p2 - w.p0)) {
            if (sample) sampleValue->fail("a zero-area triangle cannot be sampled");
            matValue.fail("a zero-area triangle cannot have an emitting material (\"" + matName +
                          "\" emits): it would be a light of zero area");
        }
        out.push_back(w);
    }
    return out;
}

/// An entry's "type" when it is an object with a string "type", else "" (its reader reports it).
std::string objectType(const json::Value& v) {
    const json::Json& j = v.json();
    if (!j.is_object()) return {};
    const auto t = j.find("type");
    return t != j.end() && t->is_string() ? t->get<std::string>() : std::string();
}

bool isPunctualObject(const json::Value& v) {
    const std::string type = objectType(v);
    return type == "point_light" || type == "spot_light" || type == "directional_light";
}

bool isGltfObject(const json::Value& v) { return objectType(v) == "gltf"; }

/// {"type": "point_light" | "spot_light" | "directional_light", ...} (scenes/README.md "Lights"):
/// a punctual light in radiometric units, moved by its "transform" and made camera-relative.
PunctualLight readPunctual(const json::Value& v, const Scene& scene) {
    json::Object o = v.object();
    const std::string type = o.choice("type", {"point_light", "spot_light", "directional_light"});
    PunctualLight l;
    l.kind = type == "point_light"  ? PunctualLight::Kind::Point
             : type == "spot_light" ? PunctualLight::Kind::Spot
                                    : PunctualLight::Kind::Directional;
    l.name = "the light at " + v.pointer();
    if (auto m = o.optional("motion"))
        m->fail("a " + type + " cannot move: motion blur moves shapes (spheres, quads, boxes, triangles, glTF files), not punctual lights");
    ObjectTransform xf;
    if (auto t = o.optional("transform")) xf = readTransform(*t);
    const double pi = 3.14159265358979323846;
    if (l.kind != PunctualLight::Kind::Point) {  // a spot's axis, the way a directional light travels
        const json::Value dir = o.required("direction");
        const glm::dvec3 d = xf.map.vector(dir.dvec3());
        if (!(glm::length(d) > 0.0)) dir.fail("must not be zero");
        l.direction = glm::vec3(glm::normalize(d));
    }
    if (l.kind == PunctualLight::Kind::Directional) {
        l.intensity = o.vec3("irradiance", json::Range::atLeast(0.0));
    } else {
        l.position = glm::vec3(xf.map.point(o.dvec3("position")) - scene.origin);
        const auto intensity = o.optional("intensity");
        const auto power = o.optional("power");
        if (intensity && power) power->fail("give either intensity (W/sr) or power (W), not both");
        if (!intensity && !power) o.fail("a " + type + " needs \"intensity\" (W/sr) or \"power\" (W)");
        // Power as Blender states it: a spot of power P is as bright as a point light of power P.
        l.intensity = intensity ? intensity->vec3(json::Range::atLeast(0.0))
                                : glm::vec3(glm::dvec3(power->vec3(json::Range::atLeast(0.0))) / (4.0 * pi));
    }
    if (l.kind == PunctualLight::Kind::Spot) {
        const float outer = o.number("outer_angle", json::Range::closed(0.0, 90.0), 45.0f);
        if (!(outer > 0.0f)) o.required("outer_angle").fail("must be > 0");
        const float inner = o.number("inner_angle", json::Range::closed(0.0, 90.0), 0.0f);
        if (!(inner <= outer)) o.required("inner_angle").fail("must be at most outer_angle (" + std::to_string(outer) + ")");
        l.outerCone = float(double(outer) * pi / 180.0);
        l.innerCone = float(double(inner) * pi / 180.0);
    }
    o.finish();
    if (const std::string problem = punctualLightProblem(l); !problem.empty()) v.fail(problem);
    return l;
}

/// The include's file, resolved against the JSON file's folder.
std::filesystem::path includePath(const std::string& name, const Scene& scene) {
    std::filesystem::path file(name);
    if (file.is_relative()) file = scene.path.parent_path() / file;
    return file;
}

/// {"type": "gltf", "file": "...", "transform": [...], "material": "name"}: the triangles of a
/// glTF file's default scene, file relative to the JSON file, placed by transform (after the
/// file's own node transforms); "material" replaces every material of the file. A problem inside
/// the file is one line naming the JSON file and object, then the glTF file and its part.
void readGltfObject(const json::Value& v, const std::map<std::string, std::uint32_t>& index,
                    const AllowedPaths& allowed, Scene& scene, GltfIncludes& includes) {
    json::Object o = v.object();
    o.choice("type", {"gltf"});
    const json::Value fileValue = o.required("file");
    const std::string name = fileValue.string();
    if (name.empty()) fileValue.fail("must not be empty");
    std::string problem;
    (void)resolveReference(scene.path.parent_path(), name, allowed, problem);
    if (!problem.empty()) fileValue.fail(problem);
    const std::filesystem::path file = includePath(name, scene);  // as the messages name it
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        fileValue.fail("cannot read " + file.string() + ": " +
                       (std::filesystem::exists(file, ec) ? "not a regular file" : "no such file"));
    }
    GltfInclude include;
    if (auto t = o.optional("transform")) {
        const Affine a = readTransform(*t).map;
        include.transform = glm::dmat4(a.linear);
        include.transform[3] = glm::dvec4(a.offset, 1.0);
    }
    // Into the camera-relative frame, in double, before the file's vertices become float.
    include.transform[3] -= glm::dvec4(scene.origin, 0.0);
    if (auto m = o.optional("material")) {
        const std::string matName = m->string();
        const auto found = index.find(matName);
        if (found == index.end()) m->fail("unknown material \"" + matName + "\" (not a key of /materials)");
        include.material = found->second;
    }
    const std::optional<json::Value> motionValue = o.optional("motion");
    if (motionValue) include.velocity = readMotion(*motionValue);
    o.finish();
    const std::size_t firstShape = scene.shapes.size(), firstPunctual = scene.punctualLights.size();
    try {
        includes.append(file, include);
    } catch (const InputError& e) {
        v.fail(e.what());
    }
    if (!motionValue) return;
    if (scene.punctualLights.size() != firstPunctual)
        motionValue->fail("the glTF file has punctual lights (KHR_lights_punctual), which cannot move: motion blur moves shapes only");
    for (std::size_t i = firstShape; i < scene.shapes.size(); ++i)
        scene.shapes[i].velocity = checkedVelocity(scene.shapes[i], include.velocity, *motionValue, "glTF file's triangle");
}

/// Announce every include whose file and material resolve (the others fail when read), so that
/// the includes know how often each file is placed before the first is.
void expectIncludes(const json::Value& v, const std::map<std::string, std::uint32_t>& index, const Scene& scene,
                    GltfIncludes& includes) {
    for (const json::Value& item : v.array()) {
        if (!isGltfObject(item)) continue;
        const json::Json& j = item.json();
        const auto f = j.find("file");
        if (f == j.end() || !f->is_string() || f->get<std::string>().empty()) continue;
        GltfInclude include;
        if (const auto m = j.find("material"); m != j.end()) {
            if (!m->is_string()) continue;
            const auto found = index.find(m->get<std::string>());
            if (found == index.end()) continue;
            include.material = found->second;
        }
        if (j.contains("motion")) {  // as readMotion reads it; a bad one fails when the include is read
            try {
                include.velocity = readMotion(item.object().required("motion"));
            } catch (const InputError&) {
                continue;
            }
        }
        includes.expect(includePath(f->get<std::string>(), scene), include);
    }
}

}  // namespace

void readObjects(const json::Value& v, const std::map<std::string, std::uint32_t>& index,
                 const SceneJsonOptions& options, TextureReader& textures, Scene& scene) {
    GltfIncludes includes(scene, options.instancing, options.allowPaths);
    expectIncludes(v, index, scene, includes);
    for (const json::Value& item : v.array()) {
        if (isGltfObject(item)) {
            readGltfObject(item, index, options.allowPaths, scene, includes);
            continue;
        }
        if (isPunctualObject(item)) {
            scene.punctualLights.push_back(readPunctual(item, scene));
            continue;
        }
        if (objectType(item) == "constant_medium") {
            scene.media.push_back(readMedium(item, textures, scene));
            continue;
        }
        for (const Shape& s : readObject(item, index, scene)) {
            if (s.sampled) scene.lights.push_back(static_cast<std::uint32_t>(scene.shapes.size()));
            scene.shapes.push_back(s);
        }
    }
}

}  // namespace vkp::scenejson
