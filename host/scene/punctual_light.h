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
/// with the light's place ("its intensity must be ..."): what the loaders' own checks of the
/// file's values cannot see, that is a negative or non-finite intensity after the unit
/// conversion, a position beyond float range once placed, a direction that is not unit length
/// (spot, directional: a node scaled to nothing). The cone angles are checked by each loader,
/// where it can name the field (0 <= inner <= outer <= pi/2; equal: a hard edge, as Blender writes
/// a spot without blend).
std::string punctualLightProblem(const PunctualLight& l);

}  // namespace vkp
