#include "reference_scene.h"

#include <algorithm>
#include <string>

#include "core/errors.h"

namespace vkp::embree_ref {

namespace {
[[noreturn]] void refuse(const Scene& scene, const std::string& what) {
    throw InputError(scene.path.string() + ": " + what +
                     ": not supported by the Embree reference (lambertian and diffuse_light materials; "
                     "spheres, quads, triangles; emitting quads and triangles; no environment, background "
                     "or punctual light)");
}

const char* typeName(MaterialType t) {
    switch (t) {
        case MaterialType::Lambertian: return "lambertian";
        case MaterialType::Metal: return "metal";
        case MaterialType::Dielectric: return "dielectric";
        case MaterialType::DiffuseLight: return "diffuse_light";
        case MaterialType::Pbr: return "pbr (glTF)";
        case MaterialType::Isotropic: return "isotropic (a medium)";
    }
    return "?";
}

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
}  // namespace

glm::vec3 flatNormal(const Shape& s) {
    glm::vec3 n = s.type == ShapeType::Quad ? glm::cross(s.p1, s.p2) : glm::cross(s.p1 - s.p0, s.p2 - s.p0);
    float len = glm::length(n);
    return len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

void checkSupported(const Scene& scene) {
    if (!scene.meshes.empty()) refuse(scene, "instanced meshes");
    if (scene.environment.hasMap()) refuse(scene, "an environment map");
    if (scene.render.background != glm::vec3(0.0f)) refuse(scene, "a non-black background");
    if (!scene.punctualLights.empty()) refuse(scene, "punctual light " + scene.punctualLights[0].name);
    if (!scene.media.empty()) refuse(scene, "the medium at " + scene.media[0].name);
    for (const Shape& s : scene.shapes) {  // the materials shapes use (a scene may define others)
        const Material& m = scene.materials.at(s.material);
        if (m.type != MaterialType::Lambertian && m.type != MaterialType::DiffuseLight)
            refuse(scene, "material '" + m.name + "' (" + typeName(m.type) + ")");
        if (s.type == ShapeType::Sphere && m.emits()) refuse(scene, "an emitting sphere");
        if (m.albedoTexture >= 0 || m.emitTexture >= 0) refuse(scene, "material '" + m.name + "' (a texture)");
    }
}

LightTable buildLightTable(const Scene& scene) {
    LightTable t;
    t.ofShape.assign(scene.shapes.size(), -1);
    std::vector<double> power;
    for (std::uint32_t i = 0; i < scene.shapes.size(); ++i) {
        const Shape& s = scene.shapes[i];
        const Material& m = scene.materials.at(s.material);
        if (!m.emits() || s.type == ShapeType::Sphere) continue;
        AreaLight l;
        l.shape = i;
        l.area = shapeArea(s);
        l.emit = m.emit;
        l.oneSided = m.type == MaterialType::DiffuseLight && !m.twoSided;
        if (!(l.area > 0.0f)) continue;
        t.ofShape[i] = std::int32_t(t.lights.size());
        t.lights.push_back(l);
        power.push_back(double(luminance(l.emit)) * l.area * (l.oneSided ? 1.0 : 2.0));
    }
    double total = 0.0;
    for (double p : power) total += p;
    if (t.lights.empty() || !(total > 0.0)) throw InputError(scene.path.string() + ": no emitting quad or triangle: nothing to render");
    double acc = 0.0;
    for (std::size_t i = 0; i < t.lights.size(); ++i) {
        t.lights[i].pick = float(power[i] / total);
        acc += power[i] / total;
        t.cdf.push_back(float(acc));
    }
    t.cdf.back() = 1.0f;
    return t;
}

std::uint32_t LightTable::pick(float u) const {
    auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return std::uint32_t(std::min<std::ptrdiff_t>(it - cdf.begin(), std::ptrdiff_t(cdf.size()) - 1));
}

}  // namespace vkp::embree_ref
