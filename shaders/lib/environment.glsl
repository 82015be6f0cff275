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
#include "lib/lights.glsl"
#include "lib/traverse.glsl"
#include "shared/light_pick.h"
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

/// n = 0: a point inside a medium, where every direction is open (HAS_MEDIA only).
bool envNoNormal(vec3 n) { return HAS_MEDIA && dot(n, n) == 0.0f; }

/// Solid-angle pdf with which sampleEnv(n, .) produces d (without the pick probability).
float pdfEnv(vec3 d, vec3 n) {
    if (!envOn()) return 0.0f;
    if (!envMapOn()) return envNoNormal(n) ? pdfUniformSphere() : pdfCosineHemisphere(dot(d, n));
    return pdfEnvMap(frame.envSize.x, frame.envSize.y, envRotation(), d);
}

/// A direction towards the environment from a vertex with normal n (0: inside a medium), with u
/// in [0,1)^2; its solid-angle pdf in pdf (0: none).
vec3 sampleEnv(vec3 n, vec2 u, out float pdf, inout uint passes) {
    pdf = 0.0f;
    if (!envOn()) return vec3(0.0f, 1.0f, 0.0f);
    if (!envMapOn() && envNoNormal(n)) {
        pdf = pdfUniformSphere();
        return sampleUniformSphere(u);
    }
    if (!envMapOn()) {
        vec3 d = sampleLambertian(n, u);
        pdf = pdfCosineHemisphere(dot(d, n));
        return d;
    }
    passes += uint(findMSB(frame.envSize.x) + findMSB(frame.envSize.y)) + 4u;  // the binary searches' loops
    vec2 uv;
    return sampleEnvMap(frame.envSize.x, frame.envSize.y, envRotation(), u, pdf, uv);
}

/// The environment as a light for next-event estimation from a vertex with normal n: a direction
/// (sampleEnv) with its radiance and pdf (without the pick probability), the shadow ray towards
/// infinity from the offset point xo. pdf 0: no sample.
LightRay sampleEnvironmentLight(vec3 n, vec3 xo, vec2 u, inout uint passes) {
    LightRay r;
    r.dir = sampleEnv(n, u, r.pdf, passes);
    r.le = (r.pdf > 0.0f) ? envRadiance(r.dir) : vec3(0.0f);
    r.shadowDir = r.dir;
    r.shadowLength = VKP_FAR;
    r.delta = false;
    return r;
}

/// Radiance added by a ray escaping along d, if the path counts what its rays find (countEmission:
/// false after a vertex whose next-event estimation already counted it, the `light` sampler at a
/// non-glossy BSDF): under `light` and `mis` weighted against the environment sample that could have
/// found it from the previous vertex (normal prevN; prevBsdfPdf > 0: a BSDF sample; 0: the camera
/// or a delta lobe, counted fully), the power heuristic (Veach 1997).
vec3 envEscaped(vec3 d, vec3 prevN, float prevBsdfPdf, bool countEmission) {
    if (!envOn() || !countEmission) return vec3(0.0f);
    bool weighted = SAMPLER == SAMPLER_MIS || SAMPLER == SAMPLER_LIGHT;
    float w = (weighted && prevBsdfPdf > 0.0f) ? powerHeuristic(prevBsdfPdf, envPickProb() * pdfEnv(d, prevN)) : 1.0f;
    return envRadiance(d) * w;
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
