// Next-event estimation: the one direct-lighting routine every material calls ("Ray Tracing: The
// Rest of Your Life", "Sampling Lights Directly"; multiple importance sampling, Veach 1997 ch. 9),
// and the MIS weight of a light that a BSDF-sampled ray finds instead. Used by the `light` and
// `mis` samplers at every non-delta vertex (shared/bsdf.h).
//
// One light sample per vertex: the environment with probability pEnv (envPickProb, 0 without one,
// 1 without emitters), else one emitter of the light list picked in proportion to its power
// (probability (1 - pEnv) x its share, shared/light_pick.h), one point on it (lib/lights.glsl), one
// shadow ray. Under `mis` (and under `light` at a glossy BSDF, bsdfIsGlossy) the sample is weighted
// by the power heuristic against the BSDF's density of the same direction; the BSDF's own sample
// then counts the light it hits with the complementary weight (foundLightWeight). Under `light` at
// other BSDFs the weight is 1 and the path ignores the lights its BSDF samples find.
//
// Punctual lights (point, spot, directional: shared/punctual_light.h) are delta lights: under
// `light` and `mis` they are entries of the power pick like the emitting surfaces, with MIS weight
// 1 (no BSDF sample can find them). No other strategy can find them at all, so under `bsdf` and
// `mixture` a non-delta vertex samples them too: one punctual light picked by power among the
// punctual lights alone, one shadow ray (punctualOn). That adds what those samplers would
// otherwise never see; it counts nothing twice, so every sampler stays unbiased.
#ifndef VKP_DIRECT_LIGHT_GLSL
#define VKP_DIRECT_LIGHT_GLSL
#include "lib/bindings.glsl"
#include "lib/environment.glsl"
#include "lib/lights.glsl"
#include "lib/media.glsl"
#include "lib/traverse.glsl"
#include "shared/bsdf.h"
#include "shared/light_pick.h"

/// Next-event estimation is on for this sampler and this scene (something to sample).
bool neeOn() { return (SAMPLER == SAMPLER_LIGHT || SAMPLER == SAMPLER_MIS) && (emitterCount() > 0u || envOn()); }

/// The `bsdf` and `mixture` samplers' next-event estimation of the punctual lights alone.
bool punctualOn() { return HAS_PUNCTUAL_LIGHTS && !(SAMPLER == SAMPLER_LIGHT || SAMPLER == SAMPLER_MIS) && punctualCount() > 0u; }

/// The light sample is weighted by MIS against the BSDF at this vertex.
bool neeWeighted(Bsdf b) { return SAMPLER == SAMPLER_MIS || bsdfIsGlossy(b); }

/// One light sample's contribution beta f cos Le w / p (a punctual light: beta f cos E / pick) at the non-delta vertex x (BSDF b, offset
/// origin xo, on primitive prim / p), with uStrategy in [0,1) choosing the light (the vertex's
/// strategy number) and uLight in [0,1)^2 the point on it; 0 when the sample is occluded, finds no
/// light or leaves below the surface. Counts the shadow ray in rays. sigma: the absorption coefficient
/// of the glass the vertex lies in (HAS_ABSORPTION; 0 outside): the shadow ray's length attenuates.
/// The shadow ray is attenuated by the media it crosses too (HAS_MEDIA: their transmittance), from
/// surface vertices and from scattering points inside a medium (b MAT_ISOTROPIC, prim
/// VKP_NO_PRIM) alike.
vec3 directLight(Bsdf b, vec3 beta, vec3 sigma, vec3 x, vec3 xo, uint prim, GpuPrim p, float uStrategy, vec2 uLight,
                 inout uint rays, inout uint passes) {
    float pEnv = envPickProb();
    LightRay r;
    float pick;
    if (!(SAMPLER == SAMPLER_LIGHT || SAMPLER == SAMPLER_MIS)) {  // bsdf, mixture: punctual lights only (punctualOn)
        r = samplePunctual(pickPunctual(uStrategy, pick), x, xo);
    } else if (!HAS_PICKED_LIGHTS || uStrategy < pEnv) {  // without emitters pEnv is 1: the variant drops their branch
        r = sampleEnvironmentLight(b.n, xo, uLight, passes);
        pick = pEnv;
    } else {
        float uPick = min((uStrategy - pEnv) / (1.0f - pEnv), 0.99999994f);
        uint li = pickLightPower(uPick, pick);
        pick *= 1.0f - pEnv;
        r = sampleEmitter(li, x, xo, prim, p, uLight);
    }
    // No shadow ray towards nothing, towards a light's back or below the surface.
    if (!(r.pdf > 0.0f) || !(bsdfCosine(b, r.dir) > 0.0f) || !(max(r.le.x, max(r.le.y, r.le.z)) > 0.0f))
        return vec3(0.0f);
    // Everything but the visibility first: only this contribution stays live across the shadow
    // ray's traversal loop (on a SIMD device such as lavapipe, the BSDF's state would otherwise
    // occupy registers, or spill, for every pass of that loop).
    float pl = r.pdf * pick;
    float w = (neeWeighted(b) && !r.delta) ? powerHeuristic(pl, pdfBsdf(b, r.dir)) : 1.0f;
    vec3 contribution = evalBsdf(b, beta, r.dir) * r.le * (w / pl);
    if (HAS_ABSORPTION && any(greaterThan(sigma, vec3(0.0f)))) contribution *= exp(-sigma * r.shadowLength);
    if (HAS_MEDIA) contribution *= mediaTransmittance(xo, r.shadowDir, r.shadowLength, passes);
    rays++;
    if (traceAny(xo, r.shadowDir, 0.0f, r.shadowLength, passes)) return vec3(0.0f);
    return contribution;
}

/// Density with which next-event estimation reaches the emitting primitive p from x along d (its
/// pick probability included): for the MIS weight of a BSDF-sampled ray that hit it.
float emitterHitPdf(GpuPrim p, vec3 x, vec3 d) {
    int li = primLight(p);
    if (li < 0) return 0.0f;
    return pickPdfPower(uint(li)) * (1.0f - envPickProb()) * pdfLightPrim(p, x, d);
}

/// MIS weight of an emitter that a ray sampled from a BSDF with density prevBsdfPdf found (0: the
/// camera ray or a delta lobe, counted fully), rayOrigin that ray's origin (the vertex moved off
/// its surface: the density is taken from there, shaders/pathtrace.comp), lightPdf the density
/// with which next-event estimation would have sampled it (emitterHitPdf). 1 for the samplers
/// without next-event estimation. The `light` sampler needs it only where a glossy BSDF occurs (VKP_HAS_GLOSSY_BSDF).
float foundLightWeight(float prevBsdfPdf, GpuPrim p, vec3 rayOrigin, vec3 d) {
    bool weighted = SAMPLER == SAMPLER_MIS || (SAMPLER == SAMPLER_LIGHT && VKP_HAS_GLOSSY_BSDF);
    if (!weighted || !(prevBsdfPdf > 0.0f) || primLight(p) < 0) return 1.0f;
    return powerHeuristic(prevBsdfPdf, emitterHitPdf(p, rayOrigin, d));
}

#endif
