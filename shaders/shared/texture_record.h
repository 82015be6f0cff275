// The per-material texture record of the kernel, C++ and GLSL (glsl_compat.h rules): the one
// declaration of its layout. host/render/texture_pack.cpp writes it, shaders/lib/surface.glsl and
// lib/alpha.glsl read it; host/render/gpu_layout_check.cpp static_asserts it.
//
// RGBA32UI texels, material m's record at texel 1 + MAT_TEX_TEXELS m of the texture-info buffer:
//   per slot s (TEX_SLOT_*), two texels at 2 s and 2 s + 1:
//     (rotation x scale as rs: cos sx, sin sy, -sin sx, cos sy; float bits)
//     (offset.x, offset.y (float bits), texture header index or TEX_NO_TEXTURE, UV set: 0 for
//      TEXCOORD_0, 1 for TEXCOORD_1)
//   then at MAT_TEX_ALPHA_TEXEL: (alpha mode, alphaCutoff, normalTexture.scale, baseColorFactor.a),
//   and at MAT_TEX_LAYER_TEXEL: (clearcoatNormalTexture.scale as float bits, 0, 0, 0).
#ifndef VKP_TEXTURE_RECORD_H
#define VKP_TEXTURE_RECORD_H
#include "glsl_compat.h"

VKP_BEGIN

const uint TEX_SLOT_BASE_COLOR = 0u;          // sRGB; RGB x baseColorFactor, A x its alpha
const uint TEX_SLOT_METALLIC_ROUGHNESS = 1u;  // linear; metallic in B, roughness in G
const uint TEX_SLOT_NORMAL = 2u;              // linear tangent-space normal
const uint TEX_SLOT_EMISSIVE = 3u;            // sRGB; emitters (diffuse_light) only
const uint TEX_SLOT_SPECULAR = 4u;            // KHR_materials_specular specularTexture: linear, A x specularFactor
const uint TEX_SLOT_SPECULAR_COLOR = 5u;      // ... specularColorTexture: sRGB, RGB x specularColorFactor
const uint TEX_SLOT_TRANSMISSION = 6u;        // KHR_materials_transmission transmissionTexture: linear, R x transmissionFactor
const uint TEX_SLOT_CLEARCOAT = 7u;           // KHR_materials_clearcoat clearcoatTexture: linear, R x clearcoatFactor
const uint TEX_SLOT_CLEARCOAT_ROUGHNESS = 8u; // ... clearcoatRoughnessTexture: linear, G x clearcoatRoughnessFactor
const uint TEX_SLOT_CLEARCOAT_NORMAL = 9u;    // ... clearcoatNormalTexture: linear tangent-space normal of the coat
const uint TEX_SLOT_SHEEN_COLOR = 10u;        // KHR_materials_sheen sheenColorTexture: sRGB, RGB x sheenColorFactor
const uint TEX_SLOT_SHEEN_ROUGHNESS = 11u;    // ... sheenRoughnessTexture: linear, A x sheenRoughnessFactor
const uint TEX_SLOTS = 12u;
const uint MAT_TEX_ALPHA_TEXEL = 2u * TEX_SLOTS;       // (alpha mode, cutoff, normal scale, alpha factor)
const uint MAT_TEX_LAYER_TEXEL = 2u * TEX_SLOTS + 1u;  // (clearcoatNormalTexture.scale, 0, 0, 0)
const uint MAT_TEX_TEXELS = 2u * TEX_SLOTS + 2u;       // texels of one material record
const uint TEX_NO_TEXTURE = 0xffffffffu;

VKP_END
#endif
