// CPU twin of shaders/lib/traverse.glsl (vkpTraverse, vkpBinaryLoop*): keep the two in step.
#include "traverse_binary_cpu.h"

#include <algorithm>

#include "bvh/traverse_shared_cpu.h"
#include "shared/intersect.h"

namespace vkp {
namespace {

using namespace vkp::gpu;

template <class T>
const T& at(std::span<const T> a, std::uint32_t i, const char* what) {
    return traversalAt(a, i, "BVH traversal", what);
}

vec3 xyz(const vec4& v) { return vec3(v.x, v.y, v.z); }

struct Arrays {
    std::span<const GpuNode> nodes;
    std::span<const GpuPrim> prims;
    std::span<const GpuInstance> instances;
};

/// One level's loop (the GLSL's vkpBinaryLoopTop / vkpBinaryLoopBottom): from node `root`, rays
/// o + t d, t in (tmin, t). instId: GPU_NO_INSTANCE at the top level, else the instance whose bottom
/// level this is (a PRIM_INSTANCE primitive met there is not descended into: its NaN coordinates miss).
template <bool kAnyHit>
bool loop(const Arrays& a, std::uint32_t root, const vec3& o, const vec3& d, float tmin, float& t, TraceResult& r,
          std::uint32_t instId, std::uint32_t& passes, std::uint32_t maxPasses) {
    const vec3 invD = safeInverse(d);
    std::uint32_t stack[kTraceStackSize];
    std::uint32_t sp = 0;
    std::uint32_t node = root;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < maxPasses) {
        passes += 2u;
        const GpuNode& n = at(a.nodes, node, "node");
        const float tl = intersectBox(xyz(n.a), xyz(n.b), o, invD, tmin, t);
        const float tr = intersectBox(xyz(n.c), xyz(n.d), o, invD, tmin, t);
        const uint il = floatBitsToUint(n.a.w), cl = floatBitsToUint(n.b.w);
        const uint ir = floatBitsToUint(n.c.w), cr = floatBitsToUint(n.d.w);
        const bool hitL = tl < VKP_FAR;
        const bool hitR = tr < VKP_FAR;
        const uint nl = hitL ? cl : 0u;
        const uint nr = hitR ? cr : 0u;
        for (uint i = 0u; i < nl + nr; ++i) {
            passes += 1u;
            const uint p = (i < nl) ? il + i : ir + (i - nl);
            const GpuPrim& pr = at(a.prims, p, "primitive");
            const bool hit = leafPrimHitCpu(pr, p, o, d, tmin, t, r, instId, [&](std::uint32_t id) {
                const GpuInstance& inst = at(a.instances, id, "instance");
                passes += 1u;  // the bottom level's loop exit
                return loop<kAnyHit>(a, inst.info.y, instanceRayOrigin(inst, o), instanceRayDirection(inst, d), tmin, t, r, id,
                                     passes, maxPasses);
            });
            if (hit) {
                found = true;
                if (kAnyHit) break;
            }
        }
        if (kAnyHit && found) {
            finished = true;
            break;
        }
        const bool innerL = hitL && cl == 0u;
        const bool innerR = hitR && cr == 0u;
        if (innerL && innerR) {
            const bool leftFirst = tl <= tr;
            if (sp < kTraceStackSize) {
                stack[sp] = leftFirst ? ir : il;
                ++sp;
            } else {
                overflow = true;
            }
            node = leftFirst ? il : ir;
        } else if (innerL || innerR) {
            node = innerL ? il : ir;
        } else if (sp > 0u) {
            --sp;
            node = stack[sp];
        } else {
            finished = true;
            break;
        }
    }
    if (!finished || overflow) passes = std::max(passes, maxPasses);
    return found;
}

template <bool kAnyHit>
TraceResult traverse(const Arrays& a, const vec3& o, const vec3& d, float tmin, float tmax, std::uint32_t passes,
                     std::uint32_t maxPasses) {
    return traverseFromTop(o, d, tmin, tmax, passes, maxPasses, [&](float& t, TraceResult& r, std::uint32_t& p) {
        return loop<kAnyHit>(a, 0u, o, d, tmin, t, r, GPU_NO_INSTANCE, p, maxPasses);
    });
}

}  // namespace

TraceResult traceClosestCpu(std::span<const GpuNode> nodes, std::span<const GpuPrim> prims,
                            std::span<const GpuInstance> instances, const glm::vec3& o, const glm::vec3& d, float tmin,
                            float tmax, std::uint32_t passes, std::uint32_t maxPasses) {
    return traverse<false>(Arrays{nodes, prims, instances}, o, d, tmin, tmax, passes, maxPasses);
}

TraceResult traceAnyCpu(std::span<const GpuNode> nodes, std::span<const GpuPrim> prims,
                        std::span<const GpuInstance> instances, const glm::vec3& o, const glm::vec3& d, float tmin,
                        float tmax, std::uint32_t passes, std::uint32_t maxPasses) {
    return traverse<true>(Arrays{nodes, prims, instances}, o, d, tmin, tmax, passes, maxPasses);
}

}  // namespace vkp
