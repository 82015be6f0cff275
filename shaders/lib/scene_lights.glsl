// The list of sampled objects ("lights": emitters and objects marked "sample": true).
// One is picked uniformly, as in "Ray Tracing: The Rest of Your Life" (hittable_list::random);
// pdfs are in solid angle at the shading point x, and include the pick probability.
#ifndef VKP_SCENE_LIGHTS_GLSL
#define VKP_SCENE_LIGHTS_GLSL
#include "lib/bindings.glsl"
#include "shared/intersect.h"
#include "shared/light_sampling.h"

uint lightCount() { return frame.counts.x; }

/// Direction towards a point sampled on primitive p as seen from x (pdf 0: no sample).
LightSample sampleLightPrim(GpuPrim p, vec3 x, vec2 xi) {
    LightSample s;
    s.dir = vec3(0.0f, 0.0f, 1.0f);
    s.dist = 0.0f;
    s.pdf = 0.0f;
    uint kind = primKind(p);
    vec3 p0 = vec3(p.p0.x, p.p0.y, p.p0.z);
    vec3 e1 = vec3(p.p1.x, p.p1.y, p.p1.z);
    vec3 e2 = vec3(p.p2.x, p.p2.y, p.p2.z);
    if (HAS_SPHERE_LIGHTS && kind == PRIM_SPHERE) s = sampleSphereLight(p0, p.p1.w, x, xi);
    if (HAS_PARALLELOGRAM_LIGHTS && kind == PRIM_QUAD) s = sampleQuadLight(p0, e1, e2, x, xi);
    if (HAS_PARALLELOGRAM_LIGHTS && kind == PRIM_TRIANGLE) s = sampleTriangleLight(p0, e1, e2, x, xi);
    return s;
}

/// Solid-angle pdf with which sampleLightPrim(p, x, .) produces direction d.
float pdfLightPrim(GpuPrim p, vec3 x, vec3 d) {
    uint kind = primKind(p);
    vec3 p0 = vec3(p.p0.x, p.p0.y, p.p0.z);
    vec3 e1 = vec3(p.p1.x, p.p1.y, p.p1.z);
    vec3 e2 = vec3(p.p2.x, p.p2.y, p.p2.z);
    float pdf = 0.0f;
    if (HAS_SPHERE_LIGHTS && kind == PRIM_SPHERE) pdf = pdfSphereLight(p0, p.p1.w, x, d);
    if (HAS_PARALLELOGRAM_LIGHTS && kind == PRIM_QUAD) pdf = pdfQuadLight(p0, e1, e2, x, d);
    if (HAS_PARALLELOGRAM_LIGHTS && kind == PRIM_TRIANGLE) pdf = pdfTriangleLight(p0, e1, e2, x, d);
    return pdf;
}

/// Pick one light uniformly with u in [0,1): its primitive index.
uint pickLight(float u, out float pickPdf) {
    uint n = lightCount();
    pickPdf = 1.0f / float(n);
    return min(uint(u * float(n)), n - 1u);
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
