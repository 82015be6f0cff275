#version 460
// vkpath's path tracer: one invocation per pixel adds push.batch.y samples to that pixel's sums.
// Unidirectional path tracing ("Ray Tracing: The Rest of Your Life", sec. 2-12) with four ways
// to sample at a diffuse vertex (SAMPLER, a specialization constant); "light" includes the
// environment (lib/environment.glsl) when the scene has one:
//   bsdf    - cosine-weighted; emission counted wherever a ray hits it;
//   light   - next-event estimation: one emitter picked by power + shadow ray; emission found by
//             the continuing cosine-sampled ray is then skipped (it was already counted);
//   mixture - the book's mixture_pdf: 0.5 cosine + 0.5 light (picked uniformly), pdf the sum;
//   mis     - the light sample of `light` and the cosine sample both count, each weighted by the
//             power heuristic (Veach 1997, ch. 9), the light pdf including its pick probability.
// At a glTF metallic-roughness vertex (MAT_PBR) the BRDF sample replaces the cosine sample and
// `light` works as `mis` (lib/scatter_pbr.glsl).
// Every sample's random numbers depend only on (pixel, sample index, seed), and each sample is added
// to the running sums in sample order, so any split of samples over dispatches gives the same bits.
#extension GL_GOOGLE_include_directive : require
// Workgroup size: 8x8 by default, any other from specialization constants 19, 20 (`--workgroup`).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1, local_size_x_id = 19, local_size_y_id = 20) in;

#include "lib/bindings.glsl"
#include "shared/intersect.h"
#include "shared/rng.h"
#define VKP_SEQUENCE_SOBOL (SEQUENCE == SEQUENCE_SOBOL)
#include "shared/sample_stream.h"
#include "shared/onb.h"
#include "shared/sampling.h"
#include "shared/scatter.h"
#include "shared/ray_offset.h"
#include "shared/compensated_sum.h"
#include "lib/scene_lights.glsl"
#include "lib/surface.glsl"
#include "lib/alpha.glsl"  // defines the traversal's any-hit hook
#include "lib/traverse.glsl"
#include "lib/environment.glsl"

// One path in flight. A path is advanced one bounce per pass of the main loop; when it ends, its
// radiance is added to the pixel and the pixel's next sample starts in the same loop ("path
// regeneration"). On lavapipe a loop runs until the last of its 8 lanes is done, so keeping every
// lane busy with the next sample, instead of waiting for the longest path, is what makes several
// samples per dispatch pay.
struct PathState {
    vec3 o;           // ray origin (world units)
    vec3 d;           // unit ray direction
    vec3 throughput;  // product of f cos / pdf so far
    vec3 radiance;    // radiance gathered so far
    uint depth;       // rays traced along the path so far (camera ray = 1)
    SampleStream smp; // this sample's random numbers (shared/sample_stream.h: sequence, dimension layout)
    bool countEmission;  // false right after a diffuse vertex that did next-event estimation (light)
    vec3 prevX;          // mis: the diffuse vertex the current ray left from
    vec3 prevN;          // mis: its normal (facing the ray that reached it; pdfEnv needs it)
    float prevBsdfPdf;   // mis: solid-angle pdf of the BSDF sample that made the current ray; 0 after
                         // the camera or a specular bounce (emission then counts fully)
};

/// Radiance emitted by material m towards direction -d at a surface with geometric normal n.
vec3 emitted(GpuMaterial m, uint mflags, vec3 d, vec3 n) {
    if (!HAS_EMITTERS || (mflags & MATF_EMITS) == 0u) return vec3(0.0f);
    bool front = dot(d, n) < 0.0f;
    bool oneSided = (mflags & 15u) == MAT_DIFFUSE_LIGHT && (mflags & MATF_TWO_SIDED) == 0u;
    return (front || !oneSided) ? vec3(m.m1.x, m.m1.y, m.m1.z) : vec3(0.0f);
}

#include "lib/scatter_pbr.glsl"

/// Start sample `sampleIndex` of pixel `pix`: the camera ray of the book's camera with a box filter
/// over the pixel's square and, if the variant has it, a point on the defocus disk.
PathState startPath(uvec2 pix, uint pixel, uint sampleIndex) {
    PathState s;
    s.smp = sampleStreamInit(pixel, sampleIndex, frame.size.w, push.adaptive.x != 0u);
    vec2 jitter = sampleNext2(s.smp) - vec2(0.5f);
    vec3 pixel00 = vec3(frame.pixel00.x, frame.pixel00.y, frame.pixel00.z);
    vec3 du = vec3(frame.pixelDu.x, frame.pixelDu.y, frame.pixelDu.z);
    vec3 dv = vec3(frame.pixelDv.x, frame.pixelDv.y, frame.pixelDv.z);
    vec3 target = pixel00 + (float(pix.x) + jitter.x) * du + (float(pix.y) + jitter.y) * dv;
    s.o = vec3(frame.origin.x, frame.origin.y, frame.origin.z);
    vec2 lens = sampleNext2(s.smp);  // drawn in every variant, so variants see the same random numbers
    if (HAS_DEFOCUS) {
        vec2 disk = sampleUniformDisk(lens);
        s.o += disk.x * vec3(frame.defocusU.x, frame.defocusU.y, frame.defocusU.z) +
               disk.y * vec3(frame.defocusV.x, frame.defocusV.y, frame.defocusV.z);
    }
    s.d = normalize(target - s.o);
    s.throughput = vec3(1.0f);
    s.radiance = vec3(0.0f);
    s.depth = 0u;
    s.countEmission = true;
    s.prevX = s.o;
    s.prevN = vec3(0.0f, 0.0f, 1.0f);
    s.prevBsdfPdf = 0.0f;
    return s;
}

/// Trace the path's current ray and scatter at what it hits. Returns true when the path has ended
/// (escaped, absorbed, hit a light, stopped by Russian roulette or max_depth).
bool bounce(inout PathState s, inout uint rays, inout uint passes) {
    uint prim;
    float t;
    vec2 ab;
    rays++;
    s.depth++;
    sampleStartVertex(s.smp, s.depth);  // the numbers of the vertex this ray finds
    uint inst;
    bool hit = traceClosestInstance(s.o, s.d, 0.0f, VKP_FAR, prim, t, ab, inst, passes);
    if (!hit) {
        s.radiance += s.throughput * envEscaped(s.d, s.prevN, s.prevBsdfPdf, s.countEmission);  // lib/environment.glsl
        return true;
    }
    GpuPrim p = fetchPrim(prim);
    vec2 abAttr = ab;          // surface parameters of the stored triangle (its attribute record's order)
    float extraOffset = 0.0f;  // an instance's transform rounding (shared/instance.h)
    GpuPrim pObj = p;
    GpuInstance ins;
    bool instanced = HAS_INSTANCES && inst != GPU_NO_INSTANCE;
    if (instanced) {
        // An instance's triangle: shade it placed in the world, as the flattening loader places it.
        ins = fetchInstance(inst);
        p = instanceWorldPrim(ins, pObj);
        ab = instanceWorldAb(ins, ab);
    }
    vec3 x = primHitPoint(p, s.o, s.d, t, ab);  // from the primitive, not o + t d (shared/ray_offset.h)
    vec3 ng = primNormal(p, x);
    if (instanced) extraOffset = instanceOffsetDistance(ins, pObj, abAttr, x, ng);
    bool frontFace = dot(s.d, ng) < 0.0f;
    vec3 ns = frontFace ? ng : -ng;  // faces the incoming ray
    GpuMaterial m = fetchMaterial(primMaterial(p));
    vec3 nShade = surfaceAt(prim, p, abAttr, ns, s.d, primMaterial(p), m, inst);  // textures, shading normal (lib/surface.glsl)
    uint mflags = floatBitsToUint(m.m0.w);
    uint mtype = mflags & 15u;
    vec3 albedo = vec3(m.m0.x, m.m0.y, m.m0.z);
    if (SAMPLER == SAMPLER_MIS) {
        // Emission found by BSDF sampling, weighted against the light sample that could have found
        // it from the previous vertex (power heuristic).
        vec3 le = emitted(m, mflags, s.d, ng);
        float w = 1.0f;
        int li = primLight(p);
        if (s.prevBsdfPdf > 0.0f && li >= 0)
            w = powerHeuristic(s.prevBsdfPdf, pickPdfPower(uint(li)) * (1.0f - envPickProb()) * pdfLightPrim(p, s.prevX, s.d));
        s.radiance += s.throughput * le * w;
    } else if (s.countEmission) {
        // `light` after a MAT_PBR vertex (which set prevBsdfPdf) weights like mis; else w = 1.
        float w = 1.0f;
        int li = primLight(p);
        if (HAS_PBR && SAMPLER == SAMPLER_LIGHT && s.prevBsdfPdf > 0.0f && li >= 0)
            w = powerHeuristic(s.prevBsdfPdf, pickPdfPower(uint(li)) * (1.0f - envPickProb()) * pdfLightPrim(p, s.prevX, s.d));
        s.radiance += s.throughput * emitted(m, mflags, s.d, ng) * w;
    }
    s.countEmission = true;
    s.prevBsdfPdf = 0.0f;
    if (HAS_EMITTERS && mtype == MAT_DIFFUSE_LIGHT) return true;  // lights do not scatter
    if (s.depth >= frame.size.z) return true;                     // max_depth rays per path

    vec3 newDir = s.d;
    if (HAS_LAMBERTIAN && mtype == MAT_LAMBERTIAN) {
        float uStrategy = sampleNext(s.smp);
        vec2 u2 = sampleNext2(s.smp);
        vec3 xo = spawnRayOriginExtra(p, ab, x, ns, extraOffset);
        if ((SAMPLER == SAMPLER_LIGHT || SAMPLER == SAMPLER_MIS) && (emitterCount() > 0u || envOn())) {
            // Next-event estimation: the environment with probability pEnv (lib/environment.glsl),
            // else one emitter picked by power (probability (1 - pEnv) x its share), one point on
            // it, a shadow ray.
            float pEnv = envPickProb();
            bool toEnv = uStrategy < pEnv;
            vec2 uLight = sampleNext2(s.smp);
            if (toEnv) s.radiance += s.throughput * envDirectLight(xo, ns, albedo, uLight, pEnv, rays, passes);
            float pickPdf;
            float uPick = toEnv ? 0.0f : min((uStrategy - pEnv) / (1.0f - pEnv), 0.99999994f);
            uint lprim = floatBitsToUint(fetchLight(pickLightPower(uPick, pickPdf)).l0.x);
            pickPdf *= 1.0f - pEnv;
            GpuPrim lp = fetchPrim(lprim);
            LightSample ls = sampleLightPrim(lp, x, uLight);
            float cosL = dot(ls.dir, ns);
            // A flat light cannot light itself: no sample of it from a point on it (rounding may put
            // the hit point on either side of its plane). A sphere can (from inside).
            bool self = lprim == prim && primKind(p) != PRIM_SPHERE;
            if (!toEnv && ls.pdf > 0.0f && cosL > 0.0f && !self) {
                GpuMaterial lm = fetchMaterial(primMaterial(lp));
                vec3 lx = x + ls.dist * ls.dir;
                emissiveTextureAt(lprim, lp, lx, lm);  // lib/surface.glsl
                vec3 le = emitted(lm, floatBitsToUint(lm.m0.w), ls.dir, primNormal(lp, lx));
                if (max(le.x, max(le.y, le.z)) > 0.0f) {  // no shadow ray towards a light's back
                    rays++;
                    vec3 nl = primNormal(lp, lx);
                    vec4 sr = shadowRayTo(xo, lx, nl, primOffsetDistance(lp, vec2(1.0f, 1.0f), nl));  // between offset end points
                    if (!traceAny(xo, vec3(sr.x, sr.y, sr.z), 0.0f, sr.w, passes)) {
                        float pl = ls.pdf * pickPdf;
                        float w = (SAMPLER == SAMPLER_MIS) ? powerHeuristic(pl, pdfCosineHemisphere(cosL)) : 1.0f;
                        s.radiance += s.throughput * albedo * VKP_INV_PI * cosL * le * (w / pl);
                    }
                }
            }
            // Continue with a cosine sample; `light` then ignores the emission it finds, `mis`
            // weights it.
            s.countEmission = (SAMPLER == SAMPLER_MIS);
            newDir = sampleLambertian(ns, u2);
            s.prevX = x;
            s.prevN = ns;
            s.prevBsdfPdf = pdfCosineHemisphere(dot(newDir, ns));
            s.throughput *= albedo;
        } else if (SAMPLER == SAMPLER_MIXTURE && mixtureLightCount() > 0u) {
            if (uStrategy < 0.5f) {
                newDir = sampleLambertian(ns, u2);
            } else if (envOn() && pickUniform(2.0f * uStrategy - 1.0f, mixtureLightCount()) == lightCount()) {
                float envPdf;  // the environment: the last entry of the light list (lib/environment.glsl)
                newDir = sampleEnv(ns, u2, envPdf, passes);
                if (!(envPdf > 0.0f)) return true;
            } else {
                uint li = pickUniform(2.0f * uStrategy - 1.0f, mixtureLightCount());  // < lightCount() here
                LightSample ls = sampleLightPrim(fetchPrim(floatBitsToUint(fetchLight(li).l0.x)), x, u2);
                newDir = ls.dir;
                if (!(ls.pdf > 0.0f)) return true;  // no direction from this strategy: the sample is 0
            }
            float cosN = dot(newDir, ns);
            if (!(cosN > 0.0f)) return true;  // below the surface: f = 0
            float pdf = 0.5f * pdfCosineHemisphere(cosN) + 0.5f * pdfLightsAndEnv(x, ns, newDir, passes);
            s.throughput *= albedo * VKP_INV_PI * cosN / pdf;
        } else {
            newDir = sampleLambertian(ns, u2);
            s.throughput *= albedo;  // (albedo/pi) cos / (cos/pi)
        }
        s.o = xo;
    } else if (HAS_METAL && mtype == MAT_METAL) {
        bool absorbed;
        newDir = scatterMetal(s.d, ns, m.m1.w, vec3(sampleNext(s.smp), sampleNext(s.smp), sampleNext(s.smp)), absorbed);
        if (absorbed) return true;
        s.throughput *= albedo;
        s.o = spawnRayOriginExtra(p, ab, x, ns, extraOffset);
    } else if (HAS_DIELECTRIC && mtype == MAT_DIELECTRIC) {
        newDir = scatterDielectric(s.d, ns, frontFace, m.m1.w, (mflags & MATF_FRESNEL_EXACT) != 0u, sampleNext(s.smp));
        s.o = spawnRayOriginExtra(p, ab, x, dot(newDir, ns) > 0.0f ? ns : -ns, extraOffset);
    } else if (HAS_PBR && mtype == MAT_PBR) {
        if (scatterPbr(s, m, p, prim, ab, x, ns, nShade, extraOffset, newDir, rays, passes)) return true;
    }
    s.d = newDir;

    // Russian roulette (unbiased): continue with probability q, divide by q.
    if (s.depth >= frame.counts.y) {
        float q = min(max(s.throughput.x, max(s.throughput.y, s.throughput.z)), 0.95f);
        if (sampleNext(s.smp) >= q) return true;
        s.throughput /= q;
    }
    return false;
}

void main() {
    // Scrambled tile order: lavapipe hands each thread a contiguous run of workgroups, so a
    // permutation that spreads each run over the image balances cheap and expensive regions
    // (frame.tiles.z = 1: row order, `--tile-order linear`).
    uint width = frame.size.x;
    bool adaptive = push.adaptive.x != 0u;
    uvec2 pix;
    uint pixel;
    if (!adaptive) {
        uint group = gl_WorkGroupID.y * frame.tiles.x + gl_WorkGroupID.x;
        uint tile = (group * frame.tiles.z) % frame.tiles.y;  // host keeps the product below 2^32
        pix = uvec2(tile % frame.tiles.x, tile / frame.tiles.x) * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
        if (pix.x >= width || pix.y >= frame.size.y) return;
        pixel = pix.y * width + pix.x;
    } else {
        // Only the pixels still active, packed: no lane idles on a converged pixel.
        uint group = gl_WorkGroupID.y * push.adaptive.w + gl_WorkGroupID.x;
        if (group >= push.adaptive.y) return;
        uint slot = ((group * push.adaptive.z) % push.adaptive.y) * (gl_WorkGroupSize.x * gl_WorkGroupSize.y) + gl_LocalInvocationIndex;
        if (slot >= push.adaptive.x) return;
        pixel = activePixels[slot];
        pix = uvec2(pixel % width, pixel / width);
    }

    vec4 sum = accumSum[2u * pixel];
    vec4 sumLo = accumSum[2u * pixel + 1u];
    vec4 sq = accumSq[2u * pixel];
    vec4 sqLo = accumSq[2u * pixel + 1u];
    vec4 dSum = vec4(0.0f);
    vec4 dSq = vec4(0.0f);
    if (adaptive) {
        dSum = decisionSums[2u * pixel];
        dSq = decisionSums[2u * pixel + 1u];
    }
    uint rays = 0u;
    uint nonfinite = 0u;
    uint cut = 0u;
    uint passes = 0u;  // loop passes of this invocation, all loops together (lavapipe's limit is per invocation)
    uint k = 0u;       // samples of this dispatch finished
    PathState s = startPath(pix, pixel, push.batch.x);
    while (k < push.batch.y) {
        passes++;
        bool ended = bounce(s, rays, passes);
        if (passes >= VKP_MAX_PASSES) {  // lavapipe's silent loop limit is near: stop, and say so
            cut++;
            break;
        }
        if (ended) {
            // Samples are added in sample order, so any split over dispatches gives the same sums.
            vec3 L = s.radiance;
            if (any(isnan(L)) || any(isinf(L))) {
                nonfinite++;
            } else if (adaptive && ((push.batch.x + k) & 3u) == 3u) {
                dSum += vec4(L, 1.0f);  // decision stream: steers adaptive sampling, not in the image
                dSq += vec4(L * L, 0.0f);
            } else {
                addCompensated(sum, sumLo, vec4(L, 1.0f));
                addCompensated(sq, sqLo, vec4(L * L, 0.0f));
            }
            k++;
            s = startPath(pix, pixel, push.batch.x + min(k, push.batch.y - 1u));
        }
    }
    accumSum[2u * pixel] = sum;
    accumSum[2u * pixel + 1u] = sumLo;
    accumSq[2u * pixel] = sq;
    accumSq[2u * pixel + 1u] = sqLo;
    if (adaptive) {
        decisionSums[2u * pixel] = dSum;
        decisionSums[2u * pixel + 1u] = dSq;
    }

    uint old = atomicAdd(counters[COUNTER_RAYS_LO], rays);
    if (old + rays < old) atomicAdd(counters[COUNTER_RAYS_HI], 1u);
    if (nonfinite > 0u) atomicAdd(counters[COUNTER_NONFINITE], nonfinite);
    if (cut > 0u) atomicAdd(counters[COUNTER_LOOP_GUARD], cut);
    atomicMax(counters[COUNTER_MAX_PASSES], passes);
}
