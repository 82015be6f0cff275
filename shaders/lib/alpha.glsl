// glTF alphaMode in the traversal (an any-hit test; shaders/lib/traverse.glsl calls VKP_ANY_HIT for
// every candidate hit, closest-hit and shadow rays alike). Compiled in only for scenes with a MASK
// or BLEND material (HAS_ALPHA, host/render/features.cpp); other scenes never define the hook.
//   MASK:  the hit counts iff alpha >= alphaCutoff (a cut-out), alpha = baseColorFactor.a x the
//          base colour texture's alpha (linear) x COLOR_0's alpha at the hit;
//   BLEND: stochastic transparency: the hit counts with probability alpha, decided by a hash of the
//          primitive index and the ray's bits, so the same ray always makes the same decision (the
//          render stays deterministic) and different rays decide independently. The pixel then
//          averages to alpha x surface + (1 - alpha) x what lies behind, as glTF's "over" blend.
#ifndef VKP_ALPHA_GLSL
#define VKP_ALPHA_GLSL
#include "lib/surface.glsl"

uint alphaHashStep(uint x) {  // PCG output permutation (O'Neill 2014), as in "Hash Functions for GPU Rendering"
    uint s = x * 747796405u + 2891336453u;
    uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

/// A number in [0,1) from the primitive and the ray (o, d): BLEND's pass-through decision.
float alphaHash(uint prim, vec3 o, vec3 d) {
    uint h = alphaHashStep(prim);
    h = alphaHashStep(h ^ floatBitsToUint(o.x));
    h = alphaHashStep(h ^ floatBitsToUint(o.y));
    h = alphaHashStep(h ^ floatBitsToUint(o.z));
    h = alphaHashStep(h ^ floatBitsToUint(d.x));
    h = alphaHashStep(h ^ floatBitsToUint(d.y));
    h = alphaHashStep(h ^ floatBitsToUint(d.z));
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

/// Any-hit test of the ray o + t d at primitive primIndex (p, surface parameters ab): false if the
/// hit is a hole (MASK) or passed through (BLEND).
bool alphaAccept(uint primIndex, GpuPrim p, vec2 ab, vec3 o, vec3 d) {
    if (!HAS_ALPHA || primKind(p) != PRIM_TRIANGLE) return true;
    uint rec = 1u + MAT_TEX_TEXELS * primMaterial(p);
    uvec4 a = texelFetch(uTexInfo, int(rec + MAT_TEX_ALPHA_TEXEL));  // (mode, cutoff, normal scale, alpha factor)
    if (a.x == ALPHA_OPAQUE) return true;
    float alpha = uintBitsToFloat(a.w);
    if (HAS_TEXTURES || HAS_VERTEX_COLORS) {
        int base = int(primIndex * ATTR_TEXELS);
        vec4 a0 = fetchF(uAttributes, base);
        vec4 a1 = fetchF(uAttributes, base + 1);
        alpha *= vertexColor(base, floatBitsToUint(a1.z), ab).w;  // COLOR_0's alpha (1 without it)
        if (HAS_TEXTURES && (floatBitsToUint(a1.z) & (ATTR_HAS_UV | ATTR_HAS_UV1)) != 0u) {
            vec2 uv = (1.0f - ab.x - ab.y) * a0.xy + ab.x * a0.zw + ab.y * a1.xy;
            vec4 c;
            if (sampleSlot(rec, TEX_SLOT_BASE_COLOR, uv, attributeUv1(a1, ab, uv), c)) alpha *= c.w;
        }
    }
    if (a.x == ALPHA_MASK) return alpha >= uintBitsToFloat(a.y);
    return alphaHash(primIndex, o, d) < alpha;
}

#define VKP_ANY_HIT(primIndex, p, ab, o, d) alphaAccept(primIndex, p, ab, o, d)

#endif
