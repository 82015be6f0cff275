// KHR_lights_punctual: the point, spot and directional lights of a glTF file, placed by the nodes
// that carry them (https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_lights_punctual).
// Photometric units in the file (candela, lux), radiometric in vkpath: divided by kLumensPerWatt.
#include <cmath>

#include "scene/gltf_parts.h"
#include "scene/punctual_light.h"

namespace vkp::gltf {

namespace {

std::string lightPlace(const tinygltf::Model& model, std::size_t light) {
    const std::string& name = model.lights[light].name;
    return "KHR_lights_punctual light " + std::to_string(light) + (name.empty() ? "" : " (\"" + name + "\")");
}

/// The light as the file describes it, converted; its place for messages.
PunctualLight convert(const Document& doc, std::size_t index, const std::string& place) {
    const tinygltf::Light& in = doc.model.lights[index];
    PunctualLight l;
    if (in.type == "point") {
        l.kind = PunctualLight::Kind::Point;
    } else if (in.type == "spot") {
        l.kind = PunctualLight::Kind::Spot;
    } else if (in.type == "directional") {
        l.kind = PunctualLight::Kind::Directional;
    } else {
        fail(doc.file, place + "/type", "\"" + in.type + "\" is not a light type (point, spot or directional)");
    }
    glm::dvec3 color(1.0);
    if (!in.color.empty()) {
        if (in.color.size() != 3) fail(doc.file, place + "/color", "must have 3 numbers (got " + std::to_string(in.color.size()) + ")");
        for (int c = 0; c < 3; ++c) {
            if (!(in.color[std::size_t(c)] >= 0.0) || !std::isfinite(in.color[std::size_t(c)]))
                fail(doc.file, place + "/color/" + std::to_string(c), "must be finite and >= 0");
            color[c] = in.color[std::size_t(c)];
        }
    }
    if (!(in.intensity >= 0.0) || !std::isfinite(in.intensity)) fail(doc.file, place + "/intensity", "must be finite and >= 0");
    // candela -> W/sr (point, spot), lux -> W/m^2 (directional).
    l.intensity = glm::vec3(color * (in.intensity / kLumensPerWatt));
    if (l.kind == PunctualLight::Kind::Spot) {
        const double inner = in.spot.innerConeAngle, outer = in.spot.outerConeAngle;
        constexpr double halfPi = 1.57079632679489662;
        if (!(outer > 0.0 && outer <= halfPi * (1.0 + 1e-7)))
            fail(doc.file, place + "/spot/outerConeAngle", "must be in (0, pi/2] (got " + std::to_string(outer) + ")");
        // The specification asks for inner < outer; Blender's exporter writes inner = outer for a
        // spot without blend, so equal angles are accepted (a hard edge).
        if (!(inner >= 0.0 && inner <= outer))
            fail(doc.file, place + "/spot/innerConeAngle",
                 "must be >= 0 and at most outerConeAngle (got " + std::to_string(inner) + ")");
        l.innerCone = float(inner);
        l.outerCone = float(std::min(outer, halfPi));
    }
    return l;
}

}  // namespace

void appendLights(const Document& doc, const Instances& inst, Scene& scene) {
    const tinygltf::Model& model = doc.model;
    bool rangeWarned = false;
    for (const LightInstance& li : inst.lights) {
        const std::string place = lightPlace(model, li.light);
        PunctualLight l = convert(doc, li.light, place);
        l.name = place + " of " + nodePlace(doc, li.node);
        l.position = glm::vec3(glm::dvec3(li.world[3]));
        const glm::dvec3 axis = glm::dmat3(li.world) * glm::dvec3(0.0, 0.0, -1.0);  // a light shines along its node's -Z
        const double len = glm::length(axis);
        l.direction = (len > 0.0 && std::isfinite(len)) ? glm::vec3(axis / len) : glm::vec3(0.0f);
        if (const std::string problem = punctualLightProblem(l); !problem.empty()) fail(doc.file, l.name, problem);
        if (model.lights[li.light].range > 0.0 && !rangeWarned) {  // once per file, naming its first light with a range
            warnOnce(scene, line(doc.file, place, "range ignored: vkpath's lights fall off with the inverse square of the distance only (docs/gltf.md)"));
            rangeWarned = true;  // warnOnce: also when a JSON scene includes the file several times
        }
        scene.punctualLights.push_back(std::move(l));
    }
}

}  // namespace vkp::gltf
