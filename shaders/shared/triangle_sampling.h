// Sampling a triangular light uniformly in solid angle: Arvo, "Stratified Sampling of Spherical
// Triangles" (SIGGRAPH 1995), in the numerically careful form of pbrt-v4 (Pharr, Jakob, Humphreys,
// "Physically Based Rendering", 4th ed., sec. 6.5.4). Compared with uniform area sampling
// (p = d^2 / (|cos| A)) the pdf is the constant 1/S over the triangle's solid angle S, so a large
// or nearby triangle light no longer gives high-variance samples near its edges and corners. Falls
// back to area sampling where the spherical triangle's angles lose precision in float (tiny solid
// angles) and when the point is almost in the triangle's plane (S near 0 or 2 pi). Both faces are
// sampled, as with area sampling.
#ifndef VKP_TRIANGLE_SAMPLING_H
#define VKP_TRIANGLE_SAMPLING_H
#include "rect_sampling.h"

VKP_BEGIN

/// Solid angles (sr) between which sampleTriangleLightSolidAngle uses the spherical triangle. Below:
/// in float the warp's directions err by up to ~4e-4 rad whatever the triangle's size (sinBp from
/// cosBp near 1 keeps only sqrt(eps) of the angle; measured against a double-precision warp), 0.2%
/// of the triangle's angular size at 0.03 sr but 2-4% below 1e-3 sr (pbrt-v4's 3e-4 assumes fma'd
/// products lavapipe does not have); area sampling's variance there is within a few % of the
/// spherical one's anyway. Above: the point is within rounding of the triangle's plane.
const float TRI_MIN_SOLID_ANGLE = 2.0e-2f;
const float TRI_MAX_SOLID_ANGLE = 6.22f;

/// Angle (radians) between unit vectors a and b, accurate near 0 and pi (unlike acos(dot)).
VKP_FN float angleBetweenUnit(vec3 a, vec3 b) {
    if (dot(a, b) < 0.0f) return VKP_PI - 2.0f * asin(min(length(a + b) * 0.5f, 1.0f));
    return 2.0f * asin(min(length(b - a) * 0.5f, 1.0f));
}

/// A unit direction in the spherical triangle with unit vertices a, b, c, with xi in [0,1)^2,
/// uniform in solid angle (Arvo 1995: xi.x picks the sub-triangle of area xi.x S bounded by the
/// arc a-c', xi.y the point on the arc b-c'). Returns (0,0,0) for a degenerate triangle.
VKP_FN vec3 sampleSphericalTriangle(vec3 a, vec3 b, vec3 c, vec2 xi) {
    vec3 nab = cross(a, b);
    vec3 nbc = cross(b, c);
    vec3 nca = cross(c, a);
    if (!(dot(nab, nab) > 0.0f) || !(dot(nbc, nbc) > 0.0f) || !(dot(nca, nca) > 0.0f)) return vec3(0.0f);
    nab = normalize(nab);
    nbc = normalize(nbc);
    nca = normalize(nca);
    float alpha = angleBetweenUnit(nab, -nca);
    float beta = angleBetweenUnit(nbc, -nab);
    float gamma = angleBetweenUnit(nca, -nbc);
    // The sub-triangle's area plus pi: lerp from pi (xi.x = 0) to alpha + beta + gamma (xi.x = 1).
    float apPi = VKP_PI + xi.x * (alpha + beta + gamma - VKP_PI);
    float cosAlpha = cos(alpha);
    float sinAlpha = sin(alpha);
    float sinPhi = sin(apPi) * cosAlpha - cos(apPi) * sinAlpha;
    float cosPhi = cos(apPi) * cosAlpha + sin(apPi) * sinAlpha;
    float k1 = cosPhi + cosAlpha;
    float k2 = sinPhi - sinAlpha * dot(a, b);
    float den = (k2 * sinPhi + k1 * cosPhi) * sinAlpha;
    float cosBp = (den != 0.0f) ? (k2 + (k2 * cosPhi - k1 * sinPhi) * cosAlpha) / den : 1.0f;
    cosBp = clamp(cosBp, -1.0f, 1.0f);
    float sinBp = sqrt(max(0.0f, 1.0f - cosBp * cosBp));
    vec3 ca = c - dot(c, a) * a;  // Gram-Schmidt: c without its component along a
    vec3 cp = cosBp * a + sinBp * normalize(ca);
    float cosTheta = 1.0f - xi.y * (1.0f - dot(cp, b));
    float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
    vec3 cpb = cp - dot(cp, b) * b;
    float len = length(cpb);
    return (len > 0.0f) ? normalize(cosTheta * b + sinTheta * (cpb / len)) : b;
}

/// Solid angle (sr) of the triangle v0 + a e1 + b e2 seen from p (Van Oosterom and Strackee).
VKP_FN float triangleLightSolidAngle(vec3 v0, vec3 e1, vec3 e2, vec3 p) {
    vec3 a = v0 - p;
    return triangleSolidAngle(a, a + e1, a + e2);
}

/// Whether sampleTriangleLightSolidAngle uses the spherical triangle for solid angle S.
VKP_FN bool useSphericalTriangle(float S) { return S > TRI_MIN_SOLID_ANGLE && S < TRI_MAX_SOLID_ANGLE; }

/// Whether sampleTriangleLightSolidAngle(v0, e1, e2, p, ., minSize) even considers solid-angle
/// sampling: the triangle's apparentSize from p (area over squared distance to its centroid, sr)
/// reaches minSize (0: always).
VKP_FN bool triangleLargeEnough(vec3 v0, vec3 e1, vec3 e2, vec3 p, float minSize) {
    return minSize <= 0.0f ||
           apparentSize(0.5f * length(cross(e1, e2)), v0 + (e1 + e2) * (1.0f / 3.0f), p) >= minSize;
}

/// Whether sampleTriangleLightSolidAngle(v0, e1, e2, p, ., minSize) samples in solid angle.
VKP_FN bool triangleLightUsesSolidAngle(vec3 v0, vec3 e1, vec3 e2, vec3 p, float minSize) {
    return triangleLargeEnough(v0, e1, e2, p, minSize) && useSphericalTriangle(triangleLightSolidAngle(v0, e1, e2, p));
}

/// The solid-angle strategy of sampleTriangleLightSolidAngle: a direction from p uniform in the
/// triangle's solid angle S (> 0, from triangleLightSolidAngle), pdf 1/S.
VKP_FN LightSample sampleSphericalTriangleLight(vec3 v0, vec3 e1, vec3 e2, vec3 p, vec2 xi, float S) {
    vec3 a = v0 - p;
    vec3 w = sampleSphericalTriangle(normalize(a), normalize(a + e1), normalize(a + e2), xi);
    vec3 n = cross(e1, e2);
    float dn = dot(w, n);
    float t = (dn != 0.0f) ? dot(a, n) / dn : -1.0f;  // distance to the triangle's plane along w
    if (!(t > 0.0f && t < VKP_FAR)) return makeLightSample(p, p, 0.0f);
    // The point where w meets the plane, as barycentric coordinates clamped into the triangle: the
    // warp's float rounding can put a direction at the rim an ulp outside, where the pdf evaluated
    // alone (a ray cast) would miss it. Clamping, 1e-6 inside the rim, moves only points within
    // 1e-6 (in barycentric units) of it, by at most that: a change of the distribution far below
    // anything measurable, against 14 in 100k directions whose pdf was otherwise not reproducible.
    vec3 r = t * w - a;  // the point relative to v0 (a = v0 - p)
    float d11 = dot(e1, e1);
    float d12 = dot(e1, e2);
    float d22 = dot(e2, e2);
    float r1 = dot(r, e1);
    float r2 = dot(r, e2);
    float det = d11 * d22 - d12 * d12;
    const float inset = 1.0e-6f;  // keep clamped points off the rim, where a ray cast may miss
    float b1 = clamp((d22 * r1 - d12 * r2) / det, inset, 1.0f);
    float b2 = clamp((d11 * r2 - d12 * r1) / det, inset, 1.0f);
    float sum = b1 + b2;
    if (sum > 1.0f - inset) {
        b1 = b1 * ((1.0f - inset) / sum);
        b2 = b2 * ((1.0f - inset) / sum);
    }
    return makeLightSample(p, v0 + b1 * e1 + b2 * e2, 1.0f / S);
}

/// Direction from p to a point of the triangle v0 + a e1 + b e2: uniform in solid angle (pdf 1/S)
/// when the triangle looks at least minSize large from p (triangleLargeEnough; sr, 0: always) and
/// useSphericalTriangle, otherwise uniform in area (sampleTriangleLight). pdf 0: no sample.
/// (One call of the area fallback: on lavapipe every call site runs, taken or not; docs/design.md "Every reachable branch runs".)
VKP_FN LightSample sampleTriangleLightSolidAngle(vec3 v0, vec3 e1, vec3 e2, vec3 p, vec2 xi, float minSize) {
    if (triangleLargeEnough(v0, e1, e2, p, minSize)) {
        float S = triangleLightSolidAngle(v0, e1, e2, p);
        if (useSphericalTriangle(S)) return sampleSphericalTriangleLight(v0, e1, e2, p, xi, S);
    }
    return sampleTriangleLight(v0, e1, e2, p, xi);
}

/// Solid-angle density with which sampleTriangleLightSolidAngle(v0, e1, e2, p, ., minSize) produces dir.
/// One ray cast serves both strategies.
VKP_FN float pdfTriangleLightSolidAngle(vec3 v0, vec3 e1, vec3 e2, vec3 p, vec3 dir, float minSize) {
    vec2 ab;
    float t = intersectParallelogram(v0, e1, e2, true, p, dir, 0.0f, VKP_FAR, ab);
    if (t == VKP_FAR) return 0.0f;
    if (triangleLargeEnough(v0, e1, e2, p, minSize)) {
        float S = triangleLightSolidAngle(v0, e1, e2, p);
        if (useSphericalTriangle(S)) return lightPdfOrZero(1.0f / S);
    }
    return planarLightPdfFromHit(e1, e2, true, dir, t);
}

VKP_END
#endif
