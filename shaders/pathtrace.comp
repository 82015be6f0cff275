#version 460
// vkpath's path tracer: one invocation per pixel adds push.batch.y samples to that pixel's sums.
// Unidirectional path tracing ("Ray Tracing: The Rest of Your Life", sec. 2-12) with three ways
// to choose the direction at a diffuse vertex (SAMPLER, a specialization constant):
//   bsdf    - cosine-weighted; emission counted wherever a ray hits it;
//   light   - next-event estimation: one sampled light + shadow ray; emission found by the
//             continuing cosine-sampled ray is then skipped (it was already counted);
//   mixture - the book's mixture_pdf: 0.5 cosine + 0.5 light (picked uniformly), pdf the sum.
// Every sample's random numbers depend only on (pixel, sample index, seed), and each sample is added
// to the running sums in sample order, so any split of samples over dispatches gives the same bits.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "lib/bindings.glsl"
#include "shared/intersect.h"
#include "shared/rng.h"
#include "shared/onb.h"
#include "shared/sampling.h"
#include "shared/scatter.h"
#include "shared/ray_offset.h"
#include "lib/scene_lights.glsl"
#include "lib/traverse.glsl"

struct PathResult {
    vec3 radiance;
    uint rays;
    bool cut;  // stopped by the loop-pass guard (lavapipe's silent loop limit is near)
};

/// Radiance emitted by material m towards direction -d at a surface with geometric normal n.
vec3 emitted(GpuMaterial m, uint mflags, vec3 d, vec3 n) {
    if (!HAS_EMITTERS || (mflags & MATF_EMITS) == 0u) return vec3(0.0f);
    bool front = dot(d, n) < 0.0f;
    bool oneSided = (mflags & 15u) == MAT_DIFFUSE_LIGHT && (mflags & MATF_TWO_SIDED) == 0u;
    return (front || !oneSided) ? vec3(m.m1.x, m.m1.y, m.m1.z) : vec3(0.0f);
}

PathResult tracePath(vec3 o, vec3 d, inout uint rng, inout uint passes) {
    PathResult r;
    r.radiance = vec3(0.0f);
    r.rays = 0u;
    r.cut = false;
    vec3 throughput = vec3(1.0f);
    bool countEmission = true;  // false right after a diffuse vertex that did next-event estimation
    uint maxDepth = frame.size.z;
    for (uint depth = 0u; depth < maxDepth; ++depth) {
        passes++;
        uint prim;
        float t;
        vec2 ab;
        r.rays++;
        bool hit = traceClosest(o, d, 0.0f, VKP_FAR, prim, t, ab, passes);
        if (passes >= VKP_MAX_PASSES) { r.cut = true; break; }
        if (!hit) {
            r.radiance += throughput * vec3(frame.background.x, frame.background.y, frame.background.z);
            break;
        }
        GpuPrim p = fetchPrim(prim);
        vec3 x = o + t * d;
        vec3 ng = primNormal(p, x);
        bool frontFace = dot(d, ng) < 0.0f;
        vec3 ns = frontFace ? ng : -ng;  // faces the incoming ray
        GpuMaterial m = fetchMaterial(primMaterial(p));
        uint mflags = floatBitsToUint(m.m0.w);
        uint mtype = mflags & 15u;
        vec3 albedo = vec3(m.m0.x, m.m0.y, m.m0.z);
        if (countEmission) r.radiance += throughput * emitted(m, mflags, d, ng);
        countEmission = true;
        if (HAS_EMITTERS && mtype == MAT_DIFFUSE_LIGHT) break;  // lights do not scatter

        vec3 newDir = d;
        if (HAS_LAMBERTIAN && mtype == MAT_LAMBERTIAN) {
            float uStrategy = rngNext(rng);
            vec2 u2 = rngNext2(rng);
            vec3 xo = offsetRayOrigin(x, ns);
            if (SAMPLER == SAMPLER_LIGHT && lightCount() > 0u) {
                // Next-event estimation at this vertex, then continue with a cosine sample.
                float pickPdf;
                GpuPrim lp = fetchPrim(floatBitsToUint(fetchLight(pickLight(uStrategy, pickPdf)).l0.x));
                LightSample ls = sampleLightPrim(lp, x, rngNext2(rng));
                float cosL = dot(ls.dir, ns);
                GpuMaterial lm = fetchMaterial(primMaterial(lp));
                uint lflags = floatBitsToUint(lm.m0.w);
                if (ls.pdf > 0.0f && cosL > 0.0f && (lflags & MATF_EMITS) != 0u) {
                    vec3 lx = x + ls.dist * ls.dir;
                    vec3 le = emitted(lm, lflags, ls.dir, primNormal(lp, lx));
                    r.rays++;
                    if (max(le.x, max(le.y, le.z)) > 0.0f &&
                        !traceAny(xo, ls.dir, 0.0f, ls.dist * 0.9999f, passes))
                        r.radiance += throughput * albedo * VKP_INV_PI * cosL * le / (ls.pdf * pickPdf);
                }
                countEmission = false;
                newDir = sampleLambertian(ns, u2);
                throughput *= albedo;
            } else if (SAMPLER == SAMPLER_MIXTURE && lightCount() > 0u) {
                if (uStrategy < 0.5f) {
                    newDir = sampleLambertian(ns, u2);
                } else {
                    float pickPdf;
                    uint li = pickLight(2.0f * uStrategy - 1.0f, pickPdf);
                    LightSample ls = sampleLightPrim(fetchPrim(floatBitsToUint(fetchLight(li).l0.x)), x, u2);
                    newDir = ls.dir;
                    if (!(ls.pdf > 0.0f)) break;  // no direction from this strategy: the sample is 0
                }
                float cosN = dot(newDir, ns);
                if (!(cosN > 0.0f)) break;  // below the surface: f = 0
                float pdf = 0.5f * pdfCosineHemisphere(cosN) + 0.5f * pdfLights(x, newDir, passes);
                throughput *= albedo * VKP_INV_PI * cosN / pdf;
            } else {
                newDir = sampleLambertian(ns, u2);
                throughput *= albedo;  // (albedo/pi) cos / (cos/pi)
            }
            o = xo;
        } else if (HAS_METAL && mtype == MAT_METAL) {
            bool absorbed;
            newDir = scatterMetal(d, ns, m.m1.w, vec3(rngNext(rng), rngNext(rng), rngNext(rng)), absorbed);
            if (absorbed) break;
            throughput *= albedo;
            o = offsetRayOrigin(x, ns);
        } else if (HAS_DIELECTRIC && mtype == MAT_DIELECTRIC) {
            newDir = scatterDielectric(d, ns, frontFace, m.m1.w, (mflags & MATF_FRESNEL_EXACT) != 0u, rngNext(rng));
            o = offsetRayOrigin(x, dot(newDir, ns) > 0.0f ? ns : -ns);
        }
        d = newDir;

        // Russian roulette (unbiased): continue with probability q, divide by q.
        if (depth + 1u >= frame.counts.y) {
            float q = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95f);
            if (rngNext(rng) >= q) break;
            throughput /= q;
        }
    }
    return r;
}

void main() {
    uvec2 pix = gl_GlobalInvocationID.xy;
    uint width = frame.size.x;
    if (pix.x >= width || pix.y >= frame.size.y) return;
    uint pixel = pix.y * width + pix.x;

    vec4 sum = accumSum[pixel];
    vec4 sq = accumSq[pixel];
    uint rays = 0u;
    uint nonfinite = 0u;
    uint cut = 0u;
    uint passes = 0u;  // loop passes of this invocation, all loops together (lavapipe's limit is per invocation)
    vec3 pixel00 = vec3(frame.pixel00.x, frame.pixel00.y, frame.pixel00.z);
    vec3 du = vec3(frame.pixelDu.x, frame.pixelDu.y, frame.pixelDu.z);
    vec3 dv = vec3(frame.pixelDv.x, frame.pixelDv.y, frame.pixelDv.z);
    vec3 origin = vec3(frame.origin.x, frame.origin.y, frame.origin.z);
    for (uint k = 0u; k < push.batch.y; ++k) {
        passes++;
        uint rng = rngInit(pixel, push.batch.x + k, frame.size.w);
        vec2 jitter = rngNext2(rng) - vec2(0.5f);  // box filter over the pixel's square
        vec3 target = pixel00 + (float(pix.x) + jitter.x) * du + (float(pix.y) + jitter.y) * dv;
        vec3 o = origin;
        vec2 lens = rngNext2(rng);  // drawn in every variant, so variants see the same random numbers
        if (HAS_DEFOCUS) {
            vec2 disk = sampleUniformDisk(lens);
            o += disk.x * vec3(frame.defocusU.x, frame.defocusU.y, frame.defocusU.z) +
                 disk.y * vec3(frame.defocusV.x, frame.defocusV.y, frame.defocusV.z);
        }
        PathResult pr = tracePath(o, normalize(target - o), rng, passes);
        rays += pr.rays;
        if (pr.cut) cut++;
        vec3 L = pr.radiance;
        if (any(isnan(L)) || any(isinf(L))) {
            nonfinite++;
        } else {
            sum += vec4(L, 1.0f);
            sq += vec4(L * L, 0.0f);
        }
    }
    accumSum[pixel] = sum;
    accumSq[pixel] = sq;

    uint old = atomicAdd(counters[COUNTER_RAYS_LO], rays);
    if (old + rays < old) atomicAdd(counters[COUNTER_RAYS_HI], 1u);
    if (nonfinite > 0u) atomicAdd(counters[COUNTER_NONFINITE], nonfinite);
    if (cut > 0u) atomicAdd(counters[COUNTER_LOOP_GUARD], cut);
}
