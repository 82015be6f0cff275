// The leaf-primitive step of the CPU twins (bvh/traverse_cpu.cpp, bvh/traverse_wide_cpu.cpp), shared
// as shaders/lib/leaf_test.glsl is shared by the two GLSL traversals: keep the three in step.
#pragma once
#include <cstdint>

#include "bvh/traverse_cpu.h"
#include "shared/instance.h"
#include "shared/intersect.h"

namespace vkp {

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
