// The BSDF at one surface hit: the one interface behind which every material of the kernel sits,
// and the one dispatch on the material type (pbrt-v4's BSDF, "Physically Based Rendering", 4th
// ed., sec. 9.1). The integrator (shaders/pathtrace.comp), next-event estimation
// (lib/direct_light.glsl) and the book's mixture (lib/mixture.glsl) call only these:
//   makeBsdf     the BSDF of a material at a hit;
//   bsdfIsDelta  a specular lobe (metal, dielectric): no light sampling, no MIS, pdf 0;
//   bsdfIsGlossy the `light` sampler weights this BSDF's own samples by MIS instead of ignoring
//                the lights they find (a near-specular lobe sees small lights only that way);
//   bsdfNumbers  the random numbers sampleBsdf uses, drawn in the dimension layout of
//                shared/sample_stream.h;
//   sampleBsdf / pdfBsdf / evalBsdf   the sampling triple (directions in world space);
//   bsdfCosine   the cosine of a direction with the shading normal, 0 where f is 0 by geometry.
// The materials' own math lives in shared/scatter.h (the books' materials), shared/microfacet.h
// (the glTF BRDF) and shared/layers.h (its clear coat and sheen); each has its own statistical tests, and tests/stats/test_bsdf_stats.cpp tests
// this dispatch. C++ and GLSL (shared/glsl_compat.h): host tests run the kernel's code.
//
// Conventions: dIn is the unit direction of the ray that arrives (towards the surface); n is the
// unit geometric normal on the side it arrives from (dot(dIn, n) <= 0); dir is a unit direction
// leaving the surface. MAT_ISOTROPIC is the phase function at a scattering point inside a medium
// (shared/medium.h): there is no surface, n is 0, every direction is allowed (bsdfCosine 1) and
// "f cos" is the phase function times the albedo. A glTF material shades in the frame of its shading normal (lib/surface.glsl)
// and gets f = 0 for directions below the geometric surface, so no light leaks through.
//
// The includer may define, before including this file:
//   VKP_HAS_MATERIAL(t)  true if kernel material type t can occur (default: every type); the
//                        kernel's is a specialization constant (lib/spec_constants.glsl);
//   VKP_SHADING_NORMALS  false if shading normals always equal geometric ones (default true);
//   VKP_HAS_LAYERS       true if a MAT_PBR material may have a clear coat or sheen (shared/layers.h;
//                        default true).
#ifndef VKP_BSDF_H
#define VKP_BSDF_H
#include "gpu_types.h"
#include "layers.h"
#include "medium.h"
#include "microfacet.h"
#include "onb.h"
#include "sample_stream.h"
#include "sampling.h"
#include "scatter.h"

#ifndef VKP_HAS_MATERIAL
#define VKP_HAS_MATERIAL(t) true
#endif
#ifndef VKP_SHADING_NORMALS
#define VKP_SHADING_NORMALS true
#endif
#ifndef VKP_HAS_LAYERS
#define VKP_HAS_LAYERS true
#endif

/// A glossy BSDF (bsdfIsGlossy) can occur: the `light` sampler then needs its MIS branches.
#define VKP_HAS_GLOSSY_BSDF VKP_HAS_MATERIAL(MAT_PBR)

VKP_BEGIN

struct Bsdf {
    uint type;          ///< MAT_LAMBERTIAN, MAT_METAL, MAT_DIELECTRIC, MAT_PBR or MAT_ISOTROPIC (shared/kinds.h)
    vec3 n;             ///< unit geometric normal on the side the ray arrives from
    vec3 dIn;           ///< unit direction of the arriving ray
    bool frontFace;     ///< the ray arrives on the geometric front (outside)
    vec3 albedo;        ///< lambertian and metal reflectance, a medium's single-scattering albedo (linear RGB)
    float param;        ///< metal: fuzz radius; dielectric: index of refraction
    bool fresnelExact;  ///< dielectric: exact Fresnel instead of Schlick's
    Onb frame;          ///< MAT_PBR: the shading frame, z = the shading normal
    vec3 v;             ///< MAT_PBR: the direction to the viewer in that frame
    GltfBrdf gltf;      ///< MAT_PBR
    bool layered;       ///< MAT_PBR with a clear coat or sheen (MATF_LAYERED): layers, coatFrame
    GltfLayers layers;  ///< the coat and sheen (shared/layers.h)
    Onb coatFrame;      ///< the coat's frame, z = the coat normal
};

/// The layered material of b (b.layered), for shared/layers.h.
VKP_FN LayeredBrdf bsdfLayered(Bsdf b) {
    LayeredBrdf m;
    m.base = b.gltf;
    m.layers = b.layers;
    m.frame = b.frame;
    m.coatFrame = b.coatFrame;
    return m;
}

/// The BSDF of kernel material m (shared/gpu_types.h, textures already applied) at a hit with
/// geometric normal n (facing the arriving ray dIn), shading normal nShade (n where there is none),
/// the coat's normal nCoat (a layered MAT_PBR material; lib/surface.glsl) and frontFace.
VKP_FN Bsdf makeBsdf(GpuMaterial m, vec3 n, vec3 nShade, vec3 nCoat, vec3 dIn, bool frontFace) {
    Bsdf b;
    uint flags = floatBitsToUint(m.m0.w);
    b.type = flags & MAT_TYPE_MASK;
    b.n = n;
    b.dIn = dIn;
    b.frontFace = frontFace;
    b.albedo = vec3(m.m0.x, m.m0.y, m.m0.z);
    b.param = m.m1.w;
    b.fresnelExact = (flags & MATF_FRESNEL_EXACT) != 0u;
    if (VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR) {
        b.frame = onbFromNormal(nShade);
        b.v = toLocal(b.frame, -dIn);
        b.gltf = makeGltfBrdf(b.albedo, m.m3.x, m.m3.y, m.m2.w, vec3(m.m2.x, m.m2.y, m.m2.z));
    } else {  // unused by the other types
        b.frame.s = vec3(0.0f);
        b.frame.t = vec3(0.0f);
        b.frame.n = nShade;
        b.v = vec3(0.0f);
        b.gltf.baseColor = vec3(0.0f);
        b.gltf.metallic = 0.0f;
        b.gltf.alpha = 1.0f;
        b.gltf.roughness = 1.0f;
        b.gltf.f0 = vec3(0.0f);
        b.gltf.f90 = 0.0f;
    }
    b.layered = VKP_HAS_LAYERS && VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR && (flags & MATF_LAYERED) != 0u;
    if (b.layered) {
        b.layers = makeGltfLayers(m.m4.x, m.m4.y, vec3(m.m5.x, m.m5.y, m.m5.z), m.m4.z);
        b.coatFrame = onbFromNormal(nCoat);
    } else {
        b.layers = makeGltfLayers(0.0f, 1.0f, vec3(0.0f), 1.0f);
        b.coatFrame = b.frame;
    }
    return b;
}

/// makeBsdf with the coat normal equal to the shading normal.
VKP_FN Bsdf makeBsdf(GpuMaterial m, vec3 n, vec3 nShade, vec3 dIn, bool frontFace) {
    return makeBsdf(m, n, nShade, nShade, dIn, frontFace);
}

/// A specular (delta) BSDF: metal's fuzzy mirror and the dielectric's reflect-or-refract have no
/// density (the books' materials), so they are never light-sampled and their samples have pdf 0.
VKP_FN bool bsdfIsDelta(Bsdf b) {
    return (VKP_HAS_MATERIAL(MAT_METAL) && b.type == MAT_METAL) ||
           (VKP_HAS_MATERIAL(MAT_DIELECTRIC) && b.type == MAT_DIELECTRIC);
}

/// Under the `light` sampler, the lights found by this BSDF's own samples are weighted by MIS
/// (as under `mis`) instead of ignored: the glTF BRDF's lobe reaches alpha = 1e-3, and plain
/// next-event estimation would see small lights through it only by the shadow ray.
VKP_FN bool bsdfIsGlossy(Bsdf b) { return VKP_HAS_GLOSSY_BSDF && b.type == MAT_PBR; }

/// The numbers sampleBsdf(b, u, ...) reads, drawn from the sample stream in its layout
/// (shared/sample_stream.h): lambertian (0, pair 0), pbr (single, pair 0), metal three singles,
/// dielectric one single; isotropic (a medium) as lambertian. A non-delta vertex draws its strategy
/// number (single 0) before these.
VKP_FN vec3 bsdfNumbers(Bsdf b, INOUT(SampleStream) smp) {
    if (VKP_HAS_MATERIAL(MAT_METAL) && b.type == MAT_METAL) {
        float u0 = sampleNext(smp);
        float u1 = sampleNext(smp);
        float u2 = sampleNext(smp);
        return vec3(u0, u1, u2);
    }
    if (VKP_HAS_MATERIAL(MAT_DIELECTRIC) && b.type == MAT_DIELECTRIC) return vec3(sampleNext(smp), 0.0f, 0.0f);
    float lobe = (VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR) ? sampleNext(smp) : 0.0f;
    vec2 d = sampleNext2(smp);
    return vec3(lobe, d.x, d.y);
}

/// True if dir leaves on the other side of the geometric surface than the viewer: f = 0 there
/// for a BSDF in a shading frame (no light leaks through a surface whose shading normal leans
/// over its horizon).
VKP_FN bool belowGeometric(Bsdf b, vec3 dir) { return VKP_SHADING_NORMALS && !(dot(dir, b.n) > 0.0f); }

/// The cosine of dir with the normal the BSDF shades with, or 0 (or less) where f(dir) is 0 by
/// geometry. Next-event estimation traces no shadow ray unless it is > 0.
VKP_FN float bsdfCosine(Bsdf b, vec3 dir) {
    if (VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR) {
        float c = toLocal(b.frame, dir).z;
        if (b.layered) c = max(c, toLocal(b.coatFrame, dir).z);  // the coat's lobe lives in its own frame
        return belowGeometric(b, dir) ? 0.0f : c;
    }
    if (bsdfIsDelta(b)) return 0.0f;
    if (VKP_HAS_MATERIAL(MAT_ISOTROPIC) && b.type == MAT_ISOTROPIC) return 1.0f;  // no surface: every direction
    return dot(dir, b.n);
}

/// scale x f(dir) x cos(dir) (f in sr^-1; per channel). scale is the path throughput (next-event
/// estimation: the contribution before the light's factors) or vec3(1) (a ratio f cos / p). 0 for
/// delta BSDFs (no light sample can meet their lobe) and for directions below the surface.
VKP_FN vec3 evalBsdf(Bsdf b, vec3 scale, vec3 dir) {
    if (VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR) {
        if (b.layered) return belowGeometric(b, dir) ? vec3(0.0f) : scale * evalLayeredCos(bsdfLayered(b), -b.dIn, dir);
        vec3 l = toLocal(b.frame, dir);
        if (!(l.z > 0.0f) || belowGeometric(b, dir)) return vec3(0.0f);
        return scale * evalGltfBrdf(b.gltf, b.v, l) * l.z;
    }
    if (bsdfIsDelta(b)) return vec3(0.0f);
    if (VKP_HAS_MATERIAL(MAT_ISOTROPIC) && b.type == MAT_ISOTROPIC) return scale * b.albedo * pdfIsotropicPhase();
    float c = dot(dir, b.n);
    return (c > 0.0f) ? scale * b.albedo * VKP_INV_PI * c : vec3(0.0f);
}

/// Solid-angle density (sr^-1) with which sampleBsdf produces dir; 0 for delta BSDFs.
VKP_FN float pdfBsdf(Bsdf b, vec3 dir) {
    if (VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR) {
        if (b.layered) return pdfLayered(bsdfLayered(b), -b.dIn, dir);
        return pdfGltfBrdf(b.gltf, b.v, toLocal(b.frame, dir));
    }
    if (bsdfIsDelta(b)) return 0.0f;
    if (VKP_HAS_MATERIAL(MAT_ISOTROPIC) && b.type == MAT_ISOTROPIC) return pdfIsotropicPhase();
    return pdfCosineHemisphere(dot(dir, b.n));
}

/// One direction from the BSDF with u = bsdfNumbers(b, ...): dir, its density pdf (0 for a delta
/// lobe) and the throughput factor weight = f cos / pdf (a delta lobe: its albedo). Returns false
/// when the sample carries nothing (metal's fuzz below the surface, a glTF sample below either
/// surface): the path ends there. dir is set either way.
VKP_FN bool sampleBsdf(Bsdf b, vec3 u, OUT(vec3) dir, OUT(float) pdf, OUT(vec3) weight) {
    pdf = 0.0f;
    weight = vec3(0.0f);
    if (VKP_HAS_MATERIAL(MAT_METAL) && b.type == MAT_METAL) {
        bool absorbed;
        dir = scatterMetal(b.dIn, b.n, b.param, u, absorbed);
        weight = b.albedo;
        return !absorbed;
    }
    if (VKP_HAS_MATERIAL(MAT_DIELECTRIC) && b.type == MAT_DIELECTRIC) {
        dir = scatterDielectric(b.dIn, b.n, b.frontFace, b.param, b.fresnelExact, u.x);
        weight = vec3(1.0f);
        return true;
    }
    if (VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR && b.layered) {
        dir = sampleLayered(bsdfLayered(b), -b.dIn, u, pdf);
        if (!(pdf > 0.0f) || belowGeometric(b, dir)) return false;
        vec3 fc = evalLayeredCos(bsdfLayered(b), -b.dIn, dir);
        if (!(max(fc.x, max(fc.y, fc.z)) > 0.0f)) return false;
        weight = fc / pdf;
        return true;
    }
    if (VKP_HAS_MATERIAL(MAT_PBR) && b.type == MAT_PBR) {
        vec3 l = sampleGltfBrdf(b.gltf, b.v, u, pdf);
        dir = toWorld(b.frame, l);
        if (!(l.z > 0.0f) || !(pdf > 0.0f) || belowGeometric(b, dir)) return false;
        weight = evalGltfBrdf(b.gltf, b.v, l) * (l.z / pdf);
        return true;
    }
    if (VKP_HAS_MATERIAL(MAT_ISOTROPIC) && b.type == MAT_ISOTROPIC) {
        dir = sampleIsotropicPhase(vec2(u.y, u.z));
        pdf = pdfIsotropicPhase();
        weight = b.albedo;  // albedo p / p
        return true;
    }
    dir = sampleLambertian(b.n, vec2(u.y, u.z));
    pdf = pdfCosineHemisphere(dot(dir, b.n));
    weight = b.albedo;  // (albedo / pi) cos / (cos / pi)
    return true;
}

VKP_END
#endif
