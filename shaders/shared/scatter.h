// The materials of "Ray Tracing in One Weekend" (RTIOW) and "Ray Tracing: The Rest of Your Life"
// (RTTROYL), as the kernel calls them. Conventions: directions are world-space unit vectors; dIn
// is the direction the ray travels (towards the surface); n is the unit surface normal on the
// side the ray arrives from (RTIOW sec. "Front Faces Versus Back Faces": dot(dIn, n) <= 0), and
// frontFace tells whether that is the geometric front (outside) of the surface.
//   lambertian : sample/pdf/invert/eval; density cos(theta)/pi in solid angle (sr^-1), BRDF
//                albedo/pi (sr^-1) (RTTROYL "Cosine Sampling a Hemisphere", "Light Scattering").
//   metal      : mirror reflection plus fuzz (RTIOW "Fuzzy Reflection"): a "delta-ish" lobe with
//                no density, exactly as in the book. The kernel treats it as specular: no light
//                sampling, no MIS, throughput *= albedo.
//   dielectric : reflect or refract, chosen with probability = Fresnel reflectance (Schlick as in
//                RTIOW "Schlick Approximation", or exact unpolarised Fresnel); a delta lobe too.
#ifndef VKP_SCATTER_H
#define VKP_SCATTER_H
#include "onb.h"
#include "sampling.h"

VKP_BEGIN

// ---- Lambertian ---------------------------------------------------------------------------------

/// Cosine-weighted direction around the unit normal n (world space), density cos/pi (sr^-1).
/// Always strictly above the surface (cos >= 2^-12 for u.x < 1).
VKP_FN vec3 sampleLambertian(vec3 n, vec2 u) {
    return toWorld(onbFromNormal(n), sampleCosineHemisphere(u));
}

/// Density of sampleLambertian at the unit direction dir (sr^-1): max(n . dir, 0) / pi.
VKP_FN float pdfLambertian(vec3 n, vec3 dir) { return pdfCosineHemisphere(dot(n, dir)); }

/// u with sampleLambertian(n, u) == dir, for dir above the surface.
VKP_FN vec2 invertLambertian(vec3 n, vec3 dir) {
    return invertCosineHemisphere(toLocal(onbFromNormal(n), dir));
}

/// Lambertian BRDF albedo / pi (sr^-1) for dir above the surface, else 0.
VKP_FN vec3 evalLambertian(vec3 albedo, vec3 n, vec3 dir) {
    return (dot(n, dir) > 0.0f) ? albedo * VKP_INV_PI : vec3(0.0f);
}

// ---- Metal --------------------------------------------------------------------------------------

/// Fuzzy mirror of RTIOW "Fuzzy Reflection": reflect(dIn, n) + fuzz * (a point uniform in the
/// unit ball, from u3 in [0,1)^3), normalised; fuzz is clamped to [0,1] as in the book.
/// absorbed = true when the perturbed direction is not above the surface (the book returns
/// false from scatter()); the returned direction is then the unperturbed mirror direction and
/// must not be used. No pdf: the kernel treats metal as specular. fuzz = 0 gives exactly the
/// mirror direction.
VKP_FN vec3 scatterMetal(vec3 dIn, vec3 n, float fuzz, vec3 u3, OUT(bool) absorbed) {
    vec3 r = reflect(normalize(dIn), n);
    vec3 o = r + clamp(fuzz, 0.0f, 1.0f) * sampleUniformBall(u3);
    float len2 = dot(o, o);
    absorbed = !(dot(o, n) > 0.0f) || !(len2 > 1.0e-12f);
    return absorbed ? r : o / sqrt(len2);
}

// ---- Dielectric ---------------------------------------------------------------------------------

/// Schlick's approximation of the Fresnel reflectance (RTIOW "Schlick Approximation"):
/// r0 + (1 - r0)(1 - cosine)^5 with r0 = ((1 - ior)/(1 + ior))^2. r0 is the same for a ratio and
/// its inverse, so ior may be the material's index or the book's ratio eta_i/eta_t; cosine is the
/// cosine of the incident angle, as in the book, on both sides of the surface.
VKP_FN float fresnelSchlick(float cosine, float ior) {
    float r0 = (1.0f - ior) / (1.0f + ior);
    r0 = r0 * r0;
    float m = clamp(1.0f - cosine, 0.0f, 1.0f);
    float m2 = m * m;
    return r0 + (1.0f - r0) * (m2 * m2 * m);
}

/// Exact Fresnel reflectance of a dielectric interface for unpolarised light (pbrt-v4 sec. 9.3,
/// FrDielectric; Hecht, "Optics"): cosI = cosine of the incident angle on the incident side,
/// eta = eta_t / eta_i (transmitted over incident index). A negative cosI means the ray arrives
/// from the other side: eta is inverted and cosI negated. Returns 1 under total internal
/// reflection. Result in [0,1].
VKP_FN float fresnelDielectricExact(float cosI, float eta) {
    float c = clamp(cosI, -1.0f, 1.0f);
    float e = eta;
    if (c < 0.0f) {
        e = 1.0f / e;
        c = -c;
    }
    float sin2I = max(0.0f, (1.0f - c) * (1.0f + c));
    float sin2T = sin2I / (e * e);
    if (!(sin2T < 1.0f)) return 1.0f;
    float cosT = sqrt(max(0.0f, 1.0f - sin2T));
    float rPar = (e * c - cosT) / (e * c + cosT);
    float rPerp = (c - e * cosT) / (c + e * cosT);
    return 0.5f * (rPar * rPar + rPerp * rPerp);
}

/// Probability that scatterDielectric reflects: 1 under total internal reflection, else the
/// Fresnel reflectance (exact or Schlick) at incidence cosine cosI in [0,1] and index ratio
/// etaRatio = eta_i / eta_t (RTIOW's refraction_ratio).
VKP_FN float dielectricReflectProbability(float cosI, float etaRatio, bool exact) {
    float c = clamp(cosI, 0.0f, 1.0f);
    float sin2T = etaRatio * etaRatio * max(0.0f, (1.0f - c) * (1.0f + c));
    if (!(sin2T <= 1.0f)) return 1.0f;
    return exact ? fresnelDielectricExact(c, 1.0f / etaRatio) : fresnelSchlick(c, etaRatio);
}

/// Dielectric of index ior (RTIOW "Dielectrics"): refraction ratio eta = 1/ior when entering
/// (frontFace), ior when leaving. Reflects when u < dielectricReflectProbability (always under
/// total internal reflection), else refracts by Snell's law, t = eta d + (eta cosI - cosT) n
/// (RTIOW "Snell's Law"). u in [0,1). Returns a unit direction: reflected ones are above the
/// surface (dot(., n) > 0), refracted ones below.
VKP_FN vec3 scatterDielectric(vec3 dIn, vec3 n, bool frontFace, float ior, bool exact, float u) {
    vec3 d = normalize(dIn);
    float eta = frontFace ? 1.0f / ior : ior;
    float cosI = clamp(-dot(d, n), 0.0f, 1.0f);
    float sin2T = eta * eta * max(0.0f, (1.0f - cosI) * (1.0f + cosI));
    if (u < dielectricReflectProbability(cosI, eta, exact)) return reflect(d, n);
    float cosT = sqrt(max(0.0f, 1.0f - sin2T));
    return normalize(eta * d + (eta * cosI - cosT) * n);
}

VKP_END
#endif
