// What the two CPU twins (bvh/traverse_wide_cpu.cpp, tests/support/binary_bvh/traverse_binary_cpu.cpp) share: checked array
// access, the entry that sets up and finishes a traversal, and the leaf-primitive step (shared as
// shaders/lib/leaf_test.glsl is shared by the two GLSL traversals: keep the three in step).
#pragma once
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "bvh/trace_result.h"
#include "shared/instance.h"
#include "shared/intersect.h"

namespace vkp {

/// a[i], or std::out_of_range "<who>: <what> index i out of range (size)" (a malformed BVH).
template <class T>
const T& traversalAt(std::span<const T> a, std::uint32_t i, const char* who, const char* what) {
    if (i >= a.size())
        throw std::out_of_range(std::string(who) + ": " + what + " index " + std::to_string(i) + " out of range (" +
                                std::to_string(a.size()) + ")");
    return a[i];
}

/// A traversal of the ray o + t d, t in (tmin, tmax), from the top level: a ray with a NaN or an
/// empty interval finds nothing; else topLoop(t, r, passes) runs the layout's loop from the root
/// (t starts at min(tmax, VKP_FAR) and ends at the closest hit found) and returns whether it hit.
/// passes: the caller's loop-pass count so far (lavapipe's loop guard; maxPasses ends the walk).
template <class TopLoop>
TraceResult traverseFromTop(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, std::uint32_t passes,
                            std::uint32_t maxPasses, TopLoop&& topLoop) {
    TraceResult r;
    r.passes = passes;
    r.maxPasses = maxPasses;
    const bool nanRay = glm::any(glm::isnan(o)) || glm::any(glm::isnan(d));
    if (nanRay || !(tmin < tmax)) return r;
    float t = (tmax < gpu::VKP_FAR) ? tmax : gpu::VKP_FAR;
    const bool found = topLoop(t, r, passes);
    r.passes = passes;
    r.hit = found;
    r.t = found ? t : gpu::VKP_FAR;
    if (!found) r.instance = gpu::GPU_NO_INSTANCE;
    return r;
}

/// Tests primitive `pr` (index p) of a leaf against the ray o + t d, t in (tmin, t) (world units at
/// the top level, object units inside an instance). A shape that is hit closer than t shortens t
/// and becomes r's hit (with instId, GPU_NO_INSTANCE at the top level). An instance primitive met at
/// the top level calls descend(instance index), which traverses its bottom level with the same t
/// and r and returns whether it found a closer hit; inside a bottom level an instance primitive is
/// not descended into (its NaN coordinates miss). Returns whether t shrank.
template <class Descend>
bool leafPrimHitCpu(const gpu::GpuPrim& pr, std::uint32_t p, const glm::vec3& o, const glm::vec3& d, float tmin, float& t,
                    TraceResult& r, std::uint32_t instId, Descend&& descend) {
    if (instId == gpu::GPU_NO_INSTANCE && gpu::primKind(pr) == gpu::PRIM_INSTANCE) return descend(gpu::primMaterial(pr));
    glm::vec2 ab;
    const float th = gpu::intersectPrim(pr, o, d, tmin, t, ab);
    if (!(th < t)) return false;
    t = th;
    r.prim = p;
    r.ab = ab;
    r.instance = instId;
    return true;
}

}  // namespace vkp
