// The albedo table of the GGX specular lobe that the glTF BRDF's base weight reads
// (shaders/shared/microfacet.h: ggxAlbedoFetch, ggxAlbedoLookup, gltfBaseWeight).
#pragma once
#include <vector>

#include "shared/microfacet.h"

namespace vkp {

/// The GGX_ALBEDO_N x GGX_ALBEDO_N texels (A, B, A_avg, B_avg) (microfacet.h), computed with the
/// lobe's own visible-normal sampling (Heitz 2018): for each (mu, roughness) 32 x 32 stratified
/// samples of f cos / pdf = G2 / G1 split by the Schlick weight (1 - v.h)^5; mu = 0 is evaluated at
/// mu = 1e-6 (the limit). Averages: the integral of the interpolated table, so the base's energy
/// balance holds for the table as the kernel reads it. Deterministic; computed once and cached.
const std::vector<glm::vec4>& ggxAlbedoTable();

}  // namespace vkp
