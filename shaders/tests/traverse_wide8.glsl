// 8-wide BVH traversal: NOT the product's. A lever of issue 18 measured by the layout
// micro-benchmark (tests/bench/bench_bvh_layout.cpp): the kernels traverse 4-wide nodes
// (lib/traverse_wide.glsl); this is the same algorithm on nodes of eight children, to see whether
// fewer, wider steps pay on a device whose SIMD lanes are rays (each lane tests its node's boxes
// one after the other). The test kernel shaders/tests/bvh_trace.comp includes it with
// -DVKP_BVH_WIDE8. No instances, no CPU twin: the benchmark checks its hits against the other
// layouts' (t bit-exact, any-hit answer).
//
// Layout: an 8-wide node i is the two GpuWideNodes 2i (children 0-3) and 2i + 1 (children 4-7),
// host/bvh/wide_pack.h packWide8; the includer defines GpuWideNode fetchWideNode(uint i) and
// GpuPrim fetchPrim(uint i). Each step tests the eight child boxes, the primitives of every hit
// leaf child in one inner loop, sorts the hit inner children by entry distance (Batcher's
// odd-even merge sort, 19 comparators), descends into the nearest and pushes the others far to
// near. Passes as in lib/traverse.glsl (+2 per node step, +1 per primitive). Stack: 7 pushes per
// level, 31 levels at most (the builder's leaf depth bound): 224 entries.
#ifndef VKP_TRAVERSE_WIDE8_GLSL
#define VKP_TRAVERSE_WIDE8_GLSL

#include "shared/intersect.h"
#include "shared/wide_bvh.h"
#include "lib/leaf_test.glsl"

#ifndef VKP_MAX_PASSES
#define VKP_MAX_PASSES 60000u
#endif
#define VKP_WIDE8_STACK 224u

#define VKP_SORT8(i, j)                                          \
    if (key[j] < key[i]) {                                       \
        float tk = key[i]; key[i] = key[j]; key[j] = tk;         \
        uint tc = child[i]; child[i] = child[j]; child[j] = tc;  \
    }

#define VKP_PUSH8(k)                       \
    if (key[k] < VKP_FAR) {                \
        if (sp < VKP_WIDE8_STACK) {        \
            stack[sp] = child[k];          \
            sp += 1u;                      \
        } else {                           \
            overflow = true;               \
        }                                  \
    }

/// Box entry distances of the four children of half h, and their leaf counts (0 for a missed child).
void vkpWide8Half(GpuWideNode h, vec3 o, vec3 invD, float tmin, float t, out vec4 tb, out uvec4 nLeaf) {
    tb = intersectWideChildren(h, o, invD, tmin, t);
    nLeaf = mix(uvec4(0u), h.count, lessThan(tb, vec4(VKP_FAR)));
}

bool vkpTraverseWide8(const bool anyHit, vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float tHit,
                      out vec2 abHit, inout uint passes) {
    primIndex = GPU_NODE_EMPTY;
    tHit = VKP_FAR;
    abHit = vec2(0.0);
    if (any(isnan(o)) || any(isnan(d)) || !(tmin < tmax)) return false;
    float t = (tmax < VKP_FAR) ? tmax : VKP_FAR;
    vec3 invD = safeInverse(d);
    uint stack[VKP_WIDE8_STACK];
    uint sp = 0u;
    uint node = 0u;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < uint(VKP_MAX_PASSES)) {
        passes += 2u;
        GpuWideNode a = fetchWideNode(2u * node);
        GpuWideNode b = fetchWideNode(2u * node + 1u);
        vec4 ta, tbb;
        uvec4 la, lb;
        vkpWide8Half(a, o, invD, tmin, t, ta, la);
        vkpWide8Half(b, o, invD, tmin, t, tbb, lb);
        uint s[8];
        s[0] = la.x;
        s[1] = s[0] + la.y;
        s[2] = s[1] + la.z;
        s[3] = s[2] + la.w;
        s[4] = s[3] + lb.x;
        s[5] = s[4] + lb.y;
        s[6] = s[5] + lb.z;
        s[7] = s[6] + lb.w;
        for (uint i = 0u; i < s[7]; ++i) {
            passes += 1u;
            uint p = (i < s[0]) ? a.index.x + i
                   : (i < s[1]) ? a.index.y + (i - s[0])
                   : (i < s[2]) ? a.index.z + (i - s[1])
                   : (i < s[3]) ? a.index.w + (i - s[2])
                   : (i < s[4]) ? b.index.x + (i - s[3])
                   : (i < s[5]) ? b.index.y + (i - s[4])
                   : (i < s[6]) ? b.index.z + (i - s[5])
                                : b.index.w + (i - s[6]);
            if (vkpLeafHit(p, o, d, tmin, t, primIndex, abHit)) {
                found = true;
                if (anyHit) break;
            }
        }
        if (anyHit && found) {
            finished = true;
            break;
        }
        vec4 ka = mix(vec4(VKP_FAR), ta, bvec4(uvec4(lessThan(ta, vec4(VKP_FAR))) * uvec4(equal(a.count, uvec4(0u)))));
        vec4 kb = mix(vec4(VKP_FAR), tbb, bvec4(uvec4(lessThan(tbb, vec4(VKP_FAR))) * uvec4(equal(b.count, uvec4(0u)))));
        float key[8] = float[8](ka.x, ka.y, ka.z, ka.w, kb.x, kb.y, kb.z, kb.w);
        uint child[8] = uint[8](a.index.x, a.index.y, a.index.z, a.index.w, b.index.x, b.index.y, b.index.z, b.index.w);
        VKP_SORT8(0, 1) VKP_SORT8(2, 3) VKP_SORT8(4, 5) VKP_SORT8(6, 7)
        VKP_SORT8(0, 2) VKP_SORT8(1, 3) VKP_SORT8(4, 6) VKP_SORT8(5, 7)
        VKP_SORT8(1, 2) VKP_SORT8(5, 6)
        VKP_SORT8(0, 4) VKP_SORT8(1, 5) VKP_SORT8(2, 6) VKP_SORT8(3, 7)
        VKP_SORT8(2, 4) VKP_SORT8(3, 5)
        VKP_SORT8(1, 2) VKP_SORT8(3, 4) VKP_SORT8(5, 6)
        VKP_PUSH8(7) VKP_PUSH8(6) VKP_PUSH8(5) VKP_PUSH8(4) VKP_PUSH8(3) VKP_PUSH8(2) VKP_PUSH8(1)
        if (key[0] < VKP_FAR) {
            node = child[0];
        } else if (sp > 0u) {
            sp -= 1u;
            node = stack[sp];
        } else {
            finished = true;
            break;
        }
    }
    if (!finished || overflow) passes = max(passes, uint(VKP_MAX_PASSES));
    tHit = found ? t : VKP_FAR;
    return found;
}

#undef VKP_SORT8
#undef VKP_PUSH8

/// As lib/traverse.glsl's traceClosest.
bool traceClosest(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t, out vec2 ab, inout uint passes) {
    return vkpTraverseWide8(false, o, d, tmin, tmax, primIndex, t, ab, passes);
}

/// As lib/traverse.glsl's traceAny.
bool traceAny(vec3 o, vec3 d, float tmin, float tmax, inout uint passes) {
    uint primIndex;
    float t;
    vec2 ab;
    return vkpTraverseWide8(true, o, d, tmin, tmax, primIndex, t, ab, passes);
}

#endif
