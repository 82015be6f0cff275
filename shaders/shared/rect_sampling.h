// Sampling a rectangular light uniformly in solid angle: Urena, Fajardo and King, "An
// Area-Preserving Parametrization for Spherical Rectangles" (EGSR 2013). Compared with uniform
// area sampling (p = d^2 / (|cos| A)) the pdf is the constant 1/S over the rectangle's solid
// angle S, so a large or nearby light no longer gives high-variance samples near its edges.
// Falls back to area sampling where the parametrization loses precision (tiny solid angles) and for
// parallelograms that are not rectangles. Both faces are sampled, as with area sampling.
#ifndef VKP_RECT_SAMPLING_H
#define VKP_RECT_SAMPLING_H
#include "light_sampling.h"

VKP_BEGIN

/// Below this solid angle (sr) the spherical-rectangle angles (sums of acos near pi/2) lose too much
/// precision in float; area sampling is then as good anyway (its pdf barely varies over the light).
const float RECT_MIN_SOLID_ANGLE = 1.0e-3f;

/// The precomputed spherical rectangle of Q + a u + b v (u perpendicular to v) seen from p:
/// a local frame (x along u, y along v, z towards the side of p's opposite), the rectangle's extent
/// [x0,x1] x [y0,y1] at height z0 < 0 in it, and the constants of the inversion (b0, b1, k) and the
/// solid angle S (sr). Names follow the paper.
struct SphericalRect {
    vec3 o;
    vec3 x;
    vec3 y;
    vec3 z;
    float x0;
    float x1;
    float y0;
    float y1;
    float z0;
    float b0;
    float b1;
    float k;
    float S;
};

VKP_FN float safeAcos(float c) { return acos(clamp(c, -1.0f, 1.0f)); }

/// Solid angle of the triangle with vertices a, b, c seen from the origin (Van Oosterom and
/// Strackee 1983): 2 atan(|a.(b x c)| / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)). Accurate for
/// small triangles, unlike a sum of angles minus pi.
VKP_FN float triangleSolidAngle(vec3 a, vec3 b, vec3 c) {
    float la = length(a);
    float lb = length(b);
    float lc = length(c);
    float num = abs(dot(a, cross(b, c)));
    float den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    return 2.0f * atan(num, den);
}

/// How large a flat light of `area` (world units^2) centred at `centre` looks from p: the area over
/// the squared distance to the centre (sr), the solid angle it would subtend face-on. Cheap (no
/// trigonometry) and a function of the light and p alone, so a sample and its pdf take the same
/// branch with it. Where it is small, area sampling's pdf d^2 / (|cos| A) barely varies over the
/// light and solid-angle sampling's setup does not pay (`--light-sampling auto`, docs/performance.md "Solid angle or area").
VKP_FN float apparentSize(float area, vec3 centre, vec3 p) {
    vec3 d = centre - p;
    return area / max(dot(d, d), 1.0e-30f);
}

/// Whether sampleRectLight(Q, u, v, p, ., minSize) even considers solid-angle sampling: the quad's
/// apparentSize from p reaches minSize (sr; 0: always).
VKP_FN bool rectLargeEnough(vec3 Q, vec3 u, vec3 v, vec3 p, float minSize) {
    return minSize <= 0.0f || apparentSize(length(cross(u, v)), Q + 0.5f * (u + v), p) >= minSize;
}

/// Solid angle (sr) of the parallelogram Q + a u + b v seen from p, as two triangles (Van Oosterom
/// and Strackee; accurate when it looks small). sphericalRectInit stores exactly this value in S,
/// and pdfRectLight computes it alone, without the paper's frame and angles.
VKP_FN float rectSolidAngle(vec3 Q, vec3 u, vec3 v, vec3 p) {
    vec3 a = Q - p;
    vec3 c = a + u + v;
    return triangleSolidAngle(a, a + u, c) + triangleSolidAngle(a, c, a + v);
}

/// Setup of the paper's algorithm 1 ("SphQuadInit").
VKP_FN SphericalRect sphericalRectInit(vec3 Q, vec3 u, vec3 v, vec3 p) {
    SphericalRect r;
    float exl = length(u);
    float eyl = length(v);
    r.o = p;
    r.x = u / exl;
    r.y = v / eyl;
    r.z = cross(r.x, r.y);
    vec3 d = Q - p;
    r.z0 = dot(d, r.z);
    if (r.z0 > 0.0f) {
        r.z = -r.z;
        r.z0 = -r.z0;
    }
    r.x0 = dot(d, r.x);
    r.y0 = dot(d, r.y);
    r.x1 = r.x0 + exl;
    r.y1 = r.y0 + eyl;
    vec3 v00 = vec3(r.x0, r.y0, r.z0);
    vec3 v01 = vec3(r.x0, r.y1, r.z0);
    vec3 v10 = vec3(r.x1, r.y0, r.z0);
    vec3 v11 = vec3(r.x1, r.y1, r.z0);
    vec3 n0 = normalize(cross(v00, v10));
    vec3 n2 = normalize(cross(v11, v01));
    vec3 n3 = normalize(cross(v01, v00));
    float g2 = safeAcos(-dot(n2, n3));
    float g3 = safeAcos(-dot(n3, n0));
    r.b0 = n0.z;
    r.b1 = n2.z;
    r.k = VKP_TWO_PI - g2 - g3;
    // The paper's S = g0 + g1 - k loses precision to cancellation when the rectangle looks small;
    // the same solid angle from two triangles does not (g0, g1 are then not needed).
    r.S = rectSolidAngle(Q, u, v, p);

    return r;
}

/// Whether sampleRectLight uses the spherical rectangle for this light and point (else area
/// sampling): the quad is a rectangle and its solid angle is neither too small to be precise nor
/// so close to a hemisphere (p almost on the rectangle) that the parametrization degenerates: from
/// a point within rounding of the light's plane, solid-angle sampling would return steep
/// directions that area sampling rightly gives no weight.
VKP_FN bool useSphericalRectS(vec3 u, vec3 v, float S) {
    bool rectangle = abs(dot(u, v)) <= 1.0e-5f * length(u) * length(v);
    return rectangle && S > RECT_MIN_SOLID_ANGLE && S < 0.999f * VKP_TWO_PI;
}
VKP_FN bool useSphericalRect(vec3 u, vec3 v, SphericalRect r) { return useSphericalRectS(u, v, r.S); }

/// The point of the rectangle at xi in [0,1)^2 (paper's algorithm "SphQuadSample").
VKP_FN vec3 sphericalRectPoint(SphericalRect r, vec2 xi) {
    float au = xi.x * r.S + r.k;
    float sinAu = sin(au);
    float fu = (cos(au) * r.b0 - r.b1) / ((abs(sinAu) > 1.0e-7f) ? sinAu : 1.0e-7f);
    float cu = ((fu > 0.0f) ? 1.0f : -1.0f) / sqrt(fu * fu + r.b0 * r.b0);
    cu = clamp(cu, -1.0f, 1.0f);
    float xu = -(cu * r.z0) / max(sqrt(1.0f - cu * cu), 1.0e-7f);
    xu = clamp(xu, r.x0, r.x1);
    float dd = sqrt(xu * xu + r.z0 * r.z0);
    float h0 = r.y0 / sqrt(dd * dd + r.y0 * r.y0);
    float h1 = r.y1 / sqrt(dd * dd + r.y1 * r.y1);
    float hv = h0 + xi.y * (h1 - h0);
    float hv2 = hv * hv;
    float yv = (hv2 < 1.0f - 1.0e-6f) ? (hv * dd) / sqrt(1.0f - hv2) : r.y1;
    yv = clamp(yv, r.y0, r.y1);
    return r.o + xu * r.x + yv * r.y + r.z0 * r.z;
}

/// Whether sampleRectLight(Q, u, v, p, ., minSize) samples in solid angle (else in area).
VKP_FN bool rectLightUsesSolidAngle(vec3 Q, vec3 u, vec3 v, vec3 p, float minSize) {
    return rectLargeEnough(Q, u, v, p, minSize) && useSphericalRectS(u, v, rectSolidAngle(Q, u, v, p));
}

/// Direction from p to a point of the quad Q + a u + b v: uniform in solid angle (pdf 1/S) when
/// the quad looks at least minSize large from p (rectLargeEnough; sr, 0: always) and
/// useSphericalRect, otherwise uniform in area (sampleQuadLight). pdf 0: no sample.
/// (One call of the area fallback: on lavapipe every call site runs, taken or not; docs/design.md "Every reachable branch runs".)
VKP_FN LightSample sampleRectLight(vec3 Q, vec3 u, vec3 v, vec3 p, vec2 xi, float minSize) {
    if (rectLargeEnough(Q, u, v, p, minSize)) {
        SphericalRect r = sphericalRectInit(Q, u, v, p);
        if (useSphericalRect(u, v, r)) return makeLightSample(p, sphericalRectPoint(r, xi), 1.0f / r.S);
    }
    return sampleQuadLight(Q, u, v, p, xi);
}

/// Solid-angle density with which sampleRectLight(Q, u, v, p, ., minSize) produces unit direction dir.
/// Only the solid angle is computed (rectSolidAngle), not the sampling frame; one ray cast serves
/// both strategies.
VKP_FN float pdfRectLight(vec3 Q, vec3 u, vec3 v, vec3 p, vec3 dir, float minSize) {
    vec2 ab;
    float t = intersectParallelogram(Q, u, v, false, p, dir, 0.0f, VKP_FAR, ab);
    if (t == VKP_FAR) return 0.0f;
    if (rectLargeEnough(Q, u, v, p, minSize)) {
        float S = rectSolidAngle(Q, u, v, p);
        if (useSphericalRectS(u, v, S)) return lightPdfOrZero(1.0f / S);
    }
    return planarLightPdfFromHit(u, v, false, dir, t);
}

VKP_END
#endif
