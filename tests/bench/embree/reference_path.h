// The Embree reference's integrator: unidirectional path tracing with next-event estimation and
// multiple importance sampling, the same estimator as vkpath's default `mis` sampler on the
// scenes it supports (reference_scene.h), written independently of vkpath's kernel:
//   - camera: the book's pinhole / thin-lens camera ("Ray Tracing in One Weekend" sec. 13), box
//     filter over the pixel (uniform jitter), as vkpath's packCamera and startPath;
//   - at every Lambertian vertex one light picked by power, one point uniform in its area, one
//     shadow ray, weighted by the power heuristic (Veach 1997, ch. 9) against the cosine-weighted
//     BSDF sample, which weighs the emitter it finds the same way; diffuse_light ends the path;
//   - Russian roulette from `rouletteDepth` rays on (continue with min(max(throughput), 0.95)),
//     at most maxDepth rays per path (camera ray included), as vkpath.
// What differs from vkpath (neither changes the expected image): random numbers (PCG32 per
// sample, not Sobol'), area sampling of lights where vkpath samples quads and triangles by solid
// angle, and a ray offset of a fixed fraction of the scene's size (not Wachter-Binder). Rays are
// counted as vkpath counts them (COUNTER_RAYS, shaders/pathtrace.comp): every closest-hit ray
// (camera and bounces) and every shadow ray traced.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "embree_scene.h"
#include "reference_scene.h"
#include "scene/scene.h"

namespace vkp::embree_ref {

class PathTracer {
public:
    /// scene: checked (checkSupported); rt and lights built from it. All three must outlive this.
    PathTracer(const Scene& scene, const EmbreeScene& rt, const LightTable& lights);
    /// Sample number `index` of pixel (x, y) (y = 0: top row): its radiance (linear RGB). Its
    /// random numbers depend only on (pixel, index, scene seed). Adds the rays it traced to `rays`.
    glm::vec3 sample(std::uint32_t x, std::uint32_t y, std::uint32_t index, std::uint64_t& rays) const;

private:
    const Scene& scene_;
    const EmbreeScene& rt_;
    const LightTable& lights_;
    glm::vec3 origin_, pixel00_, du_, dv_, defocusU_, defocusV_;
    float eps_;  ///< ray offset, world units: 1e-5 x the scene's largest |coordinate| (at least 1e-5)
};

}  // namespace vkp::embree_ref
