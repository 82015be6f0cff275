// Constant-density media in the kernel (shared/medium.h; scenes/README.md "Media"): where along a
// ray segment a medium scatters it, the transmittance of a shadow ray, and the phase function as
// a BSDF (shared/bsdf.h MAT_ISOTROPIC) at a scattering point. Compiled in only for scenes with a
// medium (HAS_MEDIA: the MAT_ISOTROPIC bit of MATERIALS). Media are tested one after the other
// (at most MAX_MEDIA of them); each test is one pass of a loop, counted in `passes` like the
// traversal's (lib/traverse.glsl).
#ifndef VKP_MEDIA_GLSL
#define VKP_MEDIA_GLSL
#include "lib/bindings.glsl"
#include "lib/solid_texture.glsl"
#include "shared/bsdf.h"
#include "shared/medium.h"
#include "shared/sample_stream.h"

/// Number of media in the scene (0 without HAS_MEDIA: every loop below compiles out).
uint mediumCount() { return HAS_MEDIA ? frame.media.x : 0u; }

/// Medium i's record (after the materials' tables, at texel frame.media.y of the materials buffer).
GpuMedium fetchMedium(uint i) {
    int base = int(frame.media.y + i * GPU_MEDIUM_TEXELS);
    GpuMedium m;
    m.r0 = fetchF(uMaterials, base);
    m.r1 = fetchF(uMaterials, base + 1);
    m.r2 = fetchF(uMaterials, base + 2);
    m.params = fetchF(uMaterials, base + 3);
    return m;
}

/// Free-flight sampling along the segment o + t d, t in [0, tMax) (d unit): each medium the
/// segment crosses draws a distance from where the segment enters it (one number of the vertex's
/// stream, shared/sample_stream.h); the nearest that falls inside its medium's interval is where
/// the ray scatters. Returns true with that distance t and the medium's index, false when the
/// ray passes every medium (probability: the segment's transmittance). Overlapping media thus
/// act as one of the summed density, the event belonging to each with probability density_i /
/// sum: exactly the book's independent media.
bool sampleMediumEvent(vec3 o, vec3 d, float tMax, inout SampleStream smp, out float t, out uint material, inout uint passes) {
    t = tMax;
    material = 0u;
    bool scattered = false;
    uint count = mediumCount();
    for (uint i = 0u; i < count; ++i) {
        GpuMedium m = fetchMedium(i);
        float t0, t1;
        if (!mediumInterval(m, o, d, 0.0f, t, t0, t1)) continue;
        float ti = t0 + sampleFreeFlight(m.params.x, sampleNext(smp));
        if (ti < t1) {
            t = ti;
            material = floatBitsToUint(m.params.z);
            scattered = true;
        }
    }
    passes += count + 1u;
    return scattered;
}

/// Transmittance exp(-sum_i sigma_i L_i) of the segment o + t d, t in [0, tMax) (d unit): the
/// factor of a shadow ray through the media it crosses.
float mediaTransmittance(vec3 o, vec3 d, float tMax, inout uint passes) {
    float depth = 0.0f;  // optical depth
    uint count = mediumCount();
    for (uint i = 0u; i < count; ++i) {
        GpuMedium m = fetchMedium(i);
        float t0, t1;
        if (mediumInterval(m, o, d, 0.0f, tMax, t0, t1)) depth += m.params.x * (t1 - t0);
    }
    passes += count + 1u;
    return exp(-depth);
}

/// The phase function of a medium of MAT_ISOTROPIC material `material` at point x as a BSDF
/// (normal 0: no surface), its albedo a JSON texture evaluated at x where it has one (an image
/// texture reads UV (0, 0)).
Bsdf mediumBsdf(uint material, vec3 x, vec3 dIn) {
    GpuMaterial mat = fetchMaterial(material);
    GpuPrim none;  // no primitive: solidTextureUv of a non-sphere gives ab = (0, 0)
    none.p0 = vec4(0.0f, 0.0f, 0.0f, uintBitsToFloat(PRIM_QUAD));
    none.p1 = vec4(0.0f);
    none.p2 = vec4(0.0f);
    solidTexturesAt(none, VKP_NO_PRIM, vec2(0.0f), x, true, mat);
    return makeBsdf(mat, vec3(0.0f), vec3(0.0f), dIn, true);
}

#endif
