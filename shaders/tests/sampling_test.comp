#version 460
// Device test kernel for the shared sampling code (rng.h, onb.h, sampling.h, light_sampling.h,
// scatter.h, microfacet.h): evaluates the routine chosen by the push constant for `count` items, so a host test
// can compare the GPU results with the same headers compiled as C++.
//
// I/O layout (std430, every element a vec4):
//   binding 0 (read):  inData[4 * i + k], k = 0..3  -> in0..in3 of item i
//   binding 1 (write): outData[2 * i + k], k = 0..1 -> out0, out1 of item i
//   push constant:     uint routine, uint count
// Unused components are written as 0. Integers travel as float bits (uintBitsToFloat).
//
// Routine ids (u = uniform numbers in [0,1), dir/p world space unless "local"):
//  0 RNG          in0.xyz = bits of (pixel, sampleIndex, seed)
//                 out0 = draws 1-4 of rngInit(pixel, sample, seed), out1 = draws 5-8
//  1 ONB          in0.xyz = unit n, in1.xyz = v
//                 out0.xyz = toWorld(onbFromNormal(n), v), out1.xyz = toLocal(onbFromNormal(n), v)
//  2 COSINE_HEMI  in0.xy = u   out0.xyz = sampleCosineHemisphere(u), out0.w = its pdf,
//                              out1.xy = invertCosineHemisphere(out0.xyz)
//  3 UNIFORM_SPHERE  same layout (pdf = pdfUniformSphere())
//  4 UNIFORM_HEMI    same layout
//  5 UNIFORM_CONE in0.xy = u, in0.z = oneMinusCosMax; same layout (pdfUniformCone of the sample)
//  6 UNIFORM_DISK in0.xy = u   out0.xy = point, out0.w = pdf, out1.xy = invert
//  7 UNIFORM_BALL in0.xyz = u  out0.xyz = point, out0.w = pdf, out1.xyz = invert
//  8 QUAD_LIGHT   in0.xyz = Q, in1.xyz = u, in2.xyz = v, in3.xyz = p, (in0.w, in1.w) = xi
//                 out0 = (dir, dist), out1.x = pdf, out1.y = pdfQuadLight(dir), out1.zw = invert
//  9 TRI_LIGHT    in0.xyz = v0, in1.xyz = e1, in2.xyz = e2, rest as 8
// 10 SPHERE_LIGHT in0.xyz = c, in0.w = R, in3.xyz = p, in1.xy = xi; outputs as 8
// 11 LAMBERTIAN   in0.xyz = unit n, in1.xy = u
//                 out0.xyz = sampleLambertian(n, u), out0.w = pdfLambertian, out1.xy = invert
// 12 METAL        in0.xyz = dIn, in1.xyz = n, in1.w = fuzz, in2.xyz = u3
//                 out0.xyz = scatterMetal(...), out0.w = absorbed ? 1 : 0
// 13 DIELECTRIC   in0.xyz = dIn, in1.xyz = n, in1.w = ior, in2.x = frontFace (0/1),
//                 in2.y = exact (0/1), in2.z = u       out0.xyz = scatterDielectric(...)
// 14 FRESNEL      in0.x = cosine c, in0.y = a value e passed unchanged to each function:
//                 out0.x = fresnelSchlick(c, e),
//                 out0.y = fresnelDielectricExact(c, e)          (e read as eta_t / eta_i),
//                 out0.z = dielectricReflectProbability(c, e, false) (e read as eta_i / eta_t),
//                 out0.w = dielectricReflectProbability(c, e, true)
// 15 RECT_LIGHT   inputs as 8, in2.w = minSize (rect_sampling.h: solid angle, area fallback)
//                 out0 = (dir, dist), out1.x = pdf, out1.y = pdfRectLight(dir),
//                 out1.z = 1 if the spherical rectangle is used, else 0
// 16 GGX_VNDF     in0.xyz = v (local), in0.w = alpha, in1.xy = u     (microfacet.h)
//                 out0.xyz = sampleGgxVndf(v, alpha, u), out0.w = pdfGgxVndf(v, out0.xyz, alpha),
//                 out1.xyz = sampleGgxVisibleNormal(v, alpha, u), out1.w = pdfGgxVndfHalf(v, out1.xyz, alpha)
// 17 GLTF_SAMPLE  material: in0.xyz = baseColor, in0.w = metallic, in1.xyz = specularColor,
//                 in1.w = specularFactor, in2.x = roughness; in3.xyz = v (local), in2.yzw = u3
//                 out0.xyz = sampleGltfBrdf(...), out0.w = its pdf, out1.x = pdfGltfBrdf(v, out0.xyz),
//                 out1.y = gltfSpecularProbability(v), out1.z = ggxAlpha(roughness)
// 18 GLTF_EVAL    material as 17; in3.xyz = v, in2.yzw = l (local)
//                 out0.xyz = evalGltfBrdf(v, l), out0.w = pdfGltfBrdf(v, l),
//                 out1.x = ggxVisibility(v, l, alpha), out1.y = ggxG1(v, alpha),
//                 out1.z = ggxD(normalize(v + l), alpha) (0 when v + l = 0)
// 19 LIGHT_PICK   in0.x = u, in0.y = bits of the light count n, in0.z = bits of the item index t
//                 where the table starts: item t + j holds light j's GpuLight in its in0
//                 (light_pick.h alias pick, as lib/lights.glsl pickLightPower does it)
//                 out0.x = bits of the picked light, out0.y = the probability its entry reports
// 20 SPH_TRI_LIGHT inputs as 9, in2.w = minSize (triangle_sampling.h: solid angle, area fallback)
//                 out0 = (dir, dist), out1.x = pdf, out1.y = pdfTriangleLightSolidAngle(dir),
//                 out1.z = 1 if the spherical triangle is used, else 0
// 21 SOBOL        in0.xyzw = bits of (pixel, sampleIndex, seed, group)          (sobol.h, sample_stream.h)
//                 out0[k] = sobolSample(sobolPixelSeed(pixel, seed), index, group, k), k = 0..3,
//                 out1.xy = sobolSample2(same, group + 1), out1.z = first sampleNext of the stream
//                 sampleStreamInit(pixel, index, seed, group odd) at vertex group % 10,
//                 out1.w = sobolToFloat(sobolPixelSeed(pixel, seed)) (its top 24 bits)
#extension GL_GOOGLE_include_directive : require

#include "shared/light_sampling.h"
#include "shared/rect_sampling.h"
#include "shared/rng.h"
#include "shared/sample_stream.h"
#include "shared/scatter.h"
#include "shared/microfacet.h"
#include "shared/light_pick.h"
#include "shared/triangle_sampling.h"
#include "tests/sampling_routines.h"  // the routine ids (R_*), shared with tests/gpu/sampling_kernel.h

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer InBuf { vec4 inData[]; };
layout(std430, set = 0, binding = 1) writeonly buffer OutBuf { vec4 outData[]; };
// The GGX albedo table of microfacet.h (ggxAlbedoFetch), as the host computes it.
layout(std430, set = 0, binding = 2) readonly buffer AlbedoBuf { vec4 albedoTable[]; };
vec4 ggxAlbedoFetch(uint t) { return albedoTable[t]; }
layout(push_constant) uniform Push {
    uint routine;
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec4 in0 = inData[4u * i + 0u];
    vec4 in1 = inData[4u * i + 1u];
    vec4 in2 = inData[4u * i + 2u];
    vec4 in3 = inData[4u * i + 3u];
    vec4 out0 = vec4(0.0);
    vec4 out1 = vec4(0.0);
    uint r = pc.routine;

    if (r == R_RNG) {
        uint s = rngInit(floatBitsToUint(in0.x), floatBitsToUint(in0.y), floatBitsToUint(in0.z));
        for (int k = 0; k < 4; ++k) out0[k] = rngNext(s);
        for (int k = 0; k < 4; ++k) out1[k] = rngNext(s);
    } else if (r == R_ONB) {
        Onb f = onbFromNormal(in0.xyz);
        out0.xyz = toWorld(f, in1.xyz);
        out1.xyz = toLocal(f, in1.xyz);
    } else if (r == R_COSINE_HEMI) {
        vec3 w = sampleCosineHemisphere(in0.xy);
        out0 = vec4(w, pdfCosineHemisphere(w.z));
        out1.xy = invertCosineHemisphere(w);
    } else if (r == R_UNIFORM_SPHERE) {
        vec3 w = sampleUniformSphere(in0.xy);
        out0 = vec4(w, pdfUniformSphere());
        out1.xy = invertUniformSphere(w);
    } else if (r == R_UNIFORM_HEMI) {
        vec3 w = sampleUniformHemisphere(in0.xy);
        out0 = vec4(w, pdfUniformHemisphere(w.z));
        out1.xy = invertUniformHemisphere(w);
    } else if (r == R_UNIFORM_CONE) {
        vec3 w = sampleUniformCone(in0.xy, in0.z);
        out0 = vec4(w, pdfUniformCone(w, in0.z));
        out1.xy = invertUniformCone(w, in0.z);
    } else if (r == R_UNIFORM_DISK) {
        vec2 q = sampleUniformDisk(in0.xy);
        out0 = vec4(q, 0.0, pdfUniformDisk(q));
        out1.xy = invertUniformDisk(q);
    } else if (r == R_UNIFORM_BALL) {
        vec3 q = sampleUniformBall(in0.xyz);
        out0 = vec4(q, pdfUniformBall(q));
        out1.xyz = invertUniformBall(q);
    } else if (r == R_QUAD_LIGHT || r == R_TRI_LIGHT) {
        vec2 xi = vec2(in0.w, in1.w);
        bool tri = (r == R_TRI_LIGHT);
        LightSample s = tri ? sampleTriangleLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, xi)
                            : sampleQuadLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, xi);
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = tri ? pdfTriangleLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, s.dir)
                     : pdfQuadLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, s.dir);
        out1.zw = tri ? invertTriangleLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, s.dir)
                      : invertQuadLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, s.dir);
    } else if (r == R_RECT_LIGHT) {
        LightSample s = sampleRectLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, vec2(in0.w, in1.w), in2.w);
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = pdfRectLight(in0.xyz, in1.xyz, in2.xyz, in3.xyz, s.dir, in2.w);
        out1.z = rectLightUsesSolidAngle(in0.xyz, in1.xyz, in2.xyz, in3.xyz, in2.w) ? 1.0 : 0.0;
    } else if (r == R_SPH_TRI_LIGHT) {
        LightSample s = sampleTriangleLightSolidAngle(in0.xyz, in1.xyz, in2.xyz, in3.xyz, vec2(in0.w, in1.w), in2.w);
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = pdfTriangleLightSolidAngle(in0.xyz, in1.xyz, in2.xyz, in3.xyz, s.dir, in2.w);
        out1.z = triangleLightUsesSolidAngle(in0.xyz, in1.xyz, in2.xyz, in3.xyz, in2.w) ? 1.0 : 0.0;
    } else if (r == R_SPHERE_LIGHT) {
        LightSample s = sampleSphereLight(in0.xyz, in0.w, in3.xyz, in1.xy);
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = pdfSphereLight(in0.xyz, in0.w, in3.xyz, s.dir);
        out1.zw = invertSphereLight(in0.xyz, in0.w, in3.xyz, s.dir);
    } else if (r == R_LAMBERTIAN) {
        vec3 w = sampleLambertian(in0.xyz, in1.xy);
        out0 = vec4(w, pdfLambertian(in0.xyz, w));
        out1.xy = invertLambertian(in0.xyz, w);
    } else if (r == R_METAL) {
        bool absorbed;
        vec3 w = scatterMetal(in0.xyz, in1.xyz, in1.w, in2.xyz, absorbed);
        out0 = vec4(w, absorbed ? 1.0 : 0.0);
    } else if (r == R_DIELECTRIC) {
        out0.xyz = scatterDielectric(in0.xyz, in1.xyz, in2.x != 0.0, in1.w, in2.y != 0.0, in2.z);
    } else if (r == R_FRESNEL) {
        out0 = vec4(fresnelSchlick(in0.x, in0.y), fresnelDielectricExact(in0.x, in0.y),
                    dielectricReflectProbability(in0.x, in0.y, false),
                    dielectricReflectProbability(in0.x, in0.y, true));
    }
    if (r == R_GGX_VNDF) {
        vec3 l = sampleGgxVndf(in0.xyz, in0.w, in1.xy);
        vec3 h = sampleGgxVisibleNormal(in0.xyz, in0.w, in1.xy);
        out0 = vec4(l, pdfGgxVndf(in0.xyz, l, in0.w));
        out1 = vec4(h, pdfGgxVndfHalf(in0.xyz, h, in0.w));
    } else if (r == R_GLTF_SAMPLE || r == R_GLTF_EVAL) {
        GltfBrdf b = makeGltfBrdf(in0.xyz, in0.w, in2.x, in1.w, in1.xyz);
        vec3 v = in3.xyz;
        if (r == R_GLTF_SAMPLE) {
            float pdf;
            vec3 l = sampleGltfBrdf(b, v, in2.yzw, pdf);
            out0 = vec4(l, pdf);
            out1 = vec4(pdfGltfBrdf(b, v, l), gltfSpecularProbability(b, v), b.alpha, 0.0);
        } else {
            vec3 l = in2.yzw;
            vec3 hv = v + l;
            float len2 = dot(hv, hv);
            out0 = vec4(evalGltfBrdf(b, v, l), pdfGltfBrdf(b, v, l));
            out1 = vec4(ggxVisibility(v, l, b.alpha), ggxG1(v, b.alpha),
                        len2 > 0.0 ? ggxD(hv / sqrt(len2), b.alpha) : 0.0, 0.0);
        }
    }
    if (r == R_LIGHT_PICK) {
        uint n = floatBitsToUint(in0.y);
        uint start = floatBitsToUint(in0.z);
        if (n > 0u) {
            float frac;
            uint col = aliasColumn(in0.x, n, frac);
            GpuLight e;
            e.l0 = inData[4u * (start + col)];
            uint li = aliasResolve(col, frac, e);
            out0 = vec4(uintBitsToFloat(li), inData[4u * (start + li)].y, 0.0, 0.0);
        }
    }
    if (r == R_SOBOL) {
        uint pixel = floatBitsToUint(in0.x);
        uint index = floatBitsToUint(in0.y);
        uint seed = floatBitsToUint(in0.z);
        uint group = floatBitsToUint(in0.w);
        uint ps = sobolPixelSeed(pixel, seed);
        for (uint k = 0u; k < 4u; ++k) out0[k] = sobolSample(ps, index, group, k);
        out1.xy = sobolSample2(ps, index, group + 1u);
        SampleStream st = sampleStreamInit(pixel, index, seed, (group & 1u) != 0u);
        sampleStartVertex(st, group % 10u);
        out1.z = sampleNext(st);
        out1.w = sobolToFloat(ps);
    }
    outData[2u * i + 0u] = out0;
    outData[2u * i + 1u] = out1;
}
