// The book's mixture density ("Ray Tracing: The Rest of Your Life", "Mixture Densities": mixture_pdf
// of the BSDF's pdf and hittable_list::pdf_value), the `mixture` sampler, for every non-delta BSDF:
// one direction from 0.5 BSDF + 0.5 lights, the sampled objects picked uniformly and the
// environment one of them (lib/environment.glsl), weighted by f cos / p with p the mixture's
// density. No shadow ray: what the direction finds is what the path sees next.
#ifndef VKP_MIXTURE_GLSL
#define VKP_MIXTURE_GLSL
#include "lib/bindings.glsl"
#include "lib/environment.glsl"
#include "lib/lights.glsl"
#include "shared/bsdf.h"
#include "shared/light_pick.h"

/// The mixture applies at this vertex: the `mixture` sampler and something to sample besides the BSDF.
bool mixtureOn(Bsdf b) { return SAMPLER == SAMPLER_MIXTURE && !bsdfIsDelta(b) && mixtureLightCount() > 0u; }

/// One direction dir from the mixture at x, the offset origin the next ray starts from (so that a
/// light sample points at the light from where the ray leaves: a tiny light is missed otherwise),
/// BSDF b; uStrategy picks the half, u = bsdfNumbers(b, .),
/// whose last two numbers also drive the light sample); beta *= f cos / p. Returns false when the
/// sample carries nothing (no direction from the chosen strategy, or one below the surface).
bool sampleMixture(Bsdf b, vec3 x, float uStrategy, vec3 u, inout vec3 beta, out vec3 dir, inout uint passes) {
    vec2 u2 = vec2(u.y, u.z);
    if (uStrategy < 0.5f) {
        float pdfOwn;  // the BSDF's own density: the mixture's replaces it below
        vec3 weightOwn;
        sampleBsdf(b, u, dir, pdfOwn, weightOwn);
    } else if (envOn() && pickUniform(2.0f * uStrategy - 1.0f, mixtureLightCount()) == lightCount()) {
        float envPdf;  // the environment: the last entry of the light list
        dir = sampleEnv(b.n, u2, envPdf, passes);
        if (!(envPdf > 0.0f)) return false;
    } else {
        uint li = pickUniform(2.0f * uStrategy - 1.0f, mixtureLightCount());  // < lightCount() here
        LightSample ls = sampleLightPrim(fetchPrim(floatBitsToUint(fetchLight(li).l0.x)), x, u2);
        dir = ls.dir;
        if (!(ls.pdf > 0.0f)) return false;  // no direction from this strategy: the sample is 0
    }
    if (!(bsdfCosine(b, dir) > 0.0f)) return false;  // below the surface: f = 0
    float pdf = 0.5f * pdfBsdf(b, dir) + 0.5f * pdfLightsAndEnv(x, b.n, dir, passes);
    if (!(pdf > 0.0f)) return false;
    beta *= evalBsdf(b, vec3(1.0f), dir) / pdf;
    return true;
}

#endif
