// The light list as the device reads it: one GpuLight per sampled object, with the probability
// of picking it in proportion to its emitted power and a Walker/Vose alias table for O(1) picks.
#pragma once
#include <cstdint>
#include <vector>

#include "render/features.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vkp {

/// Emitted power of a sampled shape, up to the factor pi shared by all diffuse emitters:
/// (mean luminance of its emitted radiance) * area * (number of emitting faces: 2 for an emitting
/// lambertian or a two-sided diffuse_light, else 1). 0 for an object that does not emit.
/// Luminance weights: Rec. 709 (0.2126, 0.7152, 0.0722). A triangle under an emissive texture
/// uses the texture's mean over its own UV footprint (EmissionEstimator, emitter_power.h): an
/// estimate that only steers the pick probabilities (variance), never the mean of the image.
/// Packs the scene's textures on every call: for many shapes use lightPowers.
double lightPower(const Scene& scene, std::uint32_t shape);

/// lightPower of every entry of scene.lights, in order (the textures packed once for all).
std::vector<double> lightPowers(const Scene& scene);

/// The weights of the power pick, in the order of its entries: lightPowers(scene), then every
/// punctual light's PunctualLight::power / pi (the same units: lightPower leaves out the factor pi).
std::vector<double> pickWeights(const Scene& scene);

/// Alias table for the discrete distribution `weights` (non-negative, any scale; all zero gives
/// an empty table). threshold[i] in [0,1], alias[i] < n; the probability of i is
/// (threshold[i] + sum over j with alias[j] = i of (1 - threshold[j])) / n = weights[i] / sum.
struct AliasTable {
    std::vector<float> probability;  ///< weights[i] / sum
    std::vector<float> threshold;
    std::vector<std::uint32_t> alias;
};
AliasTable buildAliasTable(const std::vector<double>& weights);

/// The lights buffer (shared/gpu_types.h): one GpuLight per entry of scene.lights, in order
/// (primOfShape maps a shape to its primitive), one per punctual light, then the punctual lights'
/// records (GPU_PUNCTUAL_TEXELS entries each, from entry scene.lights.size() +
/// scene.punctualLights.size() on). Emitters and punctual lights are picked in proportion to
/// their power (pickWeights), or each with the same probability for LightPick::Uniform; objects of
/// power 0 (no emission, or a triangle whose emissive texture is black wherever the kernel can read
/// it) get probability 0 either way. Each punctual record also holds the pick among the punctual
/// lights alone (GpuPunctualLight::q3), by the same rule.
std::vector<gpu::GpuLight> packLights(const Scene& scene, const std::vector<std::uint32_t>& primOfShape,
                                      LightPick pick = LightPick::Power);

/// Number of entries of scene.lights whose material emits (punctual lights not counted).
std::uint32_t emittingLightCount(const Scene& scene);

}  // namespace vkp
