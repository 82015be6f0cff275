// CPU twin of shaders/lib/traverse.glsl (vkpTraverse): keep the two in step.
#include "bvh/traverse_cpu.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "shared/intersect.h"

namespace vkp {
namespace {

using namespace vkp::gpu;

template <class T>
const T& at(std::span<const T> a, std::uint32_t i, const char* what) {
    if (i >= a.size())
        throw std::out_of_range(std::string("BVH traversal: ") + what + " index " + std::to_string(i) +
                                " out of range (" + std::to_string(a.size()) + ")");
    return a[i];
}

vec3 xyz(const vec4& v) { return vec3(v.x, v.y, v.z); }

template <bool kAnyHit>
TraceResult traverse(std::span<const GpuNode> nodes, std::span<const GpuPrim> prims, const vec3& o,
                     const vec3& d, float tmin, float tmax, std::uint32_t passes,
                     std::uint32_t maxPasses) {
    TraceResult r;
    r.passes = passes;
    r.maxPasses = maxPasses;
    const bool nanRay = glm::any(glm::isnan(o)) || glm::any(glm::isnan(d));
    if (nanRay || !(tmin < tmax)) return r;
    float t = (tmax < VKP_FAR) ? tmax : VKP_FAR;
    const vec3 invD = safeInverse(d);
    std::uint32_t stack[kTraceStackSize];
    std::uint32_t sp = 0;
    std::uint32_t node = 0;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < maxPasses) {
        passes += 2u;
        const GpuNode& n = at(nodes, node, "node");
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
            vec2 ab;
            const GpuPrim& pr = at(prims, p, "primitive");
            if (primKind(pr) == PRIM_INSTANCE)
                throw std::invalid_argument("BVH traversal: the binary layout does not traverse instances (the 4-wide one does)");
            const float th = intersectPrim(pr, o, d, tmin, t, ab);
            if (th < t) {
                t = th;
                r.prim = p;
                r.ab = ab;
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
    r.passes = passes;
    r.hit = found;
    r.t = found ? t : VKP_FAR;
    return r;
}

}  // namespace

TraceResult traceClosestCpu(std::span<const GpuNode> nodes, std::span<const GpuPrim> prims,
                            const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                            std::uint32_t passes, std::uint32_t maxPasses) {
    return traverse<false>(nodes, prims, o, d, tmin, tmax, passes, maxPasses);
}

TraceResult traceAnyCpu(std::span<const GpuNode> nodes, std::span<const GpuPrim> prims,
                        const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                        std::uint32_t passes, std::uint32_t maxPasses) {
    return traverse<true>(nodes, prims, o, d, tmin, tmax, passes, maxPasses);
}

}  // namespace vkp
