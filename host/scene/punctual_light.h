// Point, spot and directional lights on the host (PunctualLight, scene/scene.h): the check of their
// parameters shared by the JSON and glTF loaders. Their power is PunctualLight::power.
#pragma once
#include <string>

#include "scene/scene.h"

namespace vkp {

/// Lumens per watt of the conversion between glTF's photometric units (candela for point and spot
/// lights, lux for directional ones) and vkpath's radiometric ones (W/sr, W/m^2): the constant
/// Blender's glTF exporter assumes (docs/gltf.md), so a Blender scene renders as in Cycles.
inline constexpr double kLumensPerWatt = 683.0;

/// Empty if l can be rendered, else what is wrong with it, as the end of a sentence that begins
/// with the light's place ("its intensity must be ..."): a negative or non-finite intensity, a
/// position beyond float range, a direction that is not unit length (spot, directional), cone
/// angles outside 0 <= inner <= outer <= pi/2 (equal: a hard edge, as Blender writes a spot
/// without blend; the falloff then spans 0.001 in cosine inside the outer cone).
std::string punctualLightProblem(const PunctualLight& l);

}  // namespace vkp
