// The glTF 2.0 metallic-roughness BRDF (glTF 2.0 specification, appendix B "BRDF Implementation",
// with KHR_materials_specular) and its importance sampling, in the C++/GLSL common subset.
//
// Conventions. Every function works in the LOCAL frame of the shading normal (onb.h: z = n).
// v is the unit direction towards the viewer (the reverse of the incoming ray), l the unit direction
// towards the light (the scattered ray); both point away from the surface. Densities are in solid
// angle (sr^-1) over the whole sphere of l; BRDF values f are in sr^-1.
//
// Model (glTF appendix B):
//   alpha     = max(roughness^2, GGX_MIN_ALPHA)
//   D(h)      = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2)                    (Trowbridge-Reitz/GGX)
//   V(l, v)   = G2 / (4 |n.l| |n.v|), G2 the height-correlated Smith masking-shadowing
//               1 / (1 + Lambda(v) + Lambda(l)) (Heitz 2014, "Understanding the Masking-Shadowing
//               Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 99), in the closed form of the
//               glTF specification: 0.5 / (n.l sqrt((n.v)^2 (1-a^2) + a^2) + n.v sqrt((n.l)^2 (1-a^2) + a^2))
//   specular  = D V                                                            (no Fresnel inside)
//   Schlick   : F = f0 + (f90 - f0) (1 - |v.h|)^5
//   dielectric= (1 - F_d(n.v)) baseColor / pi + F_d(v.h) specular, F_d with f0 = min(0.04
//               specularColor, 1) specularFactor, f90 = specularFactor (KHR_materials_specular;
//               ior 1.5 -> 0.04)
//   metal     = F_m specular, F_m with f0 = baseColor, f90 = 1
//   f         = mix(dielectric, metal, metallic)
// specularFactor = 0 leaves exactly the Lambertian base colour / pi.
// One deliberate departure from appendix B: there the base is weighted by 1 - F_d(v.h), per half
// vector. That form reflects MORE energy than arrives at grazing views (white base, metallic 0:
// directional albedo 1.03 at 60 degrees, 1.20 at 75, 1.59 at 85 and 1.88 at 89.9 for roughness 0;
// 1.02 at 89.9 for roughness 1; measured by tests/stats/test_microfacet_furnace.cpp), because
// the cosine-distributed l of the base mostly has a large v.h while the specular lobe sees
// F_d(n.v) -> 1. Weighting it by 1 - F_d(n.v) instead keeps the furnace <= 1 but loses energy
// (white, roughness 1: albedo 0.41 at 85 degrees; the Blender Cornell box 4-9% too dark). Here the
// base is weighted by the energy the specular layer leaves, reciprocally (Kulla and Conty,
// "Revisiting Physically Based Shading at Imageworks", SIGGRAPH 2017 course, sec. on the energy
// of a diffuse base under a specular layer):
//   base = baseColor / pi (1 - E(n.v)) (1 - E(n.l)) / (1 - E_avg),
// E(mu) the directional albedo of the dielectric specular lobe (Fresnel included; E = f0 A + f90 B
// from the tabulated A, B of ggxAlbedoLookup) and E_avg = 2 int E(mu) mu dmu its hemispherical
// average: a white dielectric then reflects exactly 1 at every angle and roughness (up to the
// table's interpolation error, < 0.5%), and f is reciprocal.
//
// Sampling. The specular lobe samples the distribution of visible normals (Heitz 2018, "Sampling
// the GGX Distribution of Visible Normals", JCGT 7(4), listing 1) and reflects v about the sampled
// normal: pdf(l) = D_v(h) / (4 v.h) with D_v(h) = G1(v) max(0, v.h) D(h) / n.v, i.e.
// pdf = G1(v) D(h) / (4 n.v) = D(h) / (2 (n.v + sqrt(a^2 + (1 - a^2)(n.v)^2))). Reflected
// directions below the surface are possible (f = 0 there); the pdf counts them, so it integrates
// to 1 over the sphere. The whole BRDF is sampled by picking the specular lobe with probability
// gltfSpecularProbability (Fresnel-weighted luminance at the view angle, clamped into [0.1, 0.9]
// when both lobes are present) and the diffuse lobe (cosine) otherwise; the pdf is the mixture
// (one-sample balance of the two strategies), so eval and pdf serve MIS for any direction.
//
// Near-specular stability: alpha is clamped to GGX_MIN_ALPHA = 1e-3 (roughness ~0.032). D then
// peaks at 1/(pi 1e-6) ~ 3.2e5 sr^-1, which float represents with room to spare, and every
// quantity below is finite for v, l anywhere on the sphere; the sampling weight f cos / pdf of the
// specular lobe stays F G2/G1 <= 1 (no energy gain). roughness 0 renders as this very sharp lobe.
#ifndef VKP_MICROFACET_H
#define VKP_MICROFACET_H
#include "glsl_compat.h"
#include "sampling.h"

VKP_BEGIN

/// Smallest GGX alpha (dimensionless): roughness below ~0.032 is rendered as alpha = 1e-3.
const float GGX_MIN_ALPHA = 1.0e-3f;

/// GGX alpha of a perceptual roughness in [0,1] (glTF: alpha = roughness^2), clamped.
VKP_FN float ggxAlpha(float roughness) {
    float r = clamp(roughness, 0.0f, 1.0f);
    return max(r * r, GGX_MIN_ALPHA);
}

/// GGX (Trowbridge-Reitz) normal distribution D(h) (sr^-1, per projected area) for a unit local
/// half vector h; 0 for h.z <= 0. Written as 1 / (pi a^2 ((hx^2+hy^2)/a^2 + hz^2)^2), which equals
/// the glTF form for unit h and has no cancellation for tiny alpha.
VKP_FN float ggxD(vec3 h, float alpha) {
    if (!(h.z > 0.0f)) return 0.0f;
    float a2 = alpha * alpha;
    float k = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
    return 1.0f / (VKP_PI * a2 * k * k);
}

/// sqrt(a^2 + (1 - a^2) c^2) for c = n.w in [0,1]: the Smith term's building block
/// (= c (1 + 2 Lambda(w)) for c > 0).
VKP_FN float ggxSmithRoot(float c, float alpha) {
    float a2 = alpha * alpha;
    return sqrt(a2 + (1.0f - a2) * c * c);
}

/// Smith G1(w) = 1 / (1 + Lambda(w)) = 2 c / (c + sqrt(a^2 + (1 - a^2) c^2)), c = n.w > 0; 0 below.
VKP_FN float ggxG1(vec3 w, float alpha) {
    if (!(w.z > 0.0f)) return 0.0f;
    return 2.0f * w.z / (w.z + ggxSmithRoot(w.z, alpha));
}

/// Height-correlated Smith visibility V = G2 / (4 n.l n.v) (sr^0; the glTF closed form), for
/// n.l > 0 and n.v > 0, else 0.
VKP_FN float ggxVisibility(vec3 v, vec3 l, float alpha) {
    if (!(v.z > 0.0f) || !(l.z > 0.0f)) return 0.0f;
    return 0.5f / (l.z * ggxSmithRoot(v.z, alpha) + v.z * ggxSmithRoot(l.z, alpha));
}

/// (1 - c)^5 for c clamped into [0,1]: the Schlick weight.
VKP_FN float schlickWeight(float c) {
    float m = clamp(1.0f - c, 0.0f, 1.0f);
    float m2 = m * m;
    return m2 * m2 * m;
}

/// Schlick's Fresnel f0 + (f90 - f0) (1 - c)^5 with c = |v.h|.
VKP_FN vec3 fresnelSchlickF0(vec3 f0, float f90, float c) {
    return f0 + (vec3(f90) - f0) * schlickWeight(c);
}

// ---- The visible-normal sampling of the specular lobe --------------------------------------------

/// A microfacet normal h (local, unit, h.z >= 0) distributed as the GGX visible normals seen from v
/// (local, v.z > 0), u in [0,1)^2 (Heitz 2018, listing 1). For v.z <= 0 returns (0,0,1).
VKP_FN vec3 sampleGgxVisibleNormal(vec3 v, float alpha, vec2 u) {
    if (!(v.z > 0.0f)) return vec3(0.0f, 0.0f, 1.0f);
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));  // stretched to the hemisphere
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = (lensq > 0.0f) ? vec3(-vh.y, vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = VKP_TWO_PI * u.y;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0f, nh.z)));  // unstretched
}

/// Reflected direction l = 2 (v.h) h - v (local, unit) about a visible normal h of
/// sampleGgxVisibleNormal. May lie below the surface (the caller's f is then 0). For v.z <= 0
/// returns -v (pdfGgxVndf of it is 0).
VKP_FN vec3 sampleGgxVndf(vec3 v, float alpha, vec2 u) {
    if (!(v.z > 0.0f)) return -v;
    vec3 h = sampleGgxVisibleNormal(v, alpha, u);
    return 2.0f * dot(v, h) * h - v;
}

/// Density (sr^-1) of the direction l given the half vector h = normalize(v + l):
/// D_v(h) / (4 v.h) = D(h) / (2 (n.v + sqrt(a^2 + (1 - a^2)(n.v)^2))); 0 when v.z <= 0 or v.h <= 0.
VKP_FN float pdfGgxVndfHalf(vec3 v, vec3 h, float alpha) {
    if (!(v.z > 0.0f) || !(dot(v, h) > 0.0f)) return 0.0f;
    return ggxD(h, alpha) / (2.0f * (v.z + ggxSmithRoot(v.z, alpha)));
}

/// Density (sr^-1) with which sampleGgxVndf(v, alpha, .) returns l (anywhere on the sphere).
VKP_FN float pdfGgxVndf(vec3 v, vec3 l, float alpha) {
    vec3 hv = v + l;
    float len2 = dot(hv, hv);
    if (!(len2 > 0.0f)) return 0.0f;
    return pdfGgxVndfHalf(v, hv / sqrt(len2), alpha);
}

// ---- The albedo of the specular lobe (for the base's weight) -------------------------------------

/// Samples of the table along mu^(1/4), mu = n.v, and along the perceptual roughness, each over
/// [0,1] (mu^(1/4) puts the samples where E(mu) bends, at grazing angles).
const uint GGX_ALBEDO_N = 64u;

/// Texel t = j * GGX_ALBEDO_N + i of the table, (A, B, A_avg, B_avg) at mu = (i/(N-1))^4 and roughness
/// j/(N-1): A = int D V (1 - (1 - v.h)^5) cos dl, B = int D V (1 - v.h)^5 cos dl (so that the
/// lobe's albedo with Schlick's Fresnel is f0 A + f90 B), A_avg, B_avg their averages 2 int . mu dmu.
/// Defined outside this header: by the host (host/render/ggx_albedo_table.cpp, which computes the
/// table from this header's sampleGgxVndf) and by every kernel that includes it (a texel buffer).
vec4 ggxAlbedoFetch(uint t);

/// The table bilinearly interpolated at (mu^(1/4), roughness), both clamped into [0,1].
VKP_FN vec4 ggxAlbedoLookup(float mu, float roughness) {
    float x = sqrt(sqrt(clamp(mu, 0.0f, 1.0f))) * float(GGX_ALBEDO_N - 1u);
    float y = clamp(roughness, 0.0f, 1.0f) * float(GGX_ALBEDO_N - 1u);
    uint i = min(uint(x), GGX_ALBEDO_N - 2u);
    uint j = min(uint(y), GGX_ALBEDO_N - 2u);
    float fx = x - float(i);
    float fy = y - float(j);
    uint t = j * GGX_ALBEDO_N + i;
    vec4 a = ggxAlbedoFetch(t) * (1.0f - fx) + ggxAlbedoFetch(t + 1u) * fx;
    vec4 b = ggxAlbedoFetch(t + GGX_ALBEDO_N) * (1.0f - fx) + ggxAlbedoFetch(t + GGX_ALBEDO_N + 1u) * fx;
    return a * (1.0f - fy) + b * fy;
}

/// The base's weight (per channel) for a dielectric layer of Fresnel f0, f90 (file comment):
/// (1 - E(mu_o)) (1 - E(mu_i)) / (1 - E_avg), from the table at mu_o (to) and mu_i (ti).
VKP_FN vec3 gltfBaseWeight(vec3 f0, float f90, vec4 to, vec4 ti) {
    vec3 eo = f0 * to.x + vec3(f90 * to.y);
    vec3 ei = f0 * ti.x + vec3(f90 * ti.y);
    vec3 eavg = f0 * to.z + vec3(f90 * to.w);
    return clamp((vec3(1.0f) - eo) * (vec3(1.0f) - ei) / max(vec3(1.0f) - eavg, vec3(1.0e-4f)), vec3(0.0f), vec3(1.0f));
}

// ---- The glTF BRDF -------------------------------------------------------------------------------

/// A glTF metallic-roughness material, ready to evaluate (makeGltfBrdf fills it).
struct GltfBrdf {
    vec3 baseColor;  ///< linear RGB in [0,1]
    float metallic;  ///< [0,1]
    float alpha;     ///< ggxAlpha(roughness)
    float roughness; ///< perceptual roughness in [0,1] (the albedo table's coordinate)
    vec3 f0;         ///< dielectric Fresnel at normal incidence: min(0.04 specularColor, 1) specularFactor
    float f90;       ///< dielectric Fresnel at grazing incidence: specularFactor
};

/// The material of baseColor, metallicFactor, roughnessFactor and KHR_materials_specular's
/// specularFactor and specularColorFactor (defaults 1 and (1,1,1)).
VKP_FN GltfBrdf makeGltfBrdf(vec3 baseColor, float metallic, float roughness, float specularFactor, vec3 specularColor) {
    GltfBrdf m;
    m.baseColor = clamp(baseColor, vec3(0.0f), vec3(1.0f));
    m.metallic = clamp(metallic, 0.0f, 1.0f);
    m.alpha = ggxAlpha(roughness);
    m.roughness = clamp(roughness, 0.0f, 1.0f);
    float sf = clamp(specularFactor, 0.0f, 1.0f);
    m.f0 = min(0.04f * max(specularColor, vec3(0.0f)), vec3(1.0f)) * sf;
    m.f90 = sf;
    return m;
}

/// Luminance (Rec. 709 weights) of a linear RGB colour.
VKP_FN float luminance709(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/// f(v, l) (sr^-1, per channel): 0 unless both v and l are above the surface.
VKP_FN vec3 evalGltfBrdf(GltfBrdf m, vec3 v, vec3 l) {
    if (!(v.z > 0.0f) || !(l.z > 0.0f)) return vec3(0.0f);
    vec3 hv = v + l;
    vec3 h = hv / sqrt(dot(hv, hv));  // |v + l| > 0: both are above the surface
    float vh = abs(dot(v, h));
    float spec = ggxD(h, m.alpha) * ggxVisibility(v, l, m.alpha);
    vec3 fd = fresnelSchlickF0(m.f0, m.f90, vh);
    vec3 fm = fresnelSchlickF0(m.baseColor, 1.0f, vh);
    vec3 w = gltfBaseWeight(m.f0, m.f90, ggxAlbedoLookup(v.z, m.roughness), ggxAlbedoLookup(l.z, m.roughness));
    vec3 dielectric = w * m.baseColor * VKP_INV_PI + fd * spec;  // the base's weight: file comment
    vec3 metal = fm * spec;
    return dielectric + (metal - dielectric) * m.metallic;
}

/// Probability of sampling the specular lobe when looking from v: the luminance of the specular
/// reflectance estimated with the Fresnel term at n.v, against the diffuse one, clamped into
/// [0.1, 0.9]; 1 when there is no diffuse lobe (metallic 1 or black base), 0 when there is no
/// specular one (specularFactor 0 and metallic 0).
VKP_FN float gltfSpecularProbability(GltfBrdf m, vec3 v) {
    float c = clamp(v.z, 0.0f, 1.0f);
    vec3 fd = fresnelSchlickF0(m.f0, m.f90, c);
    vec3 fm = fresnelSchlickF0(m.baseColor, 1.0f, c);
    float spec = luminance709(fd) * (1.0f - m.metallic) + luminance709(fm) * m.metallic;
    float diff = luminance709((vec3(1.0f) - fd) * m.baseColor) * (1.0f - m.metallic);
    if (!(diff > 0.0f)) return 1.0f;
    if (!(spec > 0.0f)) return 0.0f;
    return clamp(spec / (spec + diff), 0.1f, 0.9f);
}

/// Density (sr^-1) with which sampleGltfBrdf(m, v, .) returns l: the mixture
/// p_s pdfGgxVndf + (1 - p_s) cos/pi. Integrates to 1 over the sphere when v.z > 0.
VKP_FN float pdfGltfBrdf(GltfBrdf m, vec3 v, vec3 l) {
    float ps = gltfSpecularProbability(m, v);
    float pdf = (1.0f - ps) * pdfCosineHemisphere(l.z);
    if (ps > 0.0f) pdf += ps * pdfGgxVndf(v, l, m.alpha);
    return pdf;
}

/// One direction l from the whole BRDF seen from v (v.z > 0), u in [0,1)^3: u.x picks the lobe
/// (specular when u.x < gltfSpecularProbability), (u.y, u.z) drive it. pdf = pdfGltfBrdf(m, v, l)
/// (computed from the sampled half vector, not from l). l may lie below the surface (f = 0).
VKP_FN vec3 sampleGltfBrdf(GltfBrdf m, vec3 v, vec3 u, OUT(float) pdf) {
    float ps = gltfSpecularProbability(m, v);
    vec2 u2 = vec2(u.y, u.z);
    vec3 l;
    float pdfSpec = 0.0f;
    if (u.x < ps) {
        if (!(v.z > 0.0f)) {
            pdf = 0.0f;
            return -v;
        }
        vec3 h = sampleGgxVisibleNormal(v, m.alpha, u2);
        l = 2.0f * dot(v, h) * h - v;
        pdfSpec = pdfGgxVndfHalf(v, h, m.alpha);
    } else {
        l = sampleCosineHemisphere(u2);
        if (ps > 0.0f) pdfSpec = pdfGgxVndf(v, l, m.alpha);
    }
    pdf = (1.0f - ps) * pdfCosineHemisphere(l.z) + ps * pdfSpec;
    return l;
}

VKP_END
#endif
