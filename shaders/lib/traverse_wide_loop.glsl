// One level of the 4-wide traversal loop, included twice by lib/traverse_wide.glsl (GLSL has no
// recursion, so the top level and an instance's bottom level are two functions with the same body).
// No include guard. The includer defines VKP_WIDE_LOOP_FN (the function's name) and
// VKP_WIDE_LEAF(p): a bool expression that tests leaf primitive p (it may use this function's
// parameters) and updates t, primIndex, abHit, inst on a hit. See lib/traverse_wide.glsl for the
// algorithm and the pass counting; the CPU twin is host/bvh/traverse_wide_cpu.cpp (loop()).

#ifdef VKP_WIDE_POSTPONE
// Bench variant (tests/bench/bench_bvh_layout.cpp, "wide4 postponed leaves"): a leaf is a stack
// entry like an inner node, and each step does one unit of work, a node's four boxes or one
// primitive of the current leaf, so that lanes of a SIMD batch doing different work run one node
// and one primitive per step rather than a node and the busiest lane's whole leaf list (the if-if
// order of Aila and Laine 2009). A leaf entry is 0x80000000 | count << 27 | first primitive
// (count < 16, first < 2^27: enough for the bench's scenes).
bool VKP_WIDE_LOOP_FN(const bool anyHit, uint root, vec3 o, vec3 d, float tmin, inout float t, inout uint primIndex,
                      inout vec2 abHit, inout uint inst, uint instId, inout uint passes) {
    vec3 invD = safeInverse(d);
    uint stack[VKP_WIDE_STACK];
    uint sp = 0u;
    uint node = root;
    uint leafFirst = 0u;
    uint leafLeft = 0u;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < uint(VKP_MAX_PASSES)) {
        uint next = 0xffffffffu;
        if (leafLeft > 0u) {
            passes += 1u;
            uint p = leafFirst;
            leafFirst += 1u;
            leafLeft -= 1u;
            if (VKP_WIDE_LEAF(p)) {
                found = true;
                if (anyHit) {
                    finished = true;
                    break;
                }
            }
            if (leafLeft > 0u) continue;
        } else {
            passes += 2u;
            GpuWideNode n = fetchWideNode(node);
            vec4 key = intersectWideChildren(n, o, invD, tmin, t);
            uvec4 child = mix(n.index, uvec4(0x80000000u) | (n.count << 27u) | n.index, notEqual(n.count, uvec4(0u)));
            VKP_WIDE_SORT_PUSH
            if (key[0] < VKP_FAR) next = child[0];
        }
        if (next == 0xffffffffu) {
            if (sp == 0u) {
                finished = true;
                break;
            }
            sp -= 1u;
            next = stack[sp];
        }
        if ((next & 0x80000000u) != 0u) {
            leafFirst = next & 0x07ffffffu;
            leafLeft = (next >> 27u) & 15u;
        } else {
            node = next;
        }
    }
    if (!finished || overflow) passes = max(passes, uint(VKP_MAX_PASSES));
    return found;
}
#else
bool VKP_WIDE_LOOP_FN(const bool anyHit, uint root, vec3 o, vec3 d, float tmin, inout float t, inout uint primIndex,
                      inout vec2 abHit, inout uint inst, uint instId, inout uint passes) {
    vec3 invD = safeInverse(d);
    uint stack[VKP_WIDE_STACK];
    uint sp = 0u;
    uint node = root;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < uint(VKP_MAX_PASSES)) {
        passes += 2u;
        GpuWideNode n = fetchWideNode(node);
        vec4 tb = intersectWideChildren(n, o, invD, tmin, t);
        bvec4 hit = lessThan(tb, vec4(VKP_FAR));
        uvec4 nLeaf = mix(uvec4(0u), n.count, hit);
        uint s1 = nLeaf.x;
        uint s2 = s1 + nLeaf.y;
        uint s3 = s2 + nLeaf.z;
        uint total = s3 + nLeaf.w;
        for (uint i = 0u; i < total; ++i) {
            passes += 1u;
            uint p = (i < s1) ? n.index.x + i
                   : (i < s2) ? n.index.y + (i - s1)
                   : (i < s3) ? n.index.z + (i - s2)
                              : n.index.w + (i - s3);
            if (VKP_WIDE_LEAF(p)) {
                found = true;
                if (anyHit) break;
            }
        }
        if (anyHit && found) {
            finished = true;
            break;
        }
        bvec4 inner = bvec4(uvec4(hit) * uvec4(equal(n.count, uvec4(0u))));
#ifdef VKP_WIDE_RECULL
        // Bench variant: also drop inner children entered beyond the hit the leaves just found (the
        // box test repeated with tmax = t: enter <= t * VKP_BOX_EXIT_SCALE, intersect.h).
        inner = bvec4(uvec4(inner) * uvec4(lessThanEqual(tb, vec4(t * VKP_BOX_EXIT_SCALE))));
#endif
#ifdef VKP_WIDE_UNORDERED
        // Bench variant: visit hit inner children in slot order (the keys are slot numbers), to
        // measure what the nearest-first order buys; same sorting work.
        vec4 key = mix(vec4(VKP_FAR), vec4(0.0, 1.0, 2.0, 3.0), inner);
#else
        vec4 key = mix(vec4(VKP_FAR), tb, inner);
#endif
        uvec4 child = n.index;
        VKP_WIDE_SORT_PUSH
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
    return found;
}
#endif  // VKP_WIDE_POSTPONE
