// The environment light: radiance of escaping rays, from a map (HAS_ENV_MAP: an equirectangular
// image importance sampled by its 2D piecewise-constant distribution, shared/environment_map.h) or
// the constant background. The constant background is sampled as a light too, but by the cosine
// lobe around the shading normal n (pdf cos/pi) instead of uniformly over the sphere (the density a
// 1x1 map would give): radiance x cosine is then sampled exactly, so an unoccluded diffuse vertex
// gets a zero-variance estimate, and half of the uniform sphere's samples (below the surface) are
// not wasted. Its pdf therefore depends on the normal of the vertex it is sampled from. It is one more light
// for next-event estimation (`light`, `mis`: picked with probability envPickProb(), the rest goes
// to the emitters by power) and for the book's mixture (one more entry of the uniformly picked
// light list). Map lookups are nearest-texel, so the radiance is piecewise constant exactly like
// the sampling density. Without HAS_ENV every function here is a constant and compiles out.
#ifndef VKP_ENVIRONMENT_GLSL
#define VKP_ENVIRONMENT_GLSL
#include "lib/bindings.glsl"
#include "lib/traverse.glsl"
#include "shared/sampling.h"
#include "shared/scatter.h"

float distFetch(uint i) { return texelFetch(uEnvDist, int(i)).x; }
#include "shared/environment_map.h"

vec2 envRotation() { return vec2(frame.env.x, frame.env.y); }

/// The scene has environment light (a constant false without HAS_ENV; the `full` variant compiles
/// everything in and asks the frame).
bool envOn() { return HAS_ENV && frame.env.w > 0.0f; }
/// ... and it comes from a map (else from the constant background).
bool envMapOn() { return HAS_ENV_MAP && frame.envSize.x > 0u; }

/// Probability that next-event estimation samples the environment (0 without one, 1 without
/// emitters); the emitters share the rest.
float envPickProb() { return envOn() ? frame.env.z : 0.0f; }

/// Radiance arriving from world direction d (unit), i.e. carried by a ray escaping along d.
vec3 envRadiance(vec3 d) {
    if (!envOn()) return vec3(0.0f);
    if (!envMapOn()) return vec3(frame.background.x, frame.background.y, frame.background.z);
    uvec2 t = envTexel(envMapUV(envToMap(d, envRotation())), frame.envSize.x, frame.envSize.y);
    vec4 L = uintBitsToFloat(texelFetch(uEnvTexels, int(t.y * frame.envSize.x + t.x)));
    return vec3(L.x, L.y, L.z);
}

/// Solid-angle pdf with which sampleEnv(n, .) produces d (without the pick probability).
float pdfEnv(vec3 d, vec3 n) {
    if (!envOn()) return 0.0f;
    if (!envMapOn()) return pdfCosineHemisphere(dot(d, n));
    return pdfEnvMap(frame.envSize.x, frame.envSize.y, envRotation(), d);
}

/// A direction towards the environment from a vertex with normal n, with u in [0,1)^2; its
/// solid-angle pdf in pdf (0: none).
vec3 sampleEnv(vec3 n, vec2 u, out float pdf, inout uint passes) {
    pdf = 0.0f;
    if (!envOn()) return vec3(0.0f, 1.0f, 0.0f);
    if (!envMapOn()) {
        vec3 d = sampleLambertian(n, u);
        pdf = pdfCosineHemisphere(dot(d, n));
        return d;
    }
    passes += uint(findMSB(frame.envSize.x) + findMSB(frame.envSize.y)) + 4u;  // the binary searches' loops
    vec2 uv;
    return sampleEnvMap(frame.envSize.x, frame.envSize.y, envRotation(), u, pdf, uv);
}

/// Next-event estimation towards the environment from a lambertian vertex x (normal ns facing the
/// incoming ray, offset origin xo) with albedo, the environment picked with probability pick:
/// f cos L w / (pick pdf) if the shadow ray to infinity escapes, w the power heuristic against the
/// cosine sample under `mis` (1 under `light`).
vec3 envDirectLight(vec3 xo, vec3 ns, vec3 albedo, vec2 u, float pick, inout uint rays, inout uint passes) {
    if (!envOn()) return vec3(0.0f);
    float pdf;
    vec3 dir = sampleEnv(ns, u, pdf, passes);
    float cosL = dot(dir, ns);
    if (!(pdf > 0.0f) || !(cosL > 0.0f)) return vec3(0.0f);
    vec3 le = envRadiance(dir);
    if (!(max(le.x, max(le.y, le.z)) > 0.0f)) return vec3(0.0f);
    rays++;
    if (traceAny(xo, dir, 0.0f, VKP_FAR, passes)) return vec3(0.0f);
    float pl = pick * pdf;
    float w = (SAMPLER == SAMPLER_MIS) ? powerHeuristic(pl, pdfCosineHemisphere(cosL)) : 1.0f;
    return albedo * VKP_INV_PI * cosL * le * (w / pl);
}

/// Radiance added by a ray escaping along d: under `mis` weighted against the environment sample
/// that could have found it from the previous vertex (normal prevN; prevBsdfPdf > 0: a BSDF
/// sample; 0: camera or specular, counted fully); under `light`, nothing after a lambertian vertex
/// that did next-event estimation (countEmission false), weighted as under mis after a MAT_PBR one.
vec3 envEscaped(vec3 d, vec3 prevN, float prevBsdfPdf, bool countEmission) {
    if (!envOn()) return vec3(0.0f);
    // `light` after a MAT_PBR vertex (countEmission and prevBsdfPdf set: lib/scatter_pbr.glsl)
    // weights like mis; after a lambertian vertex it counts nothing (countEmission false).
    if (SAMPLER == SAMPLER_MIS || (SAMPLER == SAMPLER_LIGHT && countEmission)) {
        float w = (prevBsdfPdf > 0.0f) ? powerHeuristic(prevBsdfPdf, envPickProb() * pdfEnv(d, prevN)) : 1.0f;
        return envRadiance(d) * w;
    }
    return countEmission ? envRadiance(d) : vec3(0.0f);
}

/// Number of entries of the book mixture's uniformly picked light list: the sampled objects and,
/// if there is one, the environment (the last entry).
uint mixtureLightCount() { return lightCount() + (envOn() ? 1u : 0u); }

/// The book's light pdf (hittable_list::pdf_value) over the sampled objects and the environment,
/// at a vertex x with normal n.
float pdfLightsAndEnv(vec3 x, vec3 n, vec3 d, inout uint passes) {
    if (!envOn()) return pdfLights(x, d, passes);
    uint count = lightCount();
    float sum = (count > 0u) ? pdfLights(x, d, passes) * float(count) : 0.0f;
    sum += pdfEnv(d, n);
    return sum / float(mixtureLightCount());
}

#endif
