// Warping uniform random numbers to directions and points, each as a triple
//   sampleX(u)   : u in [0,1)^2 (or ^3) -> direction (local frame, z = axis) or point,
//   pdfX(...)    : density of what sampleX returns, in SOLID ANGLE measure (sr^-1) for directions
//                  and AREA / VOLUME measure for points,
//   invertX(...) : the u that sampleX maps to the given value (round trip up to rounding).
// Convention for 2D warps: u.x drives the polar coordinate (z, radius), u.y the azimuth
// phi = 2 pi u.y, measured from +x towards +y. Local frames: see onb.h (z = normal / cone axis).
// Derivations: "Ray Tracing: The Rest of Your Life" (RTTROYL), chapter "Generating Random
// Directions" (uniform hemisphere, cosine hemisphere), "Sampling a Sphere Object" (cone);
// pbrt-v4 (Pharr, Jakob, Humphreys 2023; src/pbrt/util/sampling.h: SampleUniformSphere,
// SampleUniformDiskConcentric, SampleUniformCone and the matching Invert* functions).
#ifndef VKP_SAMPLING_H
#define VKP_SAMPLING_H
#include "glsl_compat.h"

VKP_BEGIN

/// Azimuth of (x, y) as a fraction of a full turn, in [0,1): the inverse of phi = 2 pi u.
/// (0,0) maps to 0.
VKP_FN float azimuthToUnit(float x, float y) {
    if (x == 0.0f && y == 0.0f) return 0.0f;     // GLSL leaves atan(0, 0) undefined
    float a = atan(y, x) * (1.0f / VKP_TWO_PI);  // (-1/2, 1/2]
    if (a < 0.0f) a += 1.0f;
    return (a < 1.0f) ? a : 0.0f;                // a tiny negative a rounds to 1.0: wrap
}

/// 1 - cos(theta) of a unit local direction without cancellation near the pole:
/// (x^2 + y^2) / (1 + z) when z > 0.
VKP_FN float oneMinusCosTheta(vec3 w) {
    return (w.z > 0.0f) ? (w.x * w.x + w.y * w.y) / (1.0f + w.z) : 1.0f - w.z;
}

// ---- Cosine-weighted hemisphere (RTTROYL, "Cosine Sampling a Hemisphere") ---------------------

/// Direction in the local upper hemisphere with density cos(theta)/pi (sr^-1).
/// r^2 = u.x, z = sqrt(1 - u.x) > 0 (never on the horizon for u.x < 1), phi = 2 pi u.y.
VKP_FN vec3 sampleCosineHemisphere(vec2 u) {
    float r = sqrt(u.x);
    float phi = VKP_TWO_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - u.x)));
}

/// Density cos(theta)/pi of sampleCosineHemisphere (sr^-1); 0 below the horizon.
VKP_FN float pdfCosineHemisphere(float cosTheta) { return max(cosTheta, 0.0f) * VKP_INV_PI; }

/// Inverse of sampleCosineHemisphere for a unit local direction with z > 0.
VKP_FN vec2 invertCosineHemisphere(vec3 w) {
    return vec2(min(w.x * w.x + w.y * w.y, 1.0f), azimuthToUnit(w.x, w.y));
}

// ---- Uniform sphere (pbrt-v4 SampleUniformSphere) ----------------------------------------------

/// Direction uniform on the unit sphere (density 1/(4 pi) sr^-1): z = 1 - 2 u.x, phi = 2 pi u.y.
/// The radius sqrt(1 - z^2) is evaluated as 2 sqrt(u.x (1 - u.x)), exact near both poles.
VKP_FN vec3 sampleUniformSphere(vec2 u) {
    float z = 1.0f - 2.0f * u.x;
    float r = 2.0f * sqrt(max(0.0f, u.x * (1.0f - u.x)));
    float phi = VKP_TWO_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

/// Density of sampleUniformSphere: 1/(4 pi) sr^-1.
VKP_FN float pdfUniformSphere() { return 0.25f * VKP_INV_PI; }

/// Inverse of sampleUniformSphere for a unit direction.
VKP_FN vec2 invertUniformSphere(vec3 w) {
    float ux = 0.5f * oneMinusCosTheta(w);  // (1 - z)/2 without cancellation near z = 1
    return vec2(min(ux, 1.0f), azimuthToUnit(w.x, w.y));
}

// ---- Uniform hemisphere (RTTROYL, "Uniform Sampling a Hemisphere") ----------------------------

/// Direction uniform on the local upper hemisphere (density 1/(2 pi) sr^-1):
/// z = 1 - u.x in (0, 1], phi = 2 pi u.y.
VKP_FN vec3 sampleUniformHemisphere(vec2 u) {
    float z = 1.0f - u.x;
    float r = sqrt(max(0.0f, u.x * (2.0f - u.x)));  // sqrt(1 - z^2) = sqrt((1-z)(1+z))
    float phi = VKP_TWO_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

/// Density of sampleUniformHemisphere (sr^-1): 1/(2 pi) above the horizon, else 0.
VKP_FN float pdfUniformHemisphere(float cosTheta) {
    return (cosTheta > 0.0f) ? 0.5f * VKP_INV_PI : 0.0f;
}

/// Inverse of sampleUniformHemisphere for a unit local direction with z > 0.
VKP_FN vec2 invertUniformHemisphere(vec3 w) {
    return vec2(min(oneMinusCosTheta(w), 1.0f), azimuthToUnit(w.x, w.y));
}

// ---- Uniform cone around +z (RTTROYL, "Sampling a Sphere Object"; pbrt-v4 SampleUniformCone) ----
// The cone is given by oneMinusCosMax = 1 - cos(theta_max) in (0, 2], NOT by cos(theta_max): for
// a small cone 1 - cos(theta_max) computed from the cosine loses every digit (cos(1e-4) == 1.0f),
// while coneOneMinusCos() below gets it to full precision from sin^2(theta_max).

/// 1 - cos(theta_max) of a cone with half-angle theta_max <= pi/2, from s2 = sin^2(theta_max):
/// s2 / (1 + cos(theta_max)), exact for tiny angles (a sphere of radius R at distance d has
/// s2 = (R/d)^2).
VKP_FN float coneOneMinusCos(float sin2ThetaMax) {
    return sin2ThetaMax / (1.0f + sqrt(max(0.0f, 1.0f - sin2ThetaMax)));
}

/// Direction uniform in the cone theta <= theta_max around +z (density 1/(2 pi (1 - cos
/// theta_max)) sr^-1). 1 - cos(theta) = u.x * oneMinusCosMax exactly, sin^2(theta) from
/// t (2 - t) with t = 1 - cos(theta): no cancellation at any angle.
VKP_FN vec3 sampleUniformCone(vec2 u, float oneMinusCosMax) {
    float t = u.x * oneMinusCosMax;
    float sinTheta = sqrt(max(0.0f, t * (2.0f - t)));
    float phi = VKP_TWO_PI * u.y;
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), 1.0f - t);
}

/// Density of sampleUniformCone at the unit local direction w (sr^-1): 1/(2 pi oneMinusCosMax)
/// inside the cone, 0 outside (and 0 for an empty cone, oneMinusCosMax <= 0).
VKP_FN float pdfUniformCone(vec3 w, float oneMinusCosMax) {
    bool inside = (oneMinusCosMax > 0.0f) && (oneMinusCosTheta(w) <= oneMinusCosMax);
    return inside ? 1.0f / (VKP_TWO_PI * oneMinusCosMax) : 0.0f;
}

/// Inverse of sampleUniformCone for a unit local direction inside the cone.
VKP_FN vec2 invertUniformCone(vec3 w, float oneMinusCosMax) {
    // An empty cone (oneMinusCosMax = 0) has no interior: 0 rather than 0/0, which GLSL's and
    // glm's min would resolve differently.
    float ux = (oneMinusCosMax > 0.0f) ? min(oneMinusCosTheta(w) / oneMinusCosMax, 1.0f) : 0.0f;
    return vec2(ux, azimuthToUnit(w.x, w.y));
}

// ---- Uniform unit disk: concentric mapping (Shirley & Chiu, "A Low Distortion Map Between Disk
// and Square", JGT 2(3), 1997; pbrt-v4 SampleUniformDiskConcentric). Used for defocus. ----------

/// Point uniform on the unit disk (density 1/pi per unit area). Maps concentric squares of
/// [0,1)^2 to concentric circles, so stratified u stay stratified.
VKP_FN vec2 sampleUniformDisk(vec2 u) {
    float a = 2.0f * u.x - 1.0f;
    float b = 2.0f * u.y - 1.0f;
    if (a == 0.0f && b == 0.0f) return vec2(0.0f);
    float r;
    float theta;
    if (abs(a) > abs(b)) {
        r = a;
        theta = 0.25f * VKP_PI * (b / a);
    } else {
        r = b;
        theta = 0.5f * VKP_PI - 0.25f * VKP_PI * (a / b);
    }
    return vec2(r * cos(theta), r * sin(theta));
}

/// Density of sampleUniformDisk: 1/pi per unit area inside the unit disk, 0 outside.
VKP_FN float pdfUniformDisk(vec2 p) { return (dot(p, p) <= 1.0f) ? VKP_INV_PI : 0.0f; }

/// Inverse of sampleUniformDisk: in the sector |x| >= |y| the sample had r = a = sign(x)|p| and
/// theta = atan(y/x) = (pi/4)(b/a); elsewhere r = b = sign(y)|p| and atan(x/y) = (pi/4)(a/b).
VKP_FN vec2 invertUniformDisk(vec2 p) {
    float len = length(p);
    float a;
    float b;
    if (abs(p.x) >= abs(p.y)) {
        if (p.x == 0.0f) return vec2(0.5f);
        a = (p.x < 0.0f) ? -len : len;
        b = a * atan(p.y / p.x) * (4.0f / VKP_PI);
    } else {
        b = (p.y < 0.0f) ? -len : len;
        a = b * atan(p.x / p.y) * (4.0f / VKP_PI);
    }
    return clamp(vec2(0.5f * (a + 1.0f), 0.5f * (b + 1.0f)), vec2(0.0f), vec2(1.0f));
}

// ---- Uniform unit ball (the fuzz of "Ray Tracing in One Weekend", sec. "Fuzzy Reflection") ------

/// Point uniform in the unit ball (density 3/(4 pi) per unit volume): direction from
/// sampleUniformSphere(u.x, u.y), radius cbrt(u.z).
VKP_FN vec3 sampleUniformBall(vec3 u) {
    float r = (u.z > 0.0f) ? pow(u.z, 1.0f / 3.0f) : 0.0f;
    return r * sampleUniformSphere(vec2(u.x, u.y));
}

/// Density of sampleUniformBall: 3/(4 pi) per unit volume inside the unit ball, 0 outside.
VKP_FN float pdfUniformBall(vec3 p) { return (dot(p, p) <= 1.0f) ? 0.75f * VKP_INV_PI : 0.0f; }

/// Inverse of sampleUniformBall for a point of the unit ball (u.z = r^3).
VKP_FN vec3 invertUniformBall(vec3 p) {
    float r = length(p);
    if (!(r > 0.0f)) return vec3(0.0f);
    vec2 uv = invertUniformSphere(p / r);
    return vec3(uv.x, uv.y, min(r * r * r, 1.0f));
}

VKP_END
#endif
