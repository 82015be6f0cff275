// One level of the binary traversal loop (the layout benchmark's, not the kernels'), included twice
// by tests/traverse_binary.glsl (GLSL has no recursion, so the top level and an instance's bottom
// level are two functions with the same body). No include guard. The includer defines
// VKP_BIN_LOOP_FN (the function's name) and VKP_BIN_LEAF(p): a bool expression that tests leaf
// primitive p (it may use this function's parameters) and updates t, primIndex, abHit, inst on a
// hit. Algorithm: tests/traverse_binary.glsl; pass counting: lib/traverse.glsl; CPU twin:
// tests/bench/traverse_binary_cpu.cpp (loop()).

bool VKP_BIN_LOOP_FN(const bool anyHit, uint root, vec3 o, vec3 d, float tmin, inout float t, inout uint primIndex,
                     inout vec2 abHit, inout uint inst, uint instId, inout uint passes) {
    vec3 invD = safeInverse(d);
    uint stack[VKP_TRAVERSE_STACK];
    uint sp = 0u;
    uint node = root;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < uint(VKP_MAX_PASSES)) {
        passes += 2u;
        GpuNode n = fetchNode(node);
        float tl = intersectBox(n.a.xyz, n.b.xyz, o, invD, tmin, t);
        float tr = intersectBox(n.c.xyz, n.d.xyz, o, invD, tmin, t);
        uint il = floatBitsToUint(n.a.w);
        uint cl = floatBitsToUint(n.b.w);
        uint ir = floatBitsToUint(n.c.w);
        uint cr = floatBitsToUint(n.d.w);
        bool hitL = tl < VKP_FAR;
        bool hitR = tr < VKP_FAR;
        uint nl = hitL ? cl : 0u;
        uint nr = hitR ? cr : 0u;
        for (uint i = 0u; i < nl + nr; ++i) {
            passes += 1u;
            uint p = (i < nl) ? il + i : ir + (i - nl);
            if (VKP_BIN_LEAF(p)) {
                found = true;
                if (anyHit) break;
            }
        }
        if (anyHit && found) {
            finished = true;
            break;
        }
        bool innerL = hitL && cl == 0u;
        bool innerR = hitR && cr == 0u;
        if (innerL && innerR) {
            bool leftFirst = tl <= tr;
            if (sp < VKP_TRAVERSE_STACK) {
                stack[sp] = leftFirst ? ir : il;
                sp += 1u;
            } else {
                overflow = true;
            }
            node = leftFirst ? il : ir;
        } else if (innerL || innerR) {
            node = innerL ? il : ir;
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
