// A vkpath Scene's spheres, quads and triangles as an Embree 3 scene: closest-hit and occlusion
// queries of single incoherent rays (rtcIntersect1 / rtcOccluded1). Source: the Embree 3 API
// manual pages that Debian's libembree-dev installs (`man 3 rtcNewDevice`, RTC_GEOMETRY_TYPE_TRIANGLE,
// RTC_GEOMETRY_TYPE_QUAD, RTC_GEOMETRY_TYPE_POINT (spheres), rtcSetNewGeometryBuffer,
// rtcInitIntersectContext, rtcIntersect1, rtcOccluded1; also https://www.embree.org/api.html).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkp::embree_ref {

/// The closest hit of a ray: which Scene::shapes entry, and at what distance.
struct Hit {
    std::uint32_t shape = 0;
    float t = 0.0f;  ///< distance along the (unit) ray direction, world units
};

/// One Embree device and scene holding every shape of a Scene (built in the constructor, then
/// read-only: queries may run on any number of threads at once).
class EmbreeScene {
public:
    /// Builds the scene with an Embree device configured with `config` (e.g. "threads=2", Embree's
    /// rtcNewDevice configuration string). Throws std::runtime_error with Embree's error on failure.
    EmbreeScene(const Scene& scene, const std::string& config);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    /// The closest hit of the ray o + t d for t in [0, inf) (d unit length), or false when it misses.
    bool intersect(glm::vec3 o, glm::vec3 d, Hit& hit) const;
    /// True when something lies on the segment o + t d, t in [0, tMax] (d unit length, world units).
    bool occluded(glm::vec3 o, glm::vec3 d, float tMax) const;

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<std::vector<std::uint32_t>> shapeOf_;  ///< [geomID][primID] -> Scene::shapes index
};

/// Embree's version, e.g. "3.13.5" (RTC_VERSION_STRING).
std::string embreeVersion();

}  // namespace vkp::embree_ref
