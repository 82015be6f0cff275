// The layers the glTF extensions put over the metallic-roughness BRDF (microfacet.h), in the
// C++/GLSL common subset: KHR_materials_sheen (a sheen lobe on the base) and
// KHR_materials_clearcoat (a clear coat over both, with its own roughness and normal).
//
// Conventions as in microfacet.h, except that the coat has a frame of its own (its normal: the
// clearcoat normal map, else the interpolated normal without the base's normal map), so the
// routines here take world-space directions and both frames (onb.h): v towards the viewer, l
// towards the light, both leaving the surface. Densities are in solid angle (sr^-1).
//
// Model (github.com/KhronosGroup/glTF, extensions/2.0/Khronos/KHR_materials_sheen and
// KHR_materials_clearcoat, "Implementation"), each layer over what lies below it:
//   f = f_coat + S_c (f_sheen + S_s f_base)
//   f_coat  = c D_ggx(h_c; a_c) V_ggx(v_c, l_c; a_c) F(v_c.h_c), F Schlick with f0 = 0.04, f90 = 1
//             (the coat's ior 1.5), in the coat frame; c = clearcoatFactor x texture R,
//             a_c = ggxAlpha(clearcoatRoughness)
//   f_sheen = sheenColor D_charlie(h; a_s) V_charlie(v, l; a_s) (Estevez and Kulla 2017,
//             "Production Friendly Microfacet Sheen BRDF": D = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi),
//             V = 1 / ((1 + Lambda(v) + Lambda(l)) 4 n.v n.l) with their fitted Lambda),
//             a_s = max(sheenRoughness^2, SHEEN_MIN_ALPHA)
//   S_s = min(1 - max(sheenColor) E_s(n.v), 1 - max(sheenColor) E_s(n.l))  (the extension's
//         "albedo scaling", E_s the sheen lobe's directional albedo, tabulated, taken as at most 1)
//   One departure: with the fitted Lambda the sheen lobe reflects MORE than arrives at grazing
//   views when its roughness is small (E_s(mu -> 0) = 5.8 at sheen roughness 0, 1.96 at 0.1, 0.85
//   at 0.26: host/render/sheen_albedo_table.cpp), so f_sheen is divided by max(1, E_s(n.v),
//   E_s(n.l)): reciprocal, and never more than 1 (tests/stats/test_layers.cpp).
//   S_c = min(1 - c E_c(n_c.v), 1 - c E_c(n_c.l)), E_c = 0.04 A + B of the GGX albedo table
//         (microfacet.h) at the coat's roughness: the same scaling for the coat.
// The extension's clearcoat text weights the layers below by 1 - c F(v.h), per half vector; like
// microfacet.h's base weight, that gains energy at grazing views (the specular and the layers
// below see different Fresnel terms). The albedo scaling in the min() form conserves energy (each
// layer passes on at most what it does not reflect, at both ends of the path) and is reciprocal,
// so f(v, l) = f(l, v) and white materials stay at or below 1 in a white furnace
// (tests/stats/test_layers.cpp).
//
// Sampling: one of three strategies picked with probabilities from the layers' albedos at v (coat
// c E_c, sheen (1 - c E_c) max(sheenColor) E_s, base the rest; each present one at least
// LAYER_MIN_PROBABILITY): the coat's visible normals (Heitz 2018) in its frame, the sheen lobe
// uniformly over the hemisphere (its D is broad and peaks at grazing half vectors, where cosine
// sampling is thin), the base's own mixture (microfacet.h). The pdf is the mixture of all three,
// so eval and pdf serve MIS for any direction.
#ifndef VKP_LAYERS_H
#define VKP_LAYERS_H
#include "glsl_compat.h"
#include "microfacet.h"
#include "onb.h"
#include "sampling.h"

VKP_BEGIN

/// Smallest sheen alpha (sheenRoughness^2): D_charlie is finite for any positive alpha, but its
/// exponent 1/alpha grows without bound.
const float SHEEN_MIN_ALPHA = 1.0e-3f;
/// The smallest probability of a present layer's own sampling strategy.
const float LAYER_MIN_PROBABILITY = 0.05f;
/// Schlick f0 of the coat (ior 1.5, glTF: "clearcoat ... has a fixed index of refraction of 1.5").
const float COAT_F0 = 0.04f;

/// Samples of the sheen albedo table along mu^(1/4), mu = n.v, and along the sheen roughness, each
/// over [0,1] (mu^(1/4): E_s climbs steeply within mu < 0.02, as the GGX table's does).
const uint SHEEN_ALBEDO_N = 32u;

/// Texel t = j * SHEEN_ALBEDO_N + i of the sheen albedo table: x = E_s at mu = (i/(N-1))^4 and
/// sheen roughness j/(N-1) (the other components 0). Defined outside this header: by the host
/// (host/render/sheen_albedo_table.cpp, from this header's sheen lobe) and by every kernel that
/// includes it (after the GGX table in the materials' texel buffer).
vec4 sheenAlbedoFetch(uint t);

/// The sheen lobe's directional albedo E_s(mu) (sheenColor 1), bilinear in (mu^(1/4), roughness).
VKP_FN float sheenAlbedo(float mu, float roughness) {
    float x = sqrt(sqrt(clamp(mu, 0.0f, 1.0f))) * float(SHEEN_ALBEDO_N - 1u);
    float y = clamp(roughness, 0.0f, 1.0f) * float(SHEEN_ALBEDO_N - 1u);
    uint i = min(uint(x), SHEEN_ALBEDO_N - 2u);
    uint j = min(uint(y), SHEEN_ALBEDO_N - 2u);
    float fx = x - float(i);
    float fy = y - float(j);
    uint t = j * SHEEN_ALBEDO_N + i;
    float a = sheenAlbedoFetch(t).x * (1.0f - fx) + sheenAlbedoFetch(t + 1u).x * fx;
    float b = sheenAlbedoFetch(t + SHEEN_ALBEDO_N).x * (1.0f - fx) + sheenAlbedoFetch(t + SHEEN_ALBEDO_N + 1u).x * fx;
    return a * (1.0f - fy) + b * fy;
}

/// Sheen alpha of a sheen roughness in [0,1] (alpha = roughness^2, clamped).
VKP_FN float sheenAlpha(float roughness) {
    float r = clamp(roughness, 0.0f, 1.0f);
    return max(r * r, SHEEN_MIN_ALPHA);
}

/// The "Charlie" sheen distribution D(h) = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi) (sr^-1; Estevez
/// and Kulla 2017, eq. 2) for a unit local half vector h; 0 for h.z <= 0.
VKP_FN float charlieD(vec3 h, float alpha) {
    if (!(h.z > 0.0f)) return 0.0f;
    float sin2 = max(0.0f, 1.0f - h.z * h.z);
    float inv = 1.0f / alpha;
    return (2.0f + inv) * pow(sin2, 0.5f * inv) * (0.5f * VKP_INV_PI);
}

/// Estevez and Kulla's fit L(x) of log Lambda (their table 1, interpolated in (1 - a)^2).
VKP_FN float charlieL(float x, float alpha) {
    float t = (1.0f - alpha) * (1.0f - alpha);
    float a = 21.5473f + (25.3245f - 21.5473f) * t;
    float b = 3.82987f + (3.32435f - 3.82987f) * t;
    float c = 0.19823f + (0.16801f - 0.19823f) * t;
    float d = -1.97760f + (-1.27393f + 1.97760f) * t;
    float e = -4.32054f + (-4.85967f + 4.32054f) * t;
    return a / (1.0f + b * pow(max(x, 0.0f), c)) + d * x + e;
}

/// Lambda(cos theta) of the Charlie distribution (Estevez and Kulla 2017, eq. 3: the fit mirrored
/// about cos theta = 0.5).
VKP_FN float charlieLambda(float c, float alpha) {
    c = clamp(c, 0.0f, 1.0f);
    if (c < 0.5f) return exp(charlieL(c, alpha));
    return exp(2.0f * charlieL(0.5f, alpha) - charlieL(1.0f - c, alpha));
}

/// f_sheen / sheenColor = D V (sr^-1) for local v, l above the surface, else 0.
VKP_FN float sheenLobe(vec3 v, vec3 l, float alpha) {
    if (!(v.z > 0.0f) || !(l.z > 0.0f)) return 0.0f;
    vec3 hv = v + l;
    vec3 h = hv / sqrt(dot(hv, hv));
    float lv = charlieLambda(v.z, alpha);
    float ll = charlieLambda(l.z, alpha);
    return charlieD(h, alpha) / ((1.0f + lv + ll) * 4.0f * v.z * l.z);
}

/// The coat's specular lobe D V F (sr^-1, without the factor c) for local v, l in the coat frame.
VKP_FN float coatLobe(vec3 v, vec3 l, float alpha) {
    if (!(v.z > 0.0f) || !(l.z > 0.0f)) return 0.0f;
    vec3 hv = v + l;
    vec3 h = hv / sqrt(dot(hv, hv));
    float f = COAT_F0 + (1.0f - COAT_F0) * schlickWeight(abs(dot(v, h)));
    return ggxD(h, alpha) * ggxVisibility(v, l, alpha) * f;
}

/// The coat's directional albedo E_c(mu) (Fresnel included) at its roughness.
VKP_FN float coatAlbedo(float mu, float roughness) {
    vec4 t = ggxAlbedoLookup(mu, roughness);
    return COAT_F0 * t.x + t.y;
}

/// What the layers of a glTF material add to its metallic-roughness base (makeGltfLayers).
struct GltfLayers {
    float coat;            ///< clearcoatFactor x texture R, [0,1] (0: no coat)
    float coatAlpha;       ///< ggxAlpha(coatRoughness)
    float coatRoughness;   ///< clearcoatRoughnessFactor x texture G, [0,1]
    vec3 sheenColor;       ///< sheenColorFactor x texture RGB, linear, [0,1] (0: no sheen)
    float sheenMax;        ///< max(sheenColor)
    float sheenAlpha;      ///< sheenAlpha(sheenRoughness)
    float sheenRoughness;  ///< sheenRoughnessFactor x texture A, [0,1]
};

VKP_FN GltfLayers makeGltfLayers(float coat, float coatRoughness, vec3 sheenColor, float sheenRoughness) {
    GltfLayers g;
    g.coat = clamp(coat, 0.0f, 1.0f);
    g.coatRoughness = clamp(coatRoughness, 0.0f, 1.0f);
    g.coatAlpha = ggxAlpha(coatRoughness);
    g.sheenColor = clamp(sheenColor, vec3(0.0f), vec3(1.0f));
    g.sheenMax = max(g.sheenColor.x, max(g.sheenColor.y, g.sheenColor.z));
    g.sheenRoughness = clamp(sheenRoughness, 0.0f, 1.0f);
    g.sheenAlpha = sheenAlpha(sheenRoughness);
    return g;
}

/// The layered material at one point: base BRDF, layers, the base's and the coat's frames.
struct LayeredBrdf {
    GltfBrdf base;
    GltfLayers layers;
    Onb frame;      ///< the base's shading frame (z = the shading normal)
    Onb coatFrame;  ///< the coat's frame (z = the coat normal)
};

/// f(v, l) times the cosine each lobe integrates against (the coat: with the coat normal; sheen and
/// base: with the shading normal), per channel, for world-space unit v, l. 0 where every lobe is 0.
VKP_FN vec3 evalLayeredCos(LayeredBrdf m, vec3 v, vec3 l) {
    vec3 vb = toLocal(m.frame, v);
    vec3 lb = toLocal(m.frame, l);
    vec3 base = vec3(0.0f);
    if (lb.z > 0.0f && vb.z > 0.0f) {
        base = evalGltfBrdf(m.base, vb, lb);
        if (m.layers.sheenMax > 0.0f) {
            float ev = sheenAlbedo(vb.z, m.layers.sheenRoughness);
            float el = sheenAlbedo(lb.z, m.layers.sheenRoughness);
            float ss = max(0.0f, min(1.0f - m.layers.sheenMax * min(ev, 1.0f), 1.0f - m.layers.sheenMax * min(el, 1.0f)));
            base = base * ss + m.layers.sheenColor * (sheenLobe(vb, lb, m.layers.sheenAlpha) / max(1.0f, max(ev, el)));
        }
        base *= lb.z;
    }
    if (!(m.layers.coat > 0.0f)) return base;
    vec3 vc = toLocal(m.coatFrame, v);
    vec3 lc = toLocal(m.coatFrame, l);
    float sc = min(1.0f - m.layers.coat * coatAlbedo(vc.z, m.layers.coatRoughness),
                   1.0f - m.layers.coat * coatAlbedo(lc.z, m.layers.coatRoughness));
    float coat = (lc.z > 0.0f) ? m.layers.coat * coatLobe(vc, lc, m.layers.coatAlpha) * lc.z : 0.0f;
    return base * max(sc, 0.0f) + vec3(coat);
}

/// The probabilities of the three strategies seen from world-space v: x coat, y sheen, z base.
VKP_FN vec3 layerProbabilities(LayeredBrdf m, vec3 v) {
    float vc = toLocal(m.coatFrame, v).z;
    bool coat = m.layers.coat > 0.0f && vc > 0.0f;  // a viewer below the coat's horizon sees no coat lobe
    float ec = coat ? m.layers.coat * coatAlbedo(vc, m.layers.coatRoughness) : 0.0f;
    float es = (m.layers.sheenMax > 0.0f) ? m.layers.sheenMax * min(sheenAlbedo(toLocal(m.frame, v).z, m.layers.sheenRoughness), 1.0f) : 0.0f;
    vec3 p = vec3(ec, (1.0f - ec) * es, (1.0f - ec) * (1.0f - es));
    if (coat) p.x = max(p.x, LAYER_MIN_PROBABILITY);
    if (m.layers.sheenMax > 0.0f) p.y = max(p.y, LAYER_MIN_PROBABILITY);
    p.z = max(p.z, LAYER_MIN_PROBABILITY);
    return p / (p.x + p.y + p.z);
}

/// pdfLayered with the strategies' probabilities p = layerProbabilities(m, v) already known.
VKP_FN float pdfLayeredGiven(LayeredBrdf m, vec3 v, vec3 l, vec3 p) {
    vec3 vb = toLocal(m.frame, v);
    vec3 lb = toLocal(m.frame, l);
    float pdf = p.z * pdfGltfBrdf(m.base, vb, lb);
    if (p.y > 0.0f && lb.z > 0.0f) pdf += p.y * (0.5f * VKP_INV_PI);
    if (p.x > 0.0f) pdf += p.x * pdfGgxVndf(toLocal(m.coatFrame, v), toLocal(m.coatFrame, l), m.layers.coatAlpha);
    return pdf;
}

/// Density (sr^-1) with which sampleLayered(m, v, .) returns the world-space direction l.
VKP_FN float pdfLayered(LayeredBrdf m, vec3 v, vec3 l) { return pdfLayeredGiven(m, v, l, layerProbabilities(m, v)); }

/// One world-space direction from the layered material seen from v, u in [0,1)^3: u.x picks the
/// strategy (coat, sheen, base, in that order of the probabilities) and is stretched back to
/// [0,1) for the base's own lobe choice; (u.y, u.z) drive the picked one. pdf = pdfLayered(m, v, l).
/// l may lie below the surface (f = 0 there).
VKP_FN vec3 sampleLayered(LayeredBrdf m, vec3 v, vec3 u, OUT(float) pdf) {
    vec3 p = layerProbabilities(m, v);
    vec2 u2 = vec2(u.y, u.z);
    vec3 l;
    if (u.x < p.x) {
        l = toWorld(m.coatFrame, sampleGgxVndf(toLocal(m.coatFrame, v), m.layers.coatAlpha, u2));
    } else if (u.x < p.x + p.y) {
        l = toWorld(m.frame, sampleUniformHemisphere(u2));
    } else {
        float ub = min((u.x - p.x - p.y) / p.z, 0.99999994f);
        float unused;
        l = toWorld(m.frame, sampleGltfBrdf(m.base, toLocal(m.frame, v), vec3(ub, u.y, u.z), unused));
    }
    pdf = pdfLayeredGiven(m, v, l, p);  // the probabilities once per sample
    return l;
}

VKP_END
#endif
