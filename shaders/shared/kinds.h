// Every enumeration that the host and the kernels share, defined once here for both languages:
// primitive kinds, material types and flags, samplers, sample sequences, alpha modes and the
// vertex-attribute flags. The host's enums are defined from these values (host/scene/scene.h
// MaterialType, ShapeType, AlphaMode, TriangleVertices flags; host/render/features.h Sampler,
// Sequence), so the two sides cannot drift apart.
#ifndef VKP_KINDS_H
#define VKP_KINDS_H
#include "glsl_compat.h"

VKP_BEGIN

// ---- Primitive kinds: the low 2 bits of a GpuPrim's header word (shared/gpu_types.h) ----------
const uint PRIM_SPHERE = 0u;
const uint PRIM_QUAD = 1u;      // parallelogram Q + a u + b v, a,b in [0,1]
const uint PRIM_TRIANGLE = 2u;  // v0 + a (v1 - v0) + b (v2 - v0), a,b >= 0, a + b <= 1
const uint PRIM_INSTANCE = 3u;  // top level of a two-level BVH: an instance of a mesh (shared/instance.h)
const uint PRIM_KIND_COUNT = 4u;

// ---- Kernel material types: the low 4 bits of GpuMaterial::m0.w --------------------------------
const uint MAT_LAMBERTIAN = 0u;
const uint MAT_METAL = 1u;
const uint MAT_DIELECTRIC = 2u;
const uint MAT_DIFFUSE_LIGHT = 3u;
const uint MAT_PBR = 4u;  // glTF metallic-roughness BRDF (shared/microfacet.h)
const uint MAT_ISOTROPIC = 5u;  // the isotropic phase function of a constant_medium (shared/medium.h):
                                // no surface uses it; its bit in MATERIALS compiles media in
const uint MAT_TYPE_COUNT = 6u;
const uint MAT_TYPE_MASK = 15u;  // the type's bits of the flags word
// Flag bits above the type.
const uint MATF_TWO_SIDED = 16u;      // diffuse_light: both faces emit
const uint MATF_FRESNEL_EXACT = 32u;  // dielectric: exact Fresnel instead of Schlick
const uint MATF_EMITS = 64u;          // emit != 0
const uint MATF_LAYERED = 128u;       // pbr: a clear coat or sheen (GpuMaterial m4, m5; shared/layers.h)
const uint MATF_SOLID_TEXTURE = 256u; // lambertian, metal, diffuse_light: JSON textures give the
                                      // albedo or emission (GpuMaterial m2.xy; lib/solid_texture.glsl)

// ---- Textures of JSON scenes (shared/solid_texture.h): node kinds and limits --------------------
const uint STEX_SOLID = 0u;
const uint STEX_CHECKER = 1u;
const uint STEX_IMAGE = 2u;
const uint STEX_NOISE = 3u;
const uint STEX_TURBULENCE = 4u;
const uint STEX_MARBLE = 5u;
const uint STEX_NODE_TEXELS = 2u;
const uint PERLIN_POINTS = 256u;     // the book's point_count
const int TURBULENCE_OCTAVES = 7;    // the book's turb(p, 7)
// Checkers nest (a checker's even or odd side may be a checker): at most this many checkers on
// the way from a material's texture to the texture that colours the point (the loader refuses
// deeper nesting, and cycles).
const uint STEX_MAX_DEPTH = 16u;

// ---- Boundaries of constant-density media (GpuMedium::params.y; shared/medium.h) -----------------
const uint MEDIUM_SPHERE = 0u;  // the unit ball of the medium's local space (|x| <= 1)
const uint MEDIUM_BOX = 1u;     // the cube [-1, 1]^3 of its local space
// Media are tested one after the other along every ray (no BVH over them): at most this many.
const uint MAX_MEDIA = 64u;

// ---- Layers over the glTF BRDF (specialization constant LAYERS; shared/layers.h) ----------------
const uint LAYER_COAT = 1u;   // KHR_materials_clearcoat
const uint LAYER_SHEEN = 2u;  // KHR_materials_sheen

// ---- Punctual lights (shared/punctual_light.h): the kind in GpuPunctualLight::q0.w ----------------
const uint PUNCTUAL_POINT = 0u;
const uint PUNCTUAL_SPOT = 1u;
const uint PUNCTUAL_DIRECTIONAL = 2u;
const uint PUNCTUAL_KIND_COUNT = 3u;
// A light-list entry (GpuLight::l0.x) with this bit names punctual light (l0.x & ~bit), not a primitive.
const uint LIGHT_PUNCTUAL_BIT = 0x80000000u;
// The bit of the LIGHTS specialization constant for punctual lights (the others: PRIM_* kinds).
const uint LIGHT_KIND_PUNCTUAL = PRIM_KIND_COUNT;

// ---- How a diffuse vertex is sampled (specialization constant SAMPLER) -------------------------
const uint SAMPLER_BSDF = 0u;     // BSDF sampling only; emission counted where rays hit it
const uint SAMPLER_LIGHT = 1u;    // next-event estimation: one light sample + shadow ray per vertex
const uint SAMPLER_MIXTURE = 2u;  // the book: 0.5 BSDF + 0.5 lights (uniform pick), one direction
const uint SAMPLER_MIS = 3u;      // light sample + BSDF sample, power heuristic (Veach 1997)

// ---- Where a sample's random numbers come from (specialization constant SEQUENCE) --------------
const uint SEQUENCE_RANDOM = 0u;  // independent hashed random numbers per dimension (shared/rng.h)
const uint SEQUENCE_SOBOL = 1u;   // Owen-scrambled Sobol' points, padded (shared/sobol.h)

// ---- glTF alphaMode (the material texture record's alpha texel, shared/texture_record.h) -------
const uint ALPHA_OPAQUE = 0u;
const uint ALPHA_MASK = 1u;
const uint ALPHA_BLEND = 2u;

// ---- Vertex-attribute records (lib/surface.glsl, host/render/texture_pack.h) -------------------
const uint ATTR_TEXELS = 8u;       // texels per primitive
const uint ATTR_HAS_NORMAL = 1u;   // else shade with the geometric (flat) normal
const uint ATTR_HAS_UV = 2u;       // TEXCOORD_0 (else UV = (0,0))
const uint ATTR_HAS_TANGENT = 4u;  // from the file, or generated for a normal map
const uint ATTR_HAS_UV1 = 8u;      // TEXCOORD_1: its 2-texel record at the texel in the record's second w
const uint ATTR_HAS_COLOR = 16u;   // COLOR_0: its 2-texel record (half floats) at the texel in the record's third w

VKP_END

#ifdef __cplusplus
namespace vkp::gpu {
/// Names of the kinds above, indexed by their value (variant names, messages).
inline constexpr const char* kPrimKindNames[] = {"sphere", "quad", "triangle", "instance"};
inline constexpr const char* kPunctualKindNames[] = {"point", "spot", "directional"};
inline constexpr const char* kMaterialTypeNames[] = {"lambertian", "metal", "dielectric", "diffuse_light", "pbr", "isotropic"};
static_assert(sizeof(kPrimKindNames) / sizeof(kPrimKindNames[0]) == PRIM_KIND_COUNT, "a name per primitive kind");
static_assert(sizeof(kPunctualKindNames) / sizeof(kPunctualKindNames[0]) == PUNCTUAL_KIND_COUNT, "a name per punctual kind");
static_assert(sizeof(kMaterialTypeNames) / sizeof(kMaterialTypeNames[0]) == MAT_TYPE_COUNT, "a name per material type");
}  // namespace vkp::gpu
#endif

#endif
