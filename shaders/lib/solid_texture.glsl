// JSON textures at a shading point (shared/solid_texture.h; scenes/README.md "Textures"): the
// albedo of a lambertian or metal material and the emission of an emitter, per point, where the
// material's MATF_SOLID_TEXTURE flag says so (GpuMaterial m2.xy: texture node + 1 of each).
// Compiled in only for scenes that have some (HAS_SOLID_TEXTURES). Included by lib/hit.glsl and
// lib/lights.glsl.
#ifndef VKP_SOLID_TEXTURE_GLSL
#define VKP_SOLID_TEXTURE_GLSL
#include "lib/bindings.glsl"
#include "shared/intersect.h"

uint gSolidTextureBase = 0u;  // texel of the JSON textures in uTexInfo (info[0].w), set before each use
#define VKP_STEX_FETCH(i) texelFetch(uTexInfo, int(gSolidTextureBase + (i)))
#define VKP_TEXHEADER_FETCH(h) texelFetch(uTexInfo, int(texelFetch(uTexInfo, 0).x + (h)))
#ifndef VKP_TEXEL_FETCH
#define VKP_TEXEL_FETCH(i) texelFetch(uTexels, int(i)).x
#endif
#include "shared/solid_texture.h"

/// The book's UV of JSON primitive p at point x (surface parameters ab): a sphere's from the
/// direction of x from its centre (sphereUv), a quad's (a, b) of Q + a u + b v, a triangle's
/// barycentric weights (of v1, of v2).
vec2 solidTextureUv(GpuPrim p, vec2 ab, vec3 x) {
    if (primKind(p) == PRIM_SPHERE) return sphereUv(normalize(x - p.p0.xyz));
    return ab;
}

/// Applies the JSON textures of material m at point x of primitive p (index prim, surface
/// parameters ab): the emitted radiance and, if albedo, the albedo (clamped to [0, 1]). Other
/// materials are left alone. A moving primitive's texture moves with it: the 3D textures are
/// read where the point was at time 0 (x minus the primitive's motion so far, lib/bindings.glsl).
void solidTexturesAt(GpuPrim p, uint prim, vec2 ab, vec3 x, bool albedo, inout GpuMaterial m) {
    if (!HAS_SOLID_TEXTURES || (floatBitsToUint(m.m0.w) & MATF_SOLID_TEXTURE) == 0u) return;
    gSolidTextureBase = texelFetch(uTexInfo, 0).w;
    vec3 pf = x + solidTextureOrigin();  // the file's coordinates
    if (HAS_MOTION && prim != VKP_NO_PRIM) pf -= motionShift(prim);
    vec2 uv = solidTextureUv(p, ab, x);
    uint a = floatBitsToUint(m.m2.x);
    uint e = floatBitsToUint(m.m2.y);
    if (albedo && a != 0u) m.m0.xyz = min(evalSolidTexture(a - 1u, pf, uv), vec3(1.0f));
    if (e != 0u) m.m1.xyz = evalSolidTexture(e - 1u, pf, uv);
}

/// The emission of a JSON-textured emitter m at a point x sampled on light primitive p (index
/// prim; next-event estimation; the albedo is not needed there).
void solidEmissionAt(GpuPrim p, uint prim, vec3 x, inout GpuMaterial m) {
    if (!HAS_SOLID_TEXTURES || (floatBitsToUint(m.m0.w) & MATF_SOLID_TEXTURE) == 0u) return;
    solidTexturesAt(p, prim, primAbAt(p, x), x, false, m);
}

#endif
