// The list of sampled objects ("lights": emitters and objects marked "sample": true).
// The book's mixture picks one uniformly (hittable_list::random); next-event estimation picks an
// emitter in proportion to its power (shared/light_pick.h). Pdfs are in solid angle at the
// shading point x.
#ifndef VKP_SCENE_LIGHTS_GLSL
#define VKP_SCENE_LIGHTS_GLSL
#include "lib/bindings.glsl"
#include "shared/intersect.h"
#include "shared/light_pick.h"
#include "shared/light_sampling.h"
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

/// Number of sampled objects that emit: power-proportional picks exist when it is > 0.
uint emitterCount() { return frame.counts.z; }

/// Pick one sampled object uniformly with u in [0,1) (the book's mixture): its light index.
uint pickLightUniform(float u, out float pickPdf) {
    uint n = lightCount();
    pickPdf = 1.0f / float(n);
    return pickUniform(u, n);
}

/// Pick one emitter in proportion to its power with u in [0,1): its light index. Requires
/// emitterCount() > 0; objects that do not emit have probability 0 and are never picked.
uint pickLightPower(float u, out float pickPdf) {
    float frac;
    uint column = aliasColumn(u, lightCount(), frac);
    uint li = aliasResolve(column, frac, fetchLight(column));
    pickPdf = fetchLight(li).l0.y;
    return li;
}

/// Probability that pickLightPower picks light li.
float pickPdfPower(uint li) { return fetchLight(li).l0.y; }

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
