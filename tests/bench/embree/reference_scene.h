// What the Embree reference tracer renders (docs/performance.md "The Embree reference"): the scene
// as vkpath loads it, checked for the subset the reference supports, with its emitters as a table
// picked in proportion to power. Independent of vkpath's kernel code: only the loader is shared.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkp::embree_ref {

/// One emitting quad or triangle (Scene::shapes index `shape`), for next-event estimation.
struct AreaLight {
    std::uint32_t shape = 0;
    float area = 0.0f;       ///< world units^2
    glm::vec3 emit{0.0f};    ///< radiance (linear RGB)
    bool oneSided = true;    ///< diffuse_light without two_sided: emits from its front (u x v, or counter-clockwise) only
    float pick = 0.0f;       ///< probability of picking it (power / total power)
};

/// The lights of a scene and their pick by power (Rec. 709 luminance of the emission x area x
/// emitting faces; an emitting lambertian emits from both faces, as in vkpath).
struct LightTable {
    std::vector<AreaLight> lights;
    std::vector<float> cdf;               ///< cdf[i] = pick of lights 0..i; cdf.back() = 1
    std::vector<std::int32_t> ofShape;    ///< Scene::shapes index -> index into lights, or -1
    /// The light for u in [0,1) (binary search of cdf). Requires lights not empty.
    std::uint32_t pick(float u) const;
};

/// Throws InputError with one line "<scene>: <what>: not supported by the Embree reference (...)"
/// unless every shape is a sphere, quad or triangle (no instanced meshes), every material a shape uses is
/// lambertian or diffuse_light, no sphere emits, and there is no environment
/// map, non-black background or punctual light.
void checkSupported(const Scene& scene);

/// The emitting quads and triangles of a checked scene (checkSupported). Throws InputError when
/// the scene has none (nothing to sample: the image would be black).
LightTable buildLightTable(const Scene& scene);

/// Unit geometric normal of a quad (u x v) or triangle ((v1-v0) x (v2-v0)) shape: its front face.
glm::vec3 flatNormal(const Shape& s);

}  // namespace vkp::embree_ref
