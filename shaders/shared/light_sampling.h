// Sampling area lights as seen from a shading point p ("Ray Tracing: The Rest of Your Life"
// (RTTROYL), chapters "Sampling Lights Directly" (quad pdf p(w) = d^2 / (|cos theta_light| A)),
// "Sampling a Sphere Object" (cone)). Every density here is in SOLID ANGLE measure (sr^-1) at p;
// positions and distances are in world units. Each light kind has the triple
//   sampleXLight(..., p, xi) -> LightSample   (xi uniform in [0,1)^2)
//   pdfXLight(..., p, dir)   -> the density sampleXLight has at the unit direction dir
//   invertXLight(..., p, dir) -> the xi that samples dir, or (-1,-1) if dir is never sampled.
// LightSample.pdf == 0 means "no valid sample" (degenerate light, p on the light's plane, ...): the
// caller then adds no light-sample contribution. No function returns NaN or Inf.
// Area -> solid angle: p_w = p_A d^2 / |cos theta_light| (pbrt-v3 sec. 5.5.3 "Integrals over
// Area"); |cos| because both faces of quads and triangles are sampled (a one-sided emitter gives
// zero radiance on its back, which is the caller's business, not the sampler's).
#ifndef VKP_LIGHT_SAMPLING_H
#define VKP_LIGHT_SAMPLING_H
#include "intersect.h"
#include "onb.h"
#include "sampling.h"

VKP_BEGIN

/// One light sample: dir = unit direction from p to the sampled light point, dist = distance to
/// it (world units; shorten it by a relative epsilon for a shadow ray), pdf = solid-angle density
/// of dir (sr^-1), 0 if the sample is invalid (then dir = +z and dist = 0).
struct LightSample {
    vec3 dir;
    float dist;
    float pdf;
};

/// A finite positive pdf, or 0 for NaN, Inf, 0 and negative values.
VKP_FN float lightPdfOrZero(float pdf) { return (pdf > 0.0f && pdf < VKP_FAR) ? pdf : 0.0f; }

/// LightSample from p towards the light point x with solid-angle density `pdf`; invalid (pdf 0,
/// dir +z, dist 0) if pdf is not finite and positive or x == p.
VKP_FN LightSample makeLightSample(vec3 p, vec3 x, float pdf) {
    vec3 d = x - p;
    float dist = length(d);
    LightSample s;
    s.dir = d / dist;
    s.dist = dist;
    s.pdf = lightPdfOrZero(pdf);
    if (!(dist > 0.0f && dist < VKP_FAR) || s.pdf == 0.0f) {
        s.dir = vec3(0.0f, 0.0f, 1.0f);
        s.dist = 0.0f;
        s.pdf = 0.0f;
    }
    return s;
}

/// Solid-angle density of uniform area sampling of a parallelogram (triangle = false, A =
/// |e1 x e2|) or triangle (A = |e1 x e2| / 2) for a ray that hit it at distance t along the unit
/// direction dir: t^2 / (|cos theta_light| A). For a kernel that already has the hit (MIS weight
/// of a BSDF-sampled ray), equal to pdfQuadLight / pdfTriangleLight without a second ray cast.
VKP_FN float planarLightPdfFromHit(vec3 e1, vec3 e2, bool triangle, vec3 dir, float t) {
    float k = triangle ? 2.0f : 1.0f;
    return lightPdfOrZero(k * t * t / abs(dot(cross(e1, e2), dir)));
}

// ---- Parallelogram Q + a u + b v, a, b in [0,1) (uniform in area, A = |u x v|) ------------------

/// Uniform area sample x = Q + xi.x u + xi.y v; pdf = dist^2 / (|cos theta_light| A)
/// = dist^2 / |(u x v) . dir| (RTTROYL "Sampling Lights Directly", quad pdf).
VKP_FN LightSample sampleQuadLight(vec3 Q, vec3 u, vec3 v, vec3 p, vec2 xi) {
    vec3 x = Q + xi.x * u + xi.y * v;
    vec3 d = x - p;
    float dist2 = dot(d, d);
    float absDot = abs(dot(cross(u, v), d)) / sqrt(dist2);  // |(u x v) . dir|
    return makeLightSample(p, x, dist2 / absDot);
}

/// Solid-angle density of sampleQuadLight at unit direction dir: the ray p + t dir is cast
/// against the quad (intersect.h); t^2 / |(u x v) . dir| if it hits, else 0.
VKP_FN float pdfQuadLight(vec3 Q, vec3 u, vec3 v, vec3 p, vec3 dir) {
    vec2 ab;
    float t = intersectParallelogram(Q, u, v, false, p, dir, 0.0f, VKP_FAR, ab);
    return (t == VKP_FAR) ? 0.0f : planarLightPdfFromHit(u, v, false, dir, t);
}

/// xi with sampleQuadLight(Q, u, v, p, xi).dir == dir: the (a, b) of the hit; (-1,-1) on a miss.
VKP_FN vec2 invertQuadLight(vec3 Q, vec3 u, vec3 v, vec3 p, vec3 dir) {
    vec2 ab;
    float t = intersectParallelogram(Q, u, v, false, p, dir, 0.0f, VKP_FAR, ab);
    return (t == VKP_FAR) ? vec2(-1.0f) : clamp(ab, vec2(0.0f), vec2(1.0f));
}

// ---- Triangle v0 + a e1 + b e2 (uniform in area, A = |e1 x e2| / 2) ----------------------------

/// Uniform area sample by the square-root warp (Osada et al., "Shape Distributions", ACM TOG
/// 21(4), 2002; pbrt-v3 sec. 13.6.5 "Sampling a Triangle"):
/// s = sqrt(xi.x), (a, b) = (s (1 - xi.y), s xi.y); pdf = dist^2 / (|cos theta_light| A)
/// = 2 dist^2 / |(e1 x e2) . dir|.
VKP_FN LightSample sampleTriangleLight(vec3 v0, vec3 e1, vec3 e2, vec3 p, vec2 xi) {
    float s = sqrt(xi.x);
    vec3 x = v0 + (s * (1.0f - xi.y)) * e1 + (s * xi.y) * e2;
    vec3 d = x - p;
    float dist2 = dot(d, d);
    float absDot = abs(dot(cross(e1, e2), d)) / sqrt(dist2);
    return makeLightSample(p, x, 2.0f * dist2 / absDot);
}

/// Solid-angle density of sampleTriangleLight at unit direction dir (ray cast; 0 on a miss).
VKP_FN float pdfTriangleLight(vec3 v0, vec3 e1, vec3 e2, vec3 p, vec3 dir) {
    vec2 ab;
    float t = intersectParallelogram(v0, e1, e2, true, p, dir, 0.0f, VKP_FAR, ab);
    return (t == VKP_FAR) ? 0.0f : planarLightPdfFromHit(e1, e2, true, dir, t);
}

/// Inverse of sampleTriangleLight: from the hit's (a, b), s = a + b, xi = (s^2, b / s);
/// (-1,-1) on a miss.
VKP_FN vec2 invertTriangleLight(vec3 v0, vec3 e1, vec3 e2, vec3 p, vec3 dir) {
    vec2 ab;
    float t = intersectParallelogram(v0, e1, e2, true, p, dir, 0.0f, VKP_FAR, ab);
    if (t == VKP_FAR) return vec2(-1.0f);
    float s = max(ab.x, 0.0f) + max(ab.y, 0.0f);
    if (!(s > 0.0f)) return vec2(0.0f);
    return clamp(vec2(s * s, ab.y / s), vec2(0.0f), vec2(1.0f));
}

// ---- Sphere of centre c and radius R -----------------------------------------------------------
// Three strategies, chosen from d = |c - p| alone (sphereLightStrategy), so that the pdf
// functions always evaluate the density of the branch that the sampler takes:
//  CONE    d > R (1 + eps): uniform directions in the cone of half-angle theta_max that the
//          sphere subtends, sin^2 theta_max = (R/d)^2, p = 1 / (2 pi (1 - cos theta_max))
//          (RTTROYL "Sampling a Sphere Object"; 1 - cos from coneOneMinusCos, no cancellation).
//          The sample is the NEAR intersection, at t = (d - R)(d + R) / (d cos th + R sqrt(1 - k)),
//          k = sin^2 th / sin^2 theta_max (the quadratic's small root without cancellation).
//  SURFACE |d - R| <= eps R: p is on the sphere. Uniform AREA sampling of the sphere seen from a
//          point of its surface: every other surface point x lies above the tangent plane at p,
//          is reached along the chord p -> x of length L = 2 R cos b (b = angle between the chord
//          and the inward normal w = (c - p)/d), and the chord meets the surface at x with the same
//          angle b, so the area pdf 1/(4 pi R^2) becomes L^2/(|cos| A) = (2R cos b)^2 /
//          (cos b 4 pi R^2) = cos b / pi: exactly a cosine-weighted hemisphere around w. It is
//          sampled that way; dist is the far end of the chord, d cos b + sqrt(R^2 - d^2 sin^2 b).
//          Directions below the tangent plane are never produced; in the eps band just outside
//          the sphere, a direction so close to the tangent plane that it misses the sphere
//          (d sin b > R) is rejected (pdf 0, also in pdfSphereLight), so the estimator stays
//          unbiased and the pdf integrates to 1 - O(eps).
//  INSIDE  d < R (1 - eps): the whole sphere is visible; uniform area sampling, x = c + R s,
//          s uniform on the unit sphere, pdf = dist^2 / (cos_light 4 pi R^2) with
//          cos_light = s . dir > 0. Every direction hits the sphere exactly once (far root).
// R <= 0 or NaN input: no sample (pdf 0).
const uint SPHERE_LIGHT_CONE = 0u;
const uint SPHERE_LIGHT_SURFACE = 1u;
const uint SPHERE_LIGHT_INSIDE = 2u;
const uint SPHERE_LIGHT_INVALID = 3u;
/// Relative half-width of the SURFACE band around d = R.
const float SPHERE_LIGHT_SURFACE_EPS = 1.0e-4f;

/// Which strategy sampleSphereLight / pdfSphereLight use at distance d = |c - p| from the centre.
VKP_FN uint sphereLightStrategy(float d, float R) {
    if (!(R > 0.0f && R < VKP_FAR) || !(d >= 0.0f && d < VKP_FAR)) return SPHERE_LIGHT_INVALID;
    if (d > R * (1.0f + SPHERE_LIGHT_SURFACE_EPS)) return SPHERE_LIGHT_CONE;
    if (d < R * (1.0f - SPHERE_LIGHT_SURFACE_EPS)) return SPHERE_LIGHT_INSIDE;
    return SPHERE_LIGHT_SURFACE;
}

/// Sample the sphere light (c, R) from p (strategies above).
VKP_FN LightSample sampleSphereLight(vec3 c, float R, vec3 p, vec2 xi) {
    vec3 f = c - p;
    float d = length(f);
    uint strategy = sphereLightStrategy(d, R);
    LightSample s;
    s.dir = vec3(0.0f, 0.0f, 1.0f);
    s.dist = 0.0f;
    s.pdf = 0.0f;
    if (strategy == SPHERE_LIGHT_CONE) {
        float sinMax = R / d;
        float s2 = sinMax * sinMax;
        float cosMax = sqrt(max(0.0f, 1.0f - s2));
        float om = s2 / (1.0f + cosMax);  // 1 - cos(theta_max)
        vec3 w = sampleUniformCone(xi, om);
        float sin2 = w.x * w.x + w.y * w.y;
        float k = min(sin2 / s2, 1.0f);
        s.dir = toWorld(onbFromNormal(f / d), w);
        s.dist = (d - R) * (d + R) / (d * w.z + R * sqrt(max(0.0f, 1.0f - k)));
        s.pdf = lightPdfOrZero(1.0f / (VKP_TWO_PI * om));
    } else if (strategy == SPHERE_LIGHT_SURFACE) {
        vec3 w = sampleCosineHemisphere(xi);
        float sinB = sqrt(w.x * w.x + w.y * w.y);
        float disc = (R - d * sinB) * (R + d * sinB);  // R^2 - d^2 sin^2 b
        s.dir = toWorld(onbFromNormal(f / d), w);
        s.dist = d * w.z + sqrt(max(0.0f, disc));
        s.pdf = (disc >= 0.0f) ? lightPdfOrZero(w.z * VKP_INV_PI) : 0.0f;
    } else if (strategy == SPHERE_LIGHT_INSIDE) {
        vec3 n = sampleUniformSphere(xi);  // outward normal at the sampled point
        vec3 x = c + R * n;
        s = makeLightSample(p, x, 1.0f);
        float cosL = (R + dot(n, f)) / s.dist;  // n . (x - p) / dist, >= (R - d)/dist > 0
        float q = s.dist / R;                     // dist^2 / R^2 without under/overflow
        s.pdf = lightPdfOrZero(q * q / (cosL * 2.0f * VKP_TWO_PI));
    }
    if (s.pdf == 0.0f || !(s.dist >= 0.0f && s.dist < VKP_FAR)) {
        s.dir = vec3(0.0f, 0.0f, 1.0f);
        s.dist = 0.0f;
        s.pdf = 0.0f;
    }
    return s;
}

/// Solid-angle density of sampleSphereLight at the unit direction dir, of the same strategy.
VKP_FN float pdfSphereLight(vec3 c, float R, vec3 p, vec3 dir) {
    vec3 f = c - p;
    float d = length(f);
    uint strategy = sphereLightStrategy(d, R);
    if (strategy == SPHERE_LIGHT_CONE) {
        // Inside the cone iff cos > 0 and sin^2(angle(dir, f)) <= (R/d)^2. sin^2 from the cross
        // product stays accurate for tiny cones, where 1 - dot() would be rounding noise.
        float sinMax = R / d;
        float s2 = sinMax * sinMax;
        float om = s2 / (1.0f + sqrt(max(0.0f, 1.0f - s2)));
        vec3 cr = cross(dir, f / d);
        float sin2 = dot(cr, cr) / dot(dir, dir);
        bool inside = (dot(dir, f) > 0.0f) && (sin2 <= s2);
        return inside ? lightPdfOrZero(1.0f / (VKP_TWO_PI * om)) : 0.0f;
    }
    if (strategy == SPHERE_LIGHT_SURFACE) {
        vec3 w = f / d;
        float len = length(dir);
        float cosB = dot(dir, w) / len;
        vec3 cr = cross(dir, w);
        float sinB = length(cr) / len;
        bool hits = (cosB > 0.0f) && (d * sinB <= R);
        return hits ? lightPdfOrZero(cosB * VKP_INV_PI) : 0.0f;
    }
    if (strategy == SPHERE_LIGHT_INSIDE) {
        // Far root of |p + t dir - c| = R (Haines et al., Ray Tracing Gems ch. 7): with
        // b = dir . f and disc = R^2 - |f - b dir|^2, t = b + sqrt(disc), or, when b < 0,
        // (R - d)(R + d) / (sqrt(disc) - b) to avoid cancellation. cos_light = sqrt(disc) / R.
        float b = dot(dir, f);
        vec3 l = f - b * dir;
        float sq = sqrt(max(0.0f, (R - length(l)) * (R + length(l))));
        float t = (b >= 0.0f) ? b + sq : (R - d) * (R + d) / (sq - b);
        float q = t / R;
        return lightPdfOrZero(q * q / (2.0f * VKP_TWO_PI * (sq / R)));
    }
    return 0.0f;
}

/// xi with sampleSphereLight(c, R, p, xi).dir == dir (same strategy); (-1,-1) if dir is never
/// sampled from p.
VKP_FN vec2 invertSphereLight(vec3 c, float R, vec3 p, vec3 dir) {
    if (pdfSphereLight(c, R, p, dir) == 0.0f) return vec2(-1.0f);
    vec3 f = c - p;
    float d = length(f);
    uint strategy = sphereLightStrategy(d, R);
    if (strategy == SPHERE_LIGHT_INSIDE) {
        float b = dot(dir, f);
        vec3 l = f - b * dir;
        float sq = sqrt(max(0.0f, (R - length(l)) * (R + length(l))));
        float t = (b >= 0.0f) ? b + sq : (R - d) * (R + d) / (sq - b);
        return invertUniformSphere(normalize(t * dir - f));
    }
    vec3 w = toLocal(onbFromNormal(f / d), dir);
    if (strategy == SPHERE_LIGHT_SURFACE) return invertCosineHemisphere(w);
    float sinMax = R / d;
    float s2 = sinMax * sinMax;
    return invertUniformCone(w, s2 / (1.0f + sqrt(max(0.0f, 1.0f - s2))));
}

VKP_END
#endif
