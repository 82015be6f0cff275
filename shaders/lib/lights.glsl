// The scene's emitters behind one interface (pbrt-v4's Light: SampleLi, PDF_Li, L): what a surface
// emits, one sampled point on a light with its radiance and shadow ray (sampleEmitter), and the
// density of reaching a light by a given direction (pdfLightPrim). The light list
// holds every sampled object (emitters and objects marked "sample": true): the book's mixture picks
// one uniformly (hittable_list::random); next-event estimation picks an emitter in proportion to its
// power (shared/light_pick.h). The environment is the other light (lib/environment.glsl). Pdfs are
// in solid angle at the shading point x. A light kind is a primitive kind: its sampling triple
// lives in shared/light_sampling.h, rect_sampling.h or triangle_sampling.h, and the dispatch on it
// is sampleLightPrim / pdfLightPrim below (docs/extending.md).
#ifndef VKP_LIGHTS_GLSL
#define VKP_LIGHTS_GLSL
#include "lib/bindings.glsl"
#include "lib/solid_texture.glsl"
#include "lib/surface.glsl"
#include "shared/intersect.h"
#include "shared/light_pick.h"
#include "shared/light_sampling.h"
#include "shared/punctual_light.h"
#include "shared/ray_offset.h"
#include "shared/rect_sampling.h"
#include "shared/triangle_sampling.h"

uint lightCount() { return frame.counts.x; }

// Quads and triangles: the book's uniform area sampling for `mixture` (exactly as the book defines
// it); for next-event estimation solid-angle sampling of rectangles (Urena et al. 2013) and of
// triangles (Arvo 1995) from points where the light looks at least SOLID_ANGLE_MIN_SIZE large,
// area sampling elsewhere and as their fallback (shared/rect_sampling.h,
// shared/triangle_sampling.h); `--light-sampling area` (SOLID_ANGLE_LIGHTS false) keeps area
// sampling for every sampler, to measure what solid-angle sampling buys.
const bool SOLID_ANGLE_QUADS = SAMPLER != SAMPLER_MIXTURE && SOLID_ANGLE_LIGHTS;

/// Direction towards a point sampled on primitive p as seen from x (pdf 0: no sample).
LightSample sampleLightPrim(GpuPrim p, vec3 x, vec2 xi) {
    LightSample s;
    s.dir = vec3(0.0f, 0.0f, 1.0f);
    s.dist = 0.0f;
    s.pdf = 0.0f;
    uint kind = primKind(p);
    vec3 p0 = vec3(p.p0.x, p.p0.y, p.p0.z);
    vec3 e1 = primEdge1(p);  // triangles store vertices
    vec3 e2 = primEdge2(p);
    if (inPrimPlane(p, x)) return s;  // a flat light seen edge-on from its own plane: no sample
    if (HAS_SPHERE_LIGHTS && kind == PRIM_SPHERE) s = sampleSphereLight(p0, p.p1.w, x, xi);
    if (HAS_QUAD_LIGHTS && kind == PRIM_QUAD)
        s = SOLID_ANGLE_QUADS ? sampleRectLight(p0, e1, e2, x, xi, SOLID_ANGLE_MIN_SIZE) : sampleQuadLight(p0, e1, e2, x, xi);
    if (HAS_TRIANGLE_LIGHTS && kind == PRIM_TRIANGLE)
        s = SOLID_ANGLE_QUADS ? sampleTriangleLightSolidAngle(p0, e1, e2, x, xi, SOLID_ANGLE_MIN_SIZE) : sampleTriangleLight(p0, e1, e2, x, xi);
    return s;
}

/// Solid-angle pdf with which sampleLightPrim(p, x, .) produces direction d.
float pdfLightPrim(GpuPrim p, vec3 x, vec3 d) {
    uint kind = primKind(p);
    vec3 p0 = vec3(p.p0.x, p.p0.y, p.p0.z);
    vec3 e1 = primEdge1(p);  // triangles store vertices
    vec3 e2 = primEdge2(p);
    float pdf = 0.0f;
    if (inPrimPlane(p, x)) return 0.0f;  // as in sampleLightPrim
    if (HAS_SPHERE_LIGHTS && kind == PRIM_SPHERE) pdf = pdfSphereLight(p0, p.p1.w, x, d);
    if (HAS_QUAD_LIGHTS && kind == PRIM_QUAD)
        pdf = SOLID_ANGLE_QUADS ? pdfRectLight(p0, e1, e2, x, d, SOLID_ANGLE_MIN_SIZE) : pdfQuadLight(p0, e1, e2, x, d);
    if (HAS_TRIANGLE_LIGHTS && kind == PRIM_TRIANGLE)
        pdf = SOLID_ANGLE_QUADS ? pdfTriangleLightSolidAngle(p0, e1, e2, x, d, SOLID_ANGLE_MIN_SIZE) : pdfTriangleLight(p0, e1, e2, x, d);
    return pdf;
}

/// Number of sampled objects that emit, plus the punctual lights: power-proportional picks exist
/// when it is > 0.
uint emitterCount() { return frame.counts.z; }

/// Pick one sampled object uniformly with u in [0,1) (the book's mixture): its light index.
uint pickLightUniform(float u, out float pickPdf) {
    uint n = lightCount();
    pickPdf = 1.0f / float(n);
    return pickUniform(u, n);
}

/// Number of punctual lights (shared/punctual_light.h).
uint punctualCount() { return HAS_PUNCTUAL_LIGHTS ? frame.punctual.x : 0u; }

/// Entries of the power pick: the sampled objects, then the punctual lights.
uint pickCount() { return lightCount() + punctualCount(); }

/// An alias pick (shared/light_pick.h) with u in [0,1) among n >= 1 entries laid out as GpuLight
/// (y: probability, z: threshold, w: alias) in the lights buffer, entry i at texel base + i stride:
/// the entry's index and its probability.
uint aliasPick(float u, uint n, uint base, uint stride, out float pickPdf) {
    float frac;
    uint column = aliasColumn(u, n, frac);
    GpuLight entry;
    entry.l0 = fetchF(uLights, int(base + column * stride));
    uint i = aliasResolve(column, frac, entry);
    pickPdf = fetchF(uLights, int(base + i * stride)).y;
    return i;
}

/// Pick one emitter (emitting surface or punctual light) in proportion to its power with u in
/// [0,1): its light index. Requires emitterCount() > 0; objects that do not emit have probability
/// 0 and are never picked.
uint pickLightPower(float u, out float pickPdf) { return aliasPick(u, pickCount(), 0u, GPU_LIGHT_TEXELS, pickPdf); }

/// Probability that pickLightPower picks light li.
float pickPdfPower(uint li) { return fetchLight(li).l0.y; }

/// Radiance emitted by material m towards direction -d at a surface with geometric normal n
/// (either orientation): diffuse_light emits from its front only unless two-sided; an emitting
/// lambertian (or glTF emitter that is doubleSided) from both faces.
vec3 emitted(GpuMaterial m, vec3 d, vec3 n) {
    uint mflags = floatBitsToUint(m.m0.w);
    if (!HAS_EMITTERS || (mflags & MATF_EMITS) == 0u) return vec3(0.0f);
    bool front = dot(d, n) < 0.0f;
    bool oneSided = (mflags & MAT_TYPE_MASK) == MAT_DIFFUSE_LIGHT && (mflags & MATF_TWO_SIDED) == 0u;
    return (front || !oneSided) ? vec3(m.m1.x, m.m1.y, m.m1.z) : vec3(0.0f);
}

/// A sampled point on a light as seen from a shading point: what next-event estimation needs.
struct LightRay {
    vec3 dir;            ///< unit direction towards the light point (from the unoffset point x)
    vec3 le;             ///< radiance arriving from it along -dir (0: nothing to trace)
    float pdf;           ///< solid-angle density of dir, without the pick probability (0: no sample)
    vec3 shadowDir;      ///< the shadow ray from the offset point xo ...
    float shadowLength;  ///< ... and its length (world units; VKP_FAR: to infinity)
    bool delta;          ///< a punctual light: le is the irradiance (radiance integrated over the
                         ///< delta), pdf 1, and no BSDF sample can find it (MIS weight 1)
};

/// Punctual light k's one sample from the hit x (offset origin xo): direction, the irradiance it
/// brings to a surface facing it (in le), pdf 1 (0 when x is at the light), and the shadow ray
/// from xo to the light's position (to infinity for a directional light).
LightRay samplePunctual(uint k, vec3 x, vec3 xo) {
    GpuPunctualLight l = fetchPunctual(k);
    PunctualSample ps = samplePunctualLight(l, x);
    LightRay r;
    r.dir = ps.dir;
    r.le = ps.le;
    r.pdf = ps.valid ? 1.0f : 0.0f;
    r.delta = true;
    r.shadowDir = ps.dir;
    r.shadowLength = VKP_FAR;
    if (floatBitsToUint(l.q0.w) != PUNCTUAL_DIRECTIONAL) {
        // Nothing to offset at the light's end; cut by 2^-14 of the length (as shadowRayTo does), so
        // that a lamp placed exactly on a surface is not hidden by that surface's rounding.
        vec3 s = vec3(l.q0.x, l.q0.y, l.q0.z) - xo;
        float len = length(s);
        r.shadowDir = (len > 0.0f) ? s / len : ps.dir;
        r.shadowLength = len * (1.0f - 1.0f / 16384.0f);
    }
    return r;
}

/// Punctual light k's entry of the pick among the punctual lights alone (GpuPunctualLight::q3).
/// Pick one punctual light in proportion to its power with u in [0,1), among the punctual lights
/// alone (the alias pick over the records' q3 entries): its index. Requires punctualCount() > 0.
uint pickPunctual(float u, out float pickPdf) {
    return aliasPick(u, punctualCount(), uint(punctualTexel(0u)) + 3u, GPU_PUNCTUAL_TEXELS, pickPdf);
}

/// A point on light li (light-list index; a punctual light: samplePunctual), sampled from the hit x (offset origin xo) on primitive
/// `prim` (p) with u in [0,1)^2: direction, emitted radiance (emissive textures applied), pdf and
/// the shadow ray between the two offset points (shared/ray_offset.h). A flat light cannot light
/// itself: no sample of it from a point on it (rounding may put the hit point on either side of
/// its plane); a sphere can (from inside).
LightRay sampleEmitter(uint li, vec3 x, vec3 xo, uint prim, GpuPrim p, vec2 u) {
    LightRay r;
    uint lprim = floatBitsToUint(fetchLight(li).l0.x);
    if (HAS_PUNCTUAL_LIGHTS && (lprim & LIGHT_PUNCTUAL_BIT) != 0u) return samplePunctual(lprim & ~LIGHT_PUNCTUAL_BIT, x, xo);
    r.delta = false;
    GpuPrim lp = fetchPrim(lprim);
    LightSample ls = sampleLightPrim(lp, x, u);
    bool self = lprim == prim && primKind(p) != PRIM_SPHERE;
    r.dir = ls.dir;
    r.pdf = self ? 0.0f : ls.pdf;
    r.le = vec3(0.0f);
    r.shadowDir = ls.dir;
    r.shadowLength = 0.0f;
    if (r.pdf > 0.0f) {
        GpuMaterial lm = fetchMaterial(primMaterial(lp));
        vec3 lx = x + ls.dist * ls.dir;
        emissiveTextureAt(lprim, lp, lx, lm);  // lib/surface.glsl
        solidEmissionAt(lp, lprim, lx, lm);    // lib/solid_texture.glsl
        vec3 nl = primNormal(lp, lx);
        r.le = emitted(lm, ls.dir, nl);
        vec4 sr = shadowRayTo(xo, lx, nl, primOffsetDistance(lp, vec2(1.0f, 1.0f), nl), sceneOffsetScale());  // between offset end points
        r.shadowDir = vec3(sr.x, sr.y, sr.z);
        r.shadowLength = sr.w;
    }
    return r;
}

/// The book's light pdf: the average of every sampled object's pdf for direction d
/// (hittable_list::pdf_value). Costs one loop over the light list.
float pdfLights(vec3 x, vec3 d, inout uint passes) {
    uint n = lightCount();
    float sum = 0.0f;
    for (uint i = 0u; i < n; ++i) {
        passes++;
        GpuPrim p = fetchPrim(floatBitsToUint(fetchLight(i).l0.x));
        sum += pdfLightPrim(p, x, d);
    }
    return sum / float(n);
}

#endif
