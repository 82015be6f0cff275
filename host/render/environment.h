// The environment light as the device reads it: the map's radiance texels, its 2D sampling
// distribution (shaders/shared/distribution.h, environment_map.h) and the probability with which
// next-event estimation picks it instead of the scene's emitters.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "render/features.h"
#include "scene/scene.h"

namespace vkp {

/// True when escaping rays see radiance: a map, or a non-zero constant background.
bool hasEnvironmentLight(const Scene& scene);

/// Sampling weights of a w x h equirectangular map (row-major, row 0 = top): Rec. 709 luminance
/// times the mean of sin(theta) over the texel's row, (cos theta0 - cos theta1) / (theta1 - theta0),
/// which is > 0 for every row (also at the poles), so a texel with radiance has weight > 0.
std::vector<double> envSamplingWeights(const Image& image);

/// Device data of the map: one vec4 (rgb radiance, 0) per texel, row-major, and the distribution
/// table. Without a map: one zero texel and a 1-cell table (valid bindings that are never read).
struct EnvTables {
    std::vector<glm::vec4> texels;
    std::vector<float> distribution;
    std::uint32_t width = 0, height = 0;  ///< 0 without a map
};
EnvTables packEnvironment(const Scene& scene);

/// Probability that next-event estimation samples the environment rather than an emitter:
/// 0 without environment light, 1 without emitters, else the share of the environment's estimated
/// power, clamped to [0.1, 0.9] so that neither kind starves when the estimate is poor. Power
/// estimates (pbrt-v4's Phi, up to the common factor pi): environment 4 pi r^2 Lavg (r = radius of
/// the scene's bounding sphere, Lavg = solid-angle mean of the luminance), emitters the sum of
/// pickWeights (light_table.h: emitting surfaces and punctual lights). With LightPick::Uniform the
/// environment is one more light among the n emitters: 1 / (n + 1).
double envPickProbability(const Scene& scene, LightPick pick = LightPick::Power);

/// Radius of the bounding sphere of the scene's geometry (half the diagonal of its box; at least
/// 1e-6), 1 for a scene without shapes: the size of the environment and of directional lights in
/// power estimates.
double sceneRadius(const Scene& scene);

/// Solid-angle mean of the luminance of the environment (map or constant background).
double envMeanLuminance(const Scene& scene);

}  // namespace vkp
