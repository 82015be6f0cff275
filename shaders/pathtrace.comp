#version 460
// vkpath's path tracer: one invocation per pixel adds push.batch.y samples to that pixel's sums.
// Unidirectional path tracing ("Ray Tracing: The Rest of Your Life", sec. 2-12). bounce() is the
// integrator and only that: what a ray finds (lib/hit.glsl), the light it finds weighted by MIS
// (lib/direct_light.glsl foundLightWeight, lib/environment.glsl envEscaped), the BSDF there
// (shared/bsdf.h), next-event estimation (lib/direct_light.glsl), the next direction from the
// BSDF or from the book's mixture (lib/mixture.glsl), Russian roulette. The samplers (SAMPLER, a
// specialization constant) differ only in those calls:
//   bsdf    - BSDF sampling only; the light a ray finds counts fully;
//   light   - next-event estimation: one light picked by power + shadow ray; the light the
//             continuing BSDF sample finds is then skipped (it was already counted), except at a
//             glossy BSDF (the glTF BRDF), where both are weighted as under mis;
//   mixture - the book's mixture_pdf: 0.5 BSDF + 0.5 lights (picked uniformly), pdf the sum;
//   mis     - the light sample and the BSDF sample both count, each weighted by the power
//             heuristic (Veach 1997, ch. 9), the light pdf including its pick probability.
// Every sample's random numbers depend only on (pixel, sample index, seed), and each sample is added
// to the running sums in sample order, so any split of samples over dispatches gives the same bits.
#extension GL_GOOGLE_include_directive : require

#include "lib/bindings.glsl"  // the bindings, and every specialization constant (lib/spec_constants.glsl)
#include "shared/rng.h"
#define VKP_SEQUENCE_SOBOL (SEQUENCE == SEQUENCE_SOBOL)
#include "shared/sample_stream.h"
#include "shared/sampling.h"
#include "shared/compensated_sum.h"
#include "lib/surface.glsl"
#include "lib/alpha.glsl"  // defines the traversal's any-hit hook
#include "lib/traverse.glsl"
#include "lib/lights.glsl"
#include "lib/environment.glsl"
#include "shared/bsdf.h"
#include "lib/hit.glsl"
#include "lib/direct_light.glsl"
#include "lib/mixture.glsl"
#include "lib/media.glsl"
#include "shared/aov.h"

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
    vec3 prevN;          // mis: its normal (facing the ray that reached it; pdfEnv needs it; 0 in a medium)
    float prevBsdfPdf;   // mis: solid-angle pdf of the BSDF sample that made the current ray; 0 after
                         // the camera or a specular bounce (emission then counts fully)
    vec3 sigma;          // HAS_ABSORPTION: absorption coefficient of the dielectric the ray travels
                         // inside (1/world unit; 0 outside): set when a ray refracts in, cleared
                         // when it refracts out (closed, non-nested glass)
    // HAS_AOV (shared/aov.h): the feature values of this sample.
    vec3 aovTint;        // product of the sampled weights of the mirrors and glass passed so far
    vec3 aovAlbedo;      // albedo at the first non-specular vertex (times aovTint), 0 until then
    vec3 aovNormal;      // shading normal there, 0 until then
    bool aovDone;        // the albedo and normal are set
    vec4 aovPos;         // xyz: the camera ray's hit point (camera-relative), w: 1 if it hit, else all 0
    vec3 aovEmit;        // the radiance gathered when the first non-specular or glass vertex was reached
    bool aovEmitSet;     // ... which it was (else the path's whole radiance is emission seen directly)
};

/// Start sample `sampleIndex` of pixel `pix`: the camera ray of the book's camera with a box filter
/// over the pixel's square and, if the variant has them, a point on the defocus disk and the time
/// in [0,1) at which the path sees the scene (motion blur: gTime, "Ray Tracing: The Next Week" sec. 2).
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
    // Motion blur: the path's time, kept by every ray of the path (fetchPrim, lib/bindings.glsl).
    // Drawing it changes no other number of the stream (sampleTime).
    if (HAS_MOTION) gTime = sampleTime(s.smp);
    s.d = normalize(target - s.o);
    s.throughput = vec3(1.0f);
    s.radiance = vec3(0.0f);
    s.depth = 0u;
    s.countEmission = true;
    s.prevN = vec3(0.0f, 0.0f, 1.0f);
    s.prevBsdfPdf = 0.0f;
    s.sigma = vec3(0.0f);
    s.aovTint = vec3(1.0f);
    s.aovAlbedo = vec3(0.0f);
    s.aovNormal = vec3(0.0f);
    s.aovDone = false;
    s.aovPos = vec4(0.0f);
    s.aovEmit = vec3(0.0f);
    s.aovEmitSet = false;
    return s;
}

/// HAS_AOV: the path reaches a vertex with BSDF b. Unless the AOVs see through it (a mirror or
/// glass: the next vertex decides), its albedo and normal are the sample's; the emission feature
/// stops growing here or at glass (shared/aov.h).
void aovVertex(inout PathState s, Bsdf b) {
    if (!s.aovEmitSet && aovEmissionStops(b)) {
        s.aovEmit = s.radiance;  // what the camera saw directly, or through mirrors
        s.aovEmitSet = true;
    }
    if (aovSeesThrough(b)) return;
    s.aovAlbedo = s.aovTint * aovAlbedo(b);
    s.aovNormal = aovNormal(b);
    s.aovDone = true;
}

/// HAS_AOV: the path ends, before any non-specular vertex, at radiance L (the background, a light)
/// seen through the surface normal n (0 for none).
void aovEnd(inout PathState s, vec3 L, vec3 n) {
    s.aovAlbedo = s.aovTint * clamp(L, vec3(0.0f), vec3(1.0f));
    s.aovNormal = n;
    s.aovDone = true;
}

/// A new vertex of the path, before it scatters: what its ray found has been counted. Returns true
/// when the path ends there (max_depth rays per path).
bool lastVertex(inout PathState s) {
    s.countEmission = true;
    s.prevBsdfPdf = 0.0f;
    return s.depth >= frame.size.z;
}

/// Scatter at the path's new vertex: a surface point x (BSDF b, offset origin xo, primitive prim of
/// hit h) or a point x in a medium (b its phase function, xo = x, prim VKP_NO_PRIM; h unused):
/// next-event estimation, the next direction, Russian roulette. Returns true when the path ends.
bool scatter(inout PathState s, Bsdf b, vec3 x, vec3 xo, uint prim, SurfaceHit h, inout uint rays, inout uint passes) {
    float uStrategy = bsdfIsDelta(b) ? 0.0f : sampleNext(s.smp);  // picks a light, or the mixture's half
    vec3 uBsdf = bsdfNumbers(b, s.smp);
    bool nee = !bsdfIsDelta(b) && neeOn();
    if (nee || (punctualOn() && !bsdfIsDelta(b)))  // punctual lights: next-event estimation under every sampler
        s.radiance += directLight(b, s.throughput, s.sigma, x, xo, prim, h.p, uStrategy, nee ? sampleNext2(s.smp) : vec2(0.0f), rays, passes);
    vec3 dir;
    if (mixtureOn(b)) {
        if (!sampleMixture(b, xo, uStrategy, uBsdf, s.throughput, dir, passes)) return true;
    } else {
        float pdf;
        vec3 weight;
        if (!sampleBsdf(b, uBsdf, dir, pdf, weight)) return true;
        s.throughput *= weight;
        if (HAS_AOV && !s.aovDone) s.aovTint *= weight;  // a mirror or glass the AOVs see through
        if (nee) {
            // `light` ignores the light this sample finds (already counted), `mis` weights it.
            s.countEmission = neeWeighted(b);
            s.prevN = b.n;  // 0 in a medium (lib/environment.glsl pdfEnv)
            s.prevBsdfPdf = pdf;
        }
    }
    // A refracted ray leaves on the other side: into the glass through its front, out through its back.
    bool refracted = HAS_DIELECTRIC && b.type == MAT_DIELECTRIC && !(dot(dir, h.ns) > 0.0f);
    s.o = refracted ? spawnFrom(h, -h.ns) : xo;
    if (HAS_ABSORPTION && refracted) s.sigma = h.frontFace ? vec3(h.m.m2.x, h.m.m2.y, h.m.m2.z) : vec3(0.0f);
    s.d = dir;

    // Russian roulette (unbiased): continue with probability q, divide by q.
    if (s.depth >= frame.counts.y) {
        float q = min(max(s.throughput.x, max(s.throughput.y, s.throughput.z)), 0.95f);
        if (sampleNext(s.smp) >= q) return true;
        s.throughput /= q;
    }
    return false;
}

/// Trace the path's current ray and scatter at what it finds: a surface, or a point inside a
/// medium where free-flight sampling (lib/media.glsl) stops it first. Returns true when the path
/// has ended (escaped, absorbed, hit a light, stopped by Russian roulette or max_depth).
bool bounce(inout PathState s, inout uint rays, inout uint passes) {
    rays++;
    s.depth++;
    sampleStartVertex(s.smp, s.depth);  // the numbers of the vertex this ray finds
    SurfaceHit h;
    bool found = findSurface(s.o, s.d, h, passes);
    if (HAS_AOV && s.depth == 1u && found) s.aovPos = vec4(h.x, 1.0f);
    if (HAS_MEDIA) {
        // The ray scatters at distance t inside a medium before the surface (weight 1: the
        // transmittance times the density over the free-flight density; the albedo comes with
        // the phase function's sample), or passes every medium (weight 1 too: it does so with the
        // probability their transmittance is).
        float t = found ? distance(s.o, h.x) : VKP_FAR;
        uint material;
        if (sampleMediumEvent(s.o, s.d, t, s.smp, t, material, passes)) {
            if (HAS_ABSORPTION) s.throughput *= exp(-s.sigma * t);
            if (HAS_AOV && !s.aovDone) aovVertex(s, mediumBsdf(material, s.o + t * s.d, s.d));
            if (lastVertex(s)) return true;
            vec3 x = s.o + t * s.d;  // no surface to leave: no offset
            return scatter(s, mediumBsdf(material, x, s.d), x, x, VKP_NO_PRIM, h, rays, passes);
        }
    }
    if (!found) {
        if (HAS_AOV && !s.aovDone) aovEnd(s, envRadiance(s.d), vec3(0.0f));
        // Inside absorbing glass an escaping ray travels forever: nothing is left of it.
        if (!(HAS_ABSORPTION && any(greaterThan(s.sigma, vec3(0.0f)))))
            s.radiance += s.throughput * envEscaped(s.d, s.prevN, s.prevBsdfPdf, s.countEmission);
        return true;
    }
    // Beer-Lambert along the segment inside absorbing glass ("Ray Tracing: The Next Week" sec. 9's
    // constant density, absorbing only): the fraction exp(-sigma t) of the light is left.
    if (HAS_ABSORPTION) s.throughput *= exp(-s.sigma * distance(s.o, h.x));
    // The light this ray found, weighted against the light sample that could have found it from
    // the previous vertex: its density from where this ray started (s.o), not from the vertex
    // itself. Seen from the offset origin the light is a little larger, and in that sliver the
    // density from the vertex is 0, which gave those rays weight 1 (a bias of about twice the
    // offset over the distance: +0.035 % on the empty Cornell room's back wall, docs/accuracy.md
    // "the Cornell box's walls"); from the origin they get the BSDF's weight, as their neighbours do.
    if (HAS_EMITTERS && s.countEmission)
        s.radiance += s.throughput * emitted(h.m, s.d, h.ng) * foundLightWeight(s.prevBsdfPdf, h.p, s.o, s.d);
    if (HAS_EMITTERS && (floatBitsToUint(h.m.m0.w) & MAT_TYPE_MASK) == MAT_DIFFUSE_LIGHT) {  // lights do not scatter
        if (HAS_AOV && !s.aovDone) aovEnd(s, emitted(h.m, s.d, h.ng), h.ns);
        return true;
    }
    if (HAS_AOV && !s.aovDone) aovVertex(s, makeBsdf(h.m, h.ns, h.nShade, h.nCoat, s.d, h.frontFace));
    if (lastVertex(s)) return true;
    return scatter(s, makeBsdf(h.m, h.ns, h.nShade, h.nCoat, s.d, h.frontFace), h.x, spawnFrom(h, h.ns), h.prim, h, rays,
                   passes);
}

/// The pixel of slot j of this invocation (push.batch.z slots: the same invocation of push.batch.z
/// consecutive virtual workgroups g * z + j), or false when that slot has none (beyond the image's
/// edge, the band's tiles or the active list). Scrambled order: lavapipe hands each thread a
/// contiguous run of workgroups, so a permutation that spreads each run over the band balances
/// cheap and expensive regions (push.band.w = 1: row order, `--tile-order linear`).
bool pixelOfSlot(uint j, out uvec2 pix, out uint pixel) {
    uint width = frame.size.x;
    uint group = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * push.batch.z + j;
    if (push.adaptive.x == 0u) {
        // The band's tiles, gl_WorkGroupSize.xy pixels each.
        if (group >= push.band.z) return false;
        uint tilesX = (width + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
        uint tile = (group * push.band.w) % push.band.z;  // host keeps the product below 2^32
        pix = uvec2(tile % tilesX, tile / tilesX) * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
        pix.y += push.band.x;
        pixel = pix.y * width + pix.x;
        return pix.x < width && pix.y < push.band.x + push.band.y;
    }
    // Only the band's pixels still active, packed: no lane idles on a converged pixel.
    if (group >= push.adaptive.y) return false;
    uint slot = ((group * push.adaptive.z) % push.adaptive.y) * (gl_WorkGroupSize.x * gl_WorkGroupSize.y) + gl_LocalInvocationIndex;
    if (slot >= push.adaptive.x) return false;
    pixel = activePixels[slot];
    pix = uvec2(pixel % width, pixel / width);
    return true;
}

/// The first slot from j on that has a pixel (push.batch.z if none).
uint nextSlot(uint j, out uvec2 pix, out uint pixel) {
    while (j < push.batch.z && !pixelOfSlot(j, pix, pixel)) j++;
    return j;
}

/// One pixel's sums, held in registers while its samples are traced.
struct PixelSums {
    vec4 sum, sumLo, sq, sqLo;       // accumulation: a double-float pair each (shared/compensated_sum.h)
    vec4 dSum, dSq;                  // adaptive sampling's decision stream
    vec4 aov0, aov1, aov2, aov3;     // HAS_AOV: the feature sums (shared/aov.h)
};

PixelSums loadSums(uint pixel, uint base) {
    PixelSums p;
    uint at = 2u * (pixel - base);  // the pixel's pair of vec4 in the band's buffers
    p.sum = accumSum[at];
    p.sumLo = accumSum[at + 1u];
    p.sq = accumSq[at];
    p.sqLo = accumSq[at + 1u];
    p.dSum = vec4(0.0f);
    p.dSq = vec4(0.0f);
    if (push.adaptive.x != 0u) {
        p.dSum = decisionSums[at];
        p.dSq = decisionSums[at + 1u];
    }
    p.aov0 = vec4(0.0f), p.aov1 = vec4(0.0f), p.aov2 = vec4(0.0f), p.aov3 = vec4(0.0f);
    if (HAS_AOV) {
        uint aovAt = AOV_VEC4_PER_PIXEL * (pixel - base);
        p.aov0 = aovSums[aovAt];
        p.aov1 = aovSums[aovAt + 1u];
        p.aov2 = aovSums[aovAt + 2u];
        p.aov3 = aovSums[aovAt + 3u];
    }
    return p;
}

void storeSums(uint pixel, uint base, PixelSums p) {
    uint at = 2u * (pixel - base);
    accumSum[at] = p.sum;
    accumSum[at + 1u] = p.sumLo;
    accumSq[at] = p.sq;
    accumSq[at + 1u] = p.sqLo;
    if (HAS_AOV) {
        uint aovAt = AOV_VEC4_PER_PIXEL * (pixel - base);
        aovSums[aovAt] = p.aov0;
        aovSums[aovAt + 1u] = p.aov1;
        aovSums[aovAt + 2u] = p.aov2;
        aovSums[aovAt + 3u] = p.aov3;
    }
    if (push.adaptive.x != 0u) {
        decisionSums[at] = p.dSum;
        decisionSums[at + 1u] = p.dSq;
    }
}

/// Adds the finished sample s (index sampleIndex) to the pixel's sums; returns false if it was
/// dropped (not finite, or too large).
bool addSample(inout PixelSums p, PathState s, uint sampleIndex) {
    // Samples are added in sample order, so any split over dispatches gives the same sums.
    vec3 L = s.radiance;
    // NaN, Inf, or so large that a sum of such samples (or of their squares) could overflow:
    // dropped and counted (Inf is above the bound too).
    bool dropped = any(isnan(L)) || any(greaterThan(abs(L), vec3(MAX_SAMPLE_RADIANCE)));
    if (dropped) {
    } else if (push.adaptive.x != 0u && (sampleIndex & 3u) == 3u) {
        p.dSum += vec4(L, 1.0f);  // decision stream: steers adaptive sampling, not in the image
        p.dSq += vec4(L * L, 0.0f);
    } else {
        addCompensated(p.sum, p.sumLo, vec4(L, 1.0f));
        addCompensated(p.sq, p.sqLo, vec4(L * L, 0.0f));
    }
    if (HAS_AOV) {  // every sample, the dropped ones and adaptive sampling's decision stream too
        // Running means (shared/aov.h): over the samples, and the position over the hits.
        p.aov0.w += 1.0f;
        p.aov0.xyz += (s.aovAlbedo - p.aov0.xyz) / p.aov0.w;
        p.aov1.xyz += (s.aovNormal - p.aov1.xyz) / p.aov0.w;
        // A dropped sample adds no emission: it is not in the image either.
        vec3 emit = dropped ? vec3(0.0f) : (s.aovEmitSet ? s.aovEmit : L);
        p.aov3.xyz += (emit - p.aov3.xyz) / p.aov0.w;
        float indirect = dropped ? 0.0f : luminance709(L - emit);
        p.aov2.w += (indirect - p.aov2.w) / p.aov0.w;
        p.aov3.w += (indirect * indirect - p.aov3.w) / p.aov0.w;
        if (s.aovPos.w > 0.0f) {
            p.aov1.w += 1.0f;
            p.aov2.xyz += (s.aovPos.xyz - p.aov2.xyz) / p.aov1.w;
        }
    }
    return !dropped;
}

void main() {
    // An invocation adds push.batch.y samples (from push.batch.x on) to each pixel of its
    // push.batch.z slots, one pixel after the other (pixelOfSlot). The image is rendered in bands of
    // whole rows (push.band; one band unless the accumulation buffers would exceed the device's
    // storage-buffer range, host/render/gpu_arrays.h planBands): the accumulation buffers bound to
    // a dispatch hold its band's rows only, from pixel `base` on. A finished path is followed at
    // once by the next sample, of the same pixel or of the next slot's ("path regeneration"), so
    // the lanes of a SIMD batch stay busy whether the dispatch holds many samples of few pixels or
    // one sample of many (a large image, where one sample per pixel fills a submission).
    uint base = push.band.x * frame.size.x;
    uvec2 pix;
    uint pixel;
    uint j = nextSlot(0u, pix, pixel);
    if (j >= push.batch.z || push.batch.y == 0u) return;
    PixelSums p = loadSums(pixel, base);
    uint rays = 0u;
    uint nonfinite = 0u;
    uint cut = 0u;
    uint passes = 0u;  // loop passes of this invocation, all loops together (lavapipe's limit is per invocation)
    uint k = 0u;       // samples of the current pixel finished in this dispatch
    PathState s = startPath(pix, pixel, push.batch.x);
    while (true) {
        passes++;
        bool ended = bounce(s, rays, passes);
        if (passes >= VKP_MAX_PASSES) {  // lavapipe's silent loop limit is near: stop, and say so
            cut++;
            break;
        }
        if (ended) {
            if (!addSample(p, s, push.batch.x + k)) nonfinite++;
            k++;
            if (k == push.batch.y) {  // this pixel's samples are done: on to the next slot's pixel
                if (!PIXEL_SLOTS) break;  // one pixel per invocation: its sums are stored below
                storeSums(pixel, base, p);
                k = 0u;
                j = nextSlot(j + 1u, pix, pixel);
                if (j >= push.batch.z) break;
                p = loadSums(pixel, base);
            }
            s = startPath(pix, pixel, push.batch.x + k);
        }
    }
    if (!PIXEL_SLOTS || cut > 0u) storeSums(pixel, base, p);  // or what the cut pixel had; later slots get nothing

    uint old = atomicAdd(counters[COUNTER_RAYS_LO], rays);
    if (old + rays < old) atomicAdd(counters[COUNTER_RAYS_HI], 1u);
    if (nonfinite > 0u) atomicAdd(counters[COUNTER_NONFINITE], nonfinite);
    if (cut > 0u) atomicAdd(counters[COUNTER_LOOP_GUARD], cut);
    atomicMax(counters[COUNTER_MAX_PASSES], passes);
}
