// CPU twin of shaders/lib/traverse_wide.glsl (vkpTraverseWide, vkpWideLoop*): keep the two in step.
#include "bvh/traverse_wide_cpu.h"

#include <algorithm>
#include <utility>

#include "bvh/traverse_shared_cpu.h"
#include "shared/intersect.h"

namespace vkp {
namespace {

using namespace vkp::gpu;

template <class T>
const T& at(std::span<const T> a, std::uint32_t i, const char* what) {
    return traversalAt(a, i, "wide BVH traversal", what);
}

/// Compare-and-swap of the sorting network: after it, key[i] <= key[j] (swaps only on key[j] < key[i]).
void sortPair(float* key, uint* child, int i, int j) {
    if (key[j] < key[i]) {
        std::swap(key[i], key[j]);
        std::swap(child[i], child[j]);
    }
}

struct Arrays {
    std::span<const GpuWideNode> nodes;
    std::span<const GpuPrim> prims;
    std::span<const GpuInstance> instances;
};

/// One level's loop (the GLSL's vkpWideLoopTop / vkpWideLoopBottom): from node `root`, rays o + t d,
/// t in (tmin, t). instId: GPU_NO_INSTANCE at the top level, else the instance whose bottom level
/// this is (a PRIM_INSTANCE primitive met there is not descended into: its NaN coordinates miss).
template <bool kAnyHit>
bool loop(const Arrays& a, std::uint32_t root, const vec3& o, const vec3& d, float tmin, float& t, TraceResult& r,
          std::uint32_t instId, std::uint32_t& passes, std::uint32_t maxPasses) {
    const vec3 invD = safeInverse(d);
    std::uint32_t stack[kWideTraceStackSize];
    std::uint32_t sp = 0;
    std::uint32_t node = root;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < maxPasses) {
        passes += 2u;
        const GpuWideNode& n = at(a.nodes, node, "node");
        const vec4 tb = intersectWideChildren(n, o, invD, tmin, t);
        uint nLeaf[4];
        for (int k = 0; k < 4; ++k) nLeaf[k] = (tb[k] < VKP_FAR) ? n.count[k] : 0u;
        const uint s1 = nLeaf[0], s2 = s1 + nLeaf[1], s3 = s2 + nLeaf[2], total = s3 + nLeaf[3];
        for (uint i = 0u; i < total; ++i) {
            passes += 1u;
            const uint p = (i < s1) ? n.index[0] + i
                           : (i < s2) ? n.index[1] + (i - s1)
                           : (i < s3) ? n.index[2] + (i - s2)
                                      : n.index[3] + (i - s3);
            const GpuPrim& pr = at(a.prims, p, "primitive");
            const bool hit = leafPrimHitCpu(pr, p, o, d, tmin, t, r, instId, [&](std::uint32_t id) {
                const GpuInstance& inst = at(a.instances, id, "instance");
                passes += 1u;  // the bottom level's loop exit
                return loop<kAnyHit>(a, inst.info.x, instanceRayOrigin(inst, o), instanceRayDirection(inst, d), tmin, t, r, id,
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
        float key[4];
        uint child[4];
        for (int k = 0; k < 4; ++k) {
            key[k] = (tb[k] < VKP_FAR && n.count[k] == 0u) ? tb[k] : VKP_FAR;
            child[k] = n.index[k];
        }
        sortPair(key, child, 0, 1);
        sortPair(key, child, 2, 3);
        sortPair(key, child, 0, 2);
        sortPair(key, child, 1, 3);
        sortPair(key, child, 1, 2);
        for (int k = 3; k >= 1; --k) {
            if (key[k] < VKP_FAR) {
                if (sp < kWideTraceStackSize) {
                    stack[sp] = child[k];
                    ++sp;
                } else {
                    overflow = true;
                }
            }
        }
        if (key[0] < VKP_FAR) {
            node = child[0];
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

TraceResult traceClosestWideCpu(std::span<const GpuWideNode> nodes, std::span<const GpuPrim> prims,
                                std::span<const GpuInstance> instances, const glm::vec3& o, const glm::vec3& d,
                                float tmin, float tmax, std::uint32_t passes, std::uint32_t maxPasses) {
    return traverse<false>(Arrays{nodes, prims, instances}, o, d, tmin, tmax, passes, maxPasses);
}

TraceResult traceAnyWideCpu(std::span<const GpuWideNode> nodes, std::span<const GpuPrim> prims,
                            std::span<const GpuInstance> instances, const glm::vec3& o, const glm::vec3& d,
                            float tmin, float tmax, std::uint32_t passes, std::uint32_t maxPasses) {
    return traverse<true>(Arrays{nodes, prims, instances}, o, d, tmin, tmax, passes, maxPasses);
}

}  // namespace vkp
