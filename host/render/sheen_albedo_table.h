// The directional-albedo table of the sheen lobe that KHR_materials_sheen's albedo scaling reads
// (shaders/shared/layers.h: sheenAlbedoFetch, sheenAlbedo).
#pragma once
#include <vector>

#include "shared/layers.h"

namespace vkp {

/// SHEEN_ALBEDO_N x SHEEN_ALBEDO_N texels, x = E_s(mu, roughness) = the integral over the
/// hemisphere of D V cos(theta_l) (layers.h sheenLobe, sheen colour 1), computed by the midpoint
/// rule on a 64 x 64 grid in (cos theta_l, phi_l) refined where the lobe lives (see the .cpp).
/// Deterministic; computed once and cached.
const std::vector<glm::vec4>& sheenAlbedoTable();

}  // namespace vkp
