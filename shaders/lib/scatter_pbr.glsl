// The vertex of a glTF metallic-roughness material (MAT_PBR, shared/microfacet.h) for every
// sampler of pathtrace.comp. Included by pathtrace.comp after PathState and emitted().
//   bsdf    - one sample of the whole BRDF (specular VNDF or cosine lobe), throughput *= f cos / pdf;
//   light   - treated exactly like mis at this vertex: next-event estimation weighted by the power
//             heuristic, and the continuing BRDF sample keeps the emission it finds, weighted
//             against the light pdf. Plain NEE (skipping that emission) would be correct too, but a
//             near-specular lobe (alpha down to 1e-3) then shows small lights only through the
//             shadow ray, with enormous variance; MIS keeps the variance bounded;
//   mixture - the book's 0.5/0.5 mixture with the BRDF pdf in place of the cosine pdf;
//   mis     - light sample + BRDF sample, power heuristic, light pdf including its pick probability.
#ifndef VKP_SCATTER_PBR_GLSL
#define VKP_SCATTER_PBR_GLSL
#include "shared/microfacet.h"

/// microfacet.h's table access: the GGX albedo table follows the materials in their texel buffer
/// (host/render/ggx_albedo_table.cpp, renderer.cpp).
vec4 ggxAlbedoFetch(uint t) { return fetchF(uMaterials, int(frame.counts.w + t)); }

/// With shading normals (lib/surface.glsl): true if dir leaves on the other side of the geometric
/// surface than the viewer (ns faces the viewer); such directions get f = 0.
bool belowGeometric(vec3 dir, vec3 ns) { return HAS_VERTEX_ATTRIBUTES && !(dot(dir, ns) > 0.0f); }

/// Next-event estimation towards the environment (picked with probability pick) from a MAT_PBR
/// vertex: f cos L w / (pick pdf) if the shadow ray to infinity escapes, w the power heuristic
/// against the BRDF sample (light and mis alike, see above).
vec3 envDirectLightPbr(vec3 xo, vec3 ns, Onb f, GltfBrdf b, vec3 v, vec2 u, float pick, inout uint rays,
                       inout uint passes) {
    if (!envOn()) return vec3(0.0f);
    float pdf;
    vec3 dir = sampleEnv(ns, u, pdf, passes);
    vec3 l = toLocal(f, dir);
    if (!(pdf > 0.0f) || !(l.z > 0.0f) || belowGeometric(dir, ns)) return vec3(0.0f);
    vec3 le = envRadiance(dir);
    if (!(max(le.x, max(le.y, le.z)) > 0.0f)) return vec3(0.0f);
    rays++;
    if (traceAny(xo, dir, 0.0f, VKP_FAR, passes)) return vec3(0.0f);
    float pl = pick * pdf;
    return evalGltfBrdf(b, v, l) * l.z * le * (powerHeuristic(pl, pdfGltfBrdf(b, v, l)) / pl);
}

/// Scatter at a MAT_PBR hit x (geometric normal ns facing the incoming ray, shading normal nShade
/// from lib/surface.glsl (ns without one), primitive prim/p, surface parameters ab). The BRDF
/// lives in nShade's frame; directions below the geometric surface get f = 0 (no light leaks).
/// Adds next-event estimation to s.radiance, sets s.o, the new direction newDir, s.throughput and
/// the MIS state. Returns true when the path ends (no valid direction: f = 0). extraOffset: the
/// instance's part of the ray-origin offset (spawnRayOriginExtra; 0 for a world-space primitive).
bool scatterPbr(inout PathState s, GpuMaterial m, GpuPrim p, uint prim, vec2 ab, vec3 x, vec3 ns, vec3 nShade, float extraOffset, out vec3 newDir,
                inout uint rays, inout uint passes) {
    GltfBrdf b = makeGltfBrdf(m.m0.xyz, m.m3.x, m.m3.y, m.m2.w, m.m2.xyz);
    Onb f = onbFromNormal(nShade);
    vec3 v = toLocal(f, -s.d);
    float uStrategy = sampleNext(s.smp);
    vec3 u3 = vec3(sampleNext(s.smp), sampleNext2(s.smp));
    vec3 xo = spawnRayOriginExtra(p, ab, x, ns, extraOffset);
    newDir = s.d;
    bool nee = (SAMPLER == SAMPLER_LIGHT || SAMPLER == SAMPLER_MIS) && (emitterCount() > 0u || envOn());
    if (nee) {
        // Next-event estimation as at a Lambertian vertex (the environment with probability pEnv,
        // else an emitter by power), with f and the BRDF pdf.
        float pEnv = envPickProb();
        bool toEnv = uStrategy < pEnv;
        vec2 uLight = sampleNext2(s.smp);
        if (toEnv) s.radiance += s.throughput * envDirectLightPbr(xo, ns, f, b, v, uLight, pEnv, rays, passes);
        float pickPdf;
        float uPick = toEnv ? 0.0f : min((uStrategy - pEnv) / (1.0f - pEnv), 0.99999994f);
        uint lprim = floatBitsToUint(fetchLight(pickLightPower(uPick, pickPdf)).l0.x);
        pickPdf *= 1.0f - pEnv;
        GpuPrim lp = fetchPrim(lprim);
        LightSample ls = sampleLightPrim(lp, x, uLight);
        vec3 lLight = toLocal(f, ls.dir);
        bool self = lprim == prim && primKind(p) != PRIM_SPHERE;
        if (!toEnv && ls.pdf > 0.0f && lLight.z > 0.0f && !belowGeometric(ls.dir, ns) && !self) {
            GpuMaterial lm = fetchMaterial(primMaterial(lp));
            vec3 lx = x + ls.dist * ls.dir;
            emissiveTextureAt(lprim, lp, lx, lm);  // lib/surface.glsl
            vec3 nl = primNormal(lp, lx);
            vec3 le = emitted(lm, floatBitsToUint(lm.m0.w), ls.dir, nl);
            if (max(le.x, max(le.y, le.z)) > 0.0f) {
                rays++;
                vec4 sr = shadowRayTo(xo, lx, nl, primOffsetDistance(lp, vec2(1.0f, 1.0f), nl));
                if (!traceAny(xo, sr.xyz, 0.0f, sr.w, passes)) {
                    float pl = ls.pdf * pickPdf;
                    float w = powerHeuristic(pl, pdfGltfBrdf(b, v, lLight));
                    s.radiance += s.throughput * evalGltfBrdf(b, v, lLight) * lLight.z * le * (w / pl);
                }
            }
        }
    }
    float pdf;
    vec3 l;
    if (SAMPLER == SAMPLER_MIXTURE && mixtureLightCount() > 0u) {
        if (uStrategy < 0.5f) {
            l = sampleGltfBrdf(b, v, u3, pdf);
            newDir = toWorld(f, l);
        } else if (envOn() && pickUniform(2.0f * uStrategy - 1.0f, mixtureLightCount()) == lightCount()) {
            float envPdf;  // the environment: the last entry of the light list (lib/environment.glsl)
            newDir = sampleEnv(ns, u3.yz, envPdf, passes);
            if (!(envPdf > 0.0f)) return true;
            l = toLocal(f, newDir);
        } else {
            uint li = pickUniform(2.0f * uStrategy - 1.0f, mixtureLightCount());  // < lightCount() here
            LightSample ls = sampleLightPrim(fetchPrim(floatBitsToUint(fetchLight(li).l0.x)), x, u3.yz);
            if (!(ls.pdf > 0.0f)) return true;  // no direction from this strategy: the sample is 0
            newDir = ls.dir;
            l = toLocal(f, newDir);
        }
        pdf = 0.5f * pdfGltfBrdf(b, v, l) + 0.5f * pdfLightsAndEnv(x, ns, newDir, passes);
    } else {
        l = sampleGltfBrdf(b, v, u3, pdf);
        newDir = toWorld(f, l);
    }
    if (!(l.z > 0.0f) || !(pdf > 0.0f) || belowGeometric(newDir, ns)) return true;  // below the surface: f = 0
    s.throughput *= evalGltfBrdf(b, v, l) * (l.z / pdf);
    if (nee) {
        // light and mis: the emission this sample finds is weighted against the light sample.
        s.countEmission = true;
        s.prevX = x;
        s.prevN = ns;
        s.prevBsdfPdf = pdf;
    }
    s.o = xo;
    return false;
}

#endif
