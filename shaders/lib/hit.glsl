// What a ray finds: the closest hit turned into a shading point (hit point recomputed from the
// primitive, normals, material with its textures, an instance's triangle placed in the world).
// Used by the integrator (pathtrace.comp) before it asks the BSDF (shared/bsdf.h) and the lights.
#ifndef VKP_HIT_GLSL
#define VKP_HIT_GLSL
#include "lib/bindings.glsl"
#include "lib/solid_texture.glsl"
#include "lib/surface.glsl"
#include "lib/traverse.glsl"
#include "shared/instance.h"
#include "shared/intersect.h"
#include "shared/ray_offset.h"

struct SurfaceHit {
    uint prim;          ///< index of the primitive hit (an instance's: of its object-space triangle)
    GpuPrim p;          ///< the primitive in world space at the path's time (an instance's triangle placed in the world)
    vec2 ab;            ///< surface parameters on p (intersect.h)
    vec3 x;             ///< hit point, recomputed from the primitive (shared/ray_offset.h)
    vec3 ng;            ///< unit geometric normal (the primitive's front)
    vec3 ns;            ///< ng turned to face the arriving ray
    bool frontFace;     ///< the ray arrived on the front
    vec3 nShade;        ///< shading normal (lib/surface.glsl; ns where there is none)
    vec3 nCoat;         ///< a layered material's clear-coat normal (lib/surface.glsl; else ns)
    GpuMaterial m;      ///< the kernel material, textures applied
    float extraOffset;  ///< an instance's part of the ray-origin offset (shared/instance.h; 0 otherwise)
};

/// The closest hit of the ray o + t d (t > 0) as a shading point; false if it escapes.
bool findSurface(vec3 o, vec3 d, out SurfaceHit h, inout uint passes) {
    uint inst;
    float t;
    if (!traceClosestInstance(o, d, 0.0f, VKP_FAR, h.prim, t, h.ab, inst, passes)) return false;
    h.p = fetchPrim(h.prim);
    vec2 abAttr = h.ab;  // surface parameters of the stored triangle (its attribute record's order)
    h.extraOffset = 0.0f;
    GpuPrim pObj = h.p;
    GpuInstance ins;
    bool instanced = HAS_INSTANCES && inst != GPU_NO_INSTANCE;
    if (instanced) {
        // An instance's triangle: shade it placed in the world, as the flattening loader places it.
        ins = fetchInstance(inst);
        h.p = instanceWorldPrim(ins, pObj);
        h.ab = instanceWorldAb(ins, h.ab);
    }
    h.x = primHitPoint(h.p, o, d, t, h.ab);  // from the primitive, not o + t d
    h.ng = primNormal(h.p, h.x);
    if (instanced) h.extraOffset = instanceOffsetDistance(ins, pObj, abAttr, h.x, h.ng);
    h.frontFace = dot(d, h.ng) < 0.0f;
    h.ns = h.frontFace ? h.ng : -h.ng;
    h.m = fetchMaterial(primMaterial(h.p));
    h.nShade = surfaceAt(h.prim, h.p, abAttr, h.ns, d, primMaterial(h.p), h.m, inst, h.nCoat);
    solidTexturesAt(h.p, h.prim, h.ab, h.x, true, h.m);  // JSON textures (lib/solid_texture.glsl)
    return true;
}

/// The origin of a ray leaving the hit on the side of normal n (h.ns or -h.ns).
vec3 spawnFrom(SurfaceHit h, vec3 n) { return spawnRayOriginExtra(h.p, h.ab, h.x, n, h.extraOffset, sceneOffsetScale()); }

#endif
