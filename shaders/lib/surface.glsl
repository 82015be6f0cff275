// Surface attributes of glTF mesh triangles at a hit: UVs (TEXCOORD_0, _1), interpolated shading normal,
// normal map, vertex colours (COLOR_0), and the textures of MAT_PBR materials. Compiled in only for scenes that need it
// (HAS_VERTEX_ATTRIBUTES, HAS_TEXTURES, ...: lib/spec_constants.glsl). Included by pathtrace.comp.
//
// Buffers (host/render/texture_pack.h; declared in lib/bindings.glsl):
//   uAttributes (RGBA32UI): 8 texels per BVH primitive: (uv0, uv1) | (uv2, flags, uv1At) | n0 | n1 |
//                           n2 | t0 | t1 | t2 (TEXCOORD_0 of the corners; flags: TriangleVertices::
//                           kHas*; zeros for other primitives); after all of them, for triangles
//                           with TEXCOORD_1 (ATTR_HAS_UV1), its corners (c0, c1) | (c2, 0, 0) at
//                           texel uv1At, and for triangles with COLOR_0 (ATTR_HAS_COLOR), its
//                           corners' RGBA as half floats at the texel in n0's w (vertexColor);
//   uTexInfo    (RGBA32UI): [0] = (first texture header, ...); material m's record at
//                           1 + MAT_TEX_TEXELS m (layout: shared/texture_record.h); texture headers
//                           as in shared/texture_sample.h;
//   uTexels     (R32UI):    RGBA8 texels of every image.
//
// Shading normals: the interpolated NORMAL (and the normal map) only orient the BRDF's frame. They
// are turned to the side of the geometric normal the ray arrived on, and when the viewer would be
// below the shading hemisphere the geometric normal is used instead. Directions on the other side
// of the geometric surface than the viewer get f = 0 (shared/bsdf.h), so no light leaks
// through a surface whose shading normal leans over its horizon.
#ifndef VKP_SURFACE_GLSL
#define VKP_SURFACE_GLSL
#include "lib/bindings.glsl"
#include "shared/intersect.h"

#define VKP_TEXEL_FETCH(i) texelFetch(uTexels, int(i)).x
#include "shared/texture_sample.h"
#include "shared/texture_record.h"

/// TEXCOORD_1 at surface parameters ab of the primitive whose attribute record's second texel is
/// a1 (fallback where it has none, or in variants without HAS_TEXCOORD1).
vec2 attributeUv1(vec4 a1, vec2 ab, vec2 fallback) {
    if (!HAS_TEXCOORD1 || (floatBitsToUint(a1.z) & ATTR_HAS_UV1) == 0u) return fallback;
    int at = int(floatBitsToUint(a1.w));
    vec4 b0 = fetchF(uAttributes, at);
    vec4 b1 = fetchF(uAttributes, at + 1);
    return (1.0f - ab.x - ab.y) * b0.xy + ab.x * b0.zw + ab.y * b1.xy;
}

/// COLOR_0 (linear RGBA) at surface parameters ab of the primitive whose attribute record starts
/// at texel base; white where it has none (ATTR_HAS_COLOR in flags) or in variants without
/// HAS_VERTEX_COLORS. Its record: the corners' RGBA as half floats (host packVertexAttributes).
vec4 vertexColor(int base, uint flags, vec2 ab) {
    if (!HAS_VERTEX_COLORS || (flags & ATTR_HAS_COLOR) == 0u) return vec4(1.0f);
    int at = int(texelFetch(uAttributes, base + 2).w);
    uvec4 r0 = texelFetch(uAttributes, at);
    uvec4 r1 = texelFetch(uAttributes, at + 1);
    vec4 c0 = vec4(unpackHalf2x16(r0.x), unpackHalf2x16(r0.y));
    vec4 c1 = vec4(unpackHalf2x16(r0.z), unpackHalf2x16(r0.w));
    vec4 c2 = vec4(unpackHalf2x16(r1.x), unpackHalf2x16(r1.y));
    return (1.0f - ab.x - ab.y) * c0 + ab.x * c1 + ab.y * c2;
}

/// Sample texture slot `slot` of the material record at `rec` at uv0 (TEXCOORD_0) or uv1
/// (TEXCOORD_1), as the slot's texCoord says; false if the slot is empty.
bool sampleSlot(uint rec, uint slot, vec2 uv0, vec2 uv1, out vec4 c) {
    c = vec4(1.0f);
    uvec4 t1 = texelFetch(uTexInfo, int(rec + 2u * slot + 1u));
    if (t1.z == TEX_NO_TEXTURE) return false;
    vec2 uv = (HAS_TEXCOORD1 && t1.w == 1u) ? uv1 : uv0;
    vec4 rs = uintBitsToFloat(texelFetch(uTexInfo, int(rec + 2u * slot)));
    uint headerBase = texelFetch(uTexInfo, 0).x;
    c = texSample(texelFetch(uTexInfo, int(headerBase + t1.z)), texTransform(uv, rs, uintBitsToFloat(t1.xy)));
    return true;
}

/// KHR_materials_transmission with a transmissionTexture (github.com/KhronosGroup/glTF,
/// extensions/2.0/Khronos/KHR_materials_transmission): transmission = transmissionFactor (m3.z,
/// non-zero only for such materials, shared/gpu_types.h) x the texture's R channel (linear) at uv.
/// True where it is above 0: there the material renders as a constant transmissionFactor > 0 does
/// (host transmittedMaterial: any amount is clear glass), elsewhere as the opaque glTF BRDF.
bool transmitsAt(uint rec, vec2 uv, vec2 uv1, GpuMaterial m) {
    vec4 c;
    return m.m3.z > 0.0f && sampleSlot(rec, TEX_SLOT_TRANSMISSION, uv, uv1, c) && m.m3.z * c.x > 0.0f;
}

/// Turns the MAT_PBR record m into what host transmittedMaterial gives: exact-Fresnel clear glass
/// of index m3.w, or with ior 0 a fuzzy metal (albedo = base colour factor, fuzz = roughness^2).
void becomeTransmitted(inout GpuMaterial m) {
    float ior = m.m3.w;
    if (ior >= 1.0f) {
        m.m0 = vec4(1.0f, 1.0f, 1.0f, uintBitsToFloat(MAT_DIELECTRIC | MATF_FRESNEL_EXACT));
        m.m1.w = ior;
        m.m2 = vec4(0.0f);  // a dielectric's absorption (HAS_ABSORPTION): none, not the specular colour
    } else {
        m.m0.w = uintBitsToFloat(MAT_METAL);
        m.m1.w = m.m3.y * m.m3.y;
    }
}

/// The tangent frame (tt, bt) of a mesh triangle at surface parameters ab, interpolated from its
/// attribute record at base and made orthogonal to n (Gram-Schmidt); false where it degenerates.
/// An instance's tangents are taken into the world first (shared/instance.h).
bool tangentFrame(int base, vec2 ab, bool instanced, GpuInstance ins, vec3 n, out vec3 tt, out vec3 bt) {
    vec4 t0 = fetchF(uAttributes, base + 5);
    vec4 t1 = fetchF(uAttributes, base + 6);
    vec4 t2 = fetchF(uAttributes, base + 7);
    if (instanced) {
        t0 = instanceTangentToWorld(ins, t0);
        t1 = instanceTangentToWorld(ins, t1);
        t2 = instanceTangentToWorld(ins, t2);
    }
    vec4 t = (1.0f - ab.x - ab.y) * t0 + ab.x * t1 + ab.y * t2;
    tt = t.xyz - n * dot(n, t.xyz);
    float tl = length(tt);
    bt = vec3(0.0f);
    if (!(tl > 0.0f)) return false;
    tt /= tl;
    bt = (t.w < 0.0f ? -1.0f : 1.0f) * cross(n, tt);
    return true;
}

/// n perturbed by the tangent-space normal map texel c (linear, [0,1] per channel) with
/// normalTexture.scale `scale` in the frame (tt, bt, n) (glTF 2.0 sec. 3.9.3); n where it degenerates.
vec3 normalMapped(vec3 n, vec3 tt, vec3 bt, vec4 c, float scale) {
    vec3 tn = vec3((2.0f * c.x - 1.0f) * scale, (2.0f * c.y - 1.0f) * scale, 2.0f * c.z - 1.0f);
    vec3 nm = tt * tn.x + bt * tn.y + n * tn.z;
    float nl = length(nm);
    return nl > 0.0f ? nm / nl : n;
}

/// A shading normal turned to the side the ray arrived on (the side of ns), or ns itself where
/// there is none or the viewer would be below its horizon (file comment).
vec3 facingNormal(vec3 n, bool hasN, vec3 ns, vec3 d) {
    if (!hasN) return ns;
    if (dot(n, ns) < 0.0f) n = -n;     // the side the ray arrived on
    return dot(n, d) < 0.0f ? n : ns;  // viewer below the shading horizon: geometric
}

/// At a hit on primitive `prim` (p, surface parameters ab, geometric normal ns facing the incoming
/// direction d, material index mi): applies the textures of a MAT_PBR material m (base colour x
/// texture RGB, metallic x B, roughness x G, and the clear coat's and sheen's) and returns the
/// shading normal (ns where there is none, see above); nCoat gets the clear coat's normal
/// (KHR_materials_clearcoat: its own normal map, else the interpolated normal without the base's
/// normal map). An instance's triangle (inst != GPU_NO_INSTANCE, shared/instance.h): p is the
/// triangle placed in the world (instanceWorldPrim), ab its object-space surface parameters (the
/// order of its attribute record), and each corner's normal and tangent is taken into the world
/// (inverse transpose, linear map; unit length) before interpolating, as the flattening loader does.
vec3 surfaceAt(uint prim, GpuPrim p, vec2 ab, vec3 ns, vec3 d, uint mi, inout GpuMaterial m, uint inst, out vec3 nCoat) {
    nCoat = ns;
    if (!HAS_VERTEX_ATTRIBUTES || primKind(p) != PRIM_TRIANGLE) return ns;
    int base = int(prim * ATTR_TEXELS);
    vec4 a0 = fetchF(uAttributes, base);
    vec4 a1 = fetchF(uAttributes, base + 1);
    uint flags = floatBitsToUint(a1.z);
    float w0 = 1.0f - ab.x - ab.y;
    vec3 n = ns;
    bool hasN = (flags & ATTR_HAS_NORMAL) != 0u;
    bool instanced = HAS_INSTANCES && inst != GPU_NO_INSTANCE;
    GpuInstance ins;
    if (instanced) ins = fetchInstance(inst);
    if (hasN) {
        vec3 n0 = fetchF(uAttributes, base + 2).xyz;
        vec3 n1 = fetchF(uAttributes, base + 3).xyz;
        vec3 n2 = fetchF(uAttributes, base + 4).xyz;
        if (instanced) {
            n0 = instanceNormalToWorld(ins, n0);
            n1 = instanceNormalToWorld(ins, n1);
            n2 = instanceNormalToWorld(ins, n2);
        }
        vec3 ni = w0 * n0 + ab.x * n1 + ab.y * n2;
        float len = length(ni);
        hasN = len > 0.0f;
        if (hasN) n = ni / len;  // the file's orientation (turned to the ray's side below)
    }
    vec3 nc = n;  // the coat's normal: the interpolated one unless the coat has a normal map
    bool hasNc = hasN;
    uint mtype = floatBitsToUint(m.m0.w) & 15u;
    bool layered = HAS_LAYERS && (floatBitsToUint(m.m0.w) & MATF_LAYERED) != 0u;
    if (HAS_TEXTURES && mtype == MAT_PBR && (flags & (ATTR_HAS_UV | ATTR_HAS_UV1)) != 0u) {
        vec2 uv = w0 * a0.xy + ab.x * a0.zw + ab.y * a1.xy;
        vec2 uv1 = attributeUv1(a1, ab, uv);
        uint rec = 1u + MAT_TEX_TEXELS * mi;
        vec4 c;
        if (HAS_EXTENSION_TEXTURES && transmitsAt(rec, uv, uv1, m)) {
            becomeTransmitted(m);  // what a constant transmissionFactor > 0 renders as: no other texture applies
            layered = false;
        } else {
            if (sampleSlot(rec, TEX_SLOT_BASE_COLOR, uv, uv1, c)) m.m0.xyz *= c.xyz;
            if (sampleSlot(rec, TEX_SLOT_METALLIC_ROUGHNESS, uv, uv1, c)) {
                m.m3.x *= c.z;  // metallic in B
                m.m3.y *= c.y;  // roughness in G
            }
            if (HAS_EXTENSION_TEXTURES) {
                // KHR_materials_specular: specular = specularFactor x specularTexture.a (linear),
                // specularColor = specularColorFactor x specularColorTexture.rgb (sRGB-decoded).
                if (sampleSlot(rec, TEX_SLOT_SPECULAR, uv, uv1, c)) m.m2.w *= c.w;
                if (sampleSlot(rec, TEX_SLOT_SPECULAR_COLOR, uv, uv1, c)) m.m2.xyz *= c.xyz;
            }
            if (layered) {
                // KHR_materials_clearcoat: factor x R, roughness x G; KHR_materials_sheen: colour x
                // RGB (sRGB-decoded), roughness x A.
                if (HAS_COAT && sampleSlot(rec, TEX_SLOT_CLEARCOAT, uv, uv1, c)) m.m4.x *= c.x;
                if (HAS_COAT && sampleSlot(rec, TEX_SLOT_CLEARCOAT_ROUGHNESS, uv, uv1, c)) m.m4.y *= c.y;
                if (HAS_SHEEN && sampleSlot(rec, TEX_SLOT_SHEEN_COLOR, uv, uv1, c)) m.m5.xyz *= c.xyz;
                if (HAS_SHEEN && sampleSlot(rec, TEX_SLOT_SHEEN_ROUGHNESS, uv, uv1, c)) m.m4.z *= c.w;
            }
            if ((flags & ATTR_HAS_TANGENT) != 0u) {
                // Without NORMAL a map perturbs the flat normal (glTF: flat shading), front = winding.
                vec3 nFlat = hasN ? n : normalize(cross(primEdge1(p), primEdge2(p)));
                vec4 cc;  // the base's map in c, the coat's in cc; one tangent frame for both
                bool mapBase = sampleSlot(rec, TEX_SLOT_NORMAL, uv, uv1, c);
                bool mapCoat = HAS_COAT && layered && sampleSlot(rec, TEX_SLOT_CLEARCOAT_NORMAL, uv, uv1, cc);
                vec3 tt, bt;
                if ((mapBase || mapCoat) && tangentFrame(base, ab, instanced, ins, nFlat, tt, bt)) {
                    if (mapBase) {
                        n = normalMapped(nFlat, tt, bt, c, uintBitsToFloat(texelFetch(uTexInfo, int(rec + MAT_TEX_ALPHA_TEXEL)).z));
                        hasN = true;
                    }
                    if (mapCoat) {
                        nc = normalMapped(nFlat, tt, bt, cc, uintBitsToFloat(texelFetch(uTexInfo, int(rec + MAT_TEX_LAYER_TEXEL)).x));
                        hasNc = true;
                    }
                }
            }
        }
    }
    // glTF COLOR_0 multiplies the base colour (not glass a transmissionTexture made: becomeTransmitted).
    if (HAS_VERTEX_COLORS && (floatBitsToUint(m.m0.w) & MAT_TYPE_MASK) == MAT_PBR) m.m0.xyz *= vertexColor(base, flags, ab).xyz;
    if (HAS_TEXTURES && HAS_EMITTERS && mtype == MAT_DIFFUSE_LIGHT && (flags & (ATTR_HAS_UV | ATTR_HAS_UV1)) != 0u) {
        vec4 c;  // a glTF emitter (kernelMaterial: diffuse_light) with an emissiveTexture
        vec2 uv = w0 * a0.xy + ab.x * a0.zw + ab.y * a1.xy;
        if (sampleSlot(1u + MAT_TEX_TEXELS * mi, TEX_SLOT_EMISSIVE, uv, attributeUv1(a1, ab, uv), c)) m.m1.xyz *= c.xyz;
    }
    if (layered) nCoat = facingNormal(nc, hasNc, ns, d);
    return facingNormal(n, hasN, ns, d);
}

/// The emissive texture at a point x sampled on light primitive `prim` (next-event estimation):
/// multiplies the emission of a diffuse_light material m with an emissiveTexture by its value
/// there; anything else is left alone.
void emissiveTextureAt(uint prim, GpuPrim p, vec3 x, inout GpuMaterial m) {
    if (!HAS_TEXTURES || !HAS_EMITTERS || primKind(p) != PRIM_TRIANGLE) return;
    if ((floatBitsToUint(m.m0.w) & 15u) != MAT_DIFFUSE_LIGHT) return;
    vec2 ab = primAbAt(p, x);  // x = v0 + a e1 + b e2
    float a = ab.x;
    float b = ab.y;
    int base = int(prim * ATTR_TEXELS);
    vec4 a0 = fetchF(uAttributes, base);
    vec4 a1 = fetchF(uAttributes, base + 1);
    if ((floatBitsToUint(a1.z) & (ATTR_HAS_UV | ATTR_HAS_UV1)) == 0u) return;
    vec4 c;
    vec2 uv = (1.0f - a - b) * a0.xy + a * a0.zw + b * a1.xy;
    if (sampleSlot(1u + MAT_TEX_TEXELS * primMaterial(p), TEX_SLOT_EMISSIVE, uv, attributeUv1(a1, vec2(a, b), uv), c))
        m.m1.xyz *= c.xyz;
}

#endif
