// Packing glTF textures and per-vertex attributes for the kernel (shaders/lib/surface.glsl).
// Texel layouts are documented in shaders/shared/texture_sample.h and surface.glsl.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/flatten.h"
#include "scene/scene.h"
#include "shared/texture_record.h"

namespace vkp {

/// Texture slots of a material record, in this order (layout: shaders/shared/texture_record.h).
inline constexpr std::uint32_t kTexSlotBaseColor = gpu::TEX_SLOT_BASE_COLOR,
                               kTexSlotMetallicRoughness = gpu::TEX_SLOT_METALLIC_ROUGHNESS,
                               kTexSlotNormal = gpu::TEX_SLOT_NORMAL, kTexSlotEmissive = gpu::TEX_SLOT_EMISSIVE,
                               kTexSlotSpecular = gpu::TEX_SLOT_SPECULAR,
                               kTexSlotSpecularColor = gpu::TEX_SLOT_SPECULAR_COLOR,
                               kTexSlotTransmission = gpu::TEX_SLOT_TRANSMISSION, kTexSlots = gpu::TEX_SLOTS;
/// Texels of one material record: two per slot (transform; offset + header index) and one more
/// (alpha mode, alpha cutoff, normal scale, base colour alpha).
inline constexpr std::uint32_t kMatTexTexels = gpu::MAT_TEX_TEXELS;
/// Texels of one primitive's vertex-attribute record: uv0 uv1 | uv2 flags uv1At | n0 | n1 | n2 | t0 | t1 |
/// t2 (uv0..2: TEXCOORD_0 of the corners; uv1At: first texel of its TEXCOORD_1 record, 0: none).
inline constexpr std::uint32_t kAttributeTexels = gpu::ATTR_TEXELS;
inline constexpr std::uint32_t kNoTexture = gpu::TEX_NO_TEXTURE;

struct TexturePack {
    /// RGBA32UI: [0] = (first texture header, material count, texture count, first texel of the
    /// JSON textures or 0); material m's record at 1 + kMatTexTexels m; texture t's header
    /// (shared/texture_sample.h) at info[0].x + t; then the JSON textures (Scene::solidTextures,
    /// layout: shared/solid_texture.h), if any.
    std::vector<glm::uvec4> info;
    /// R32UI: every image's RGBA8 texels, one after the other (never empty: a token texel).
    std::vector<std::uint32_t> texels;
};

/// The textures and per-material texture records of `scene` (kernel materials: kernelMaterial);
/// without materialRecords (a variant that reads only JSON textures) no record (material count 0).
TexturePack packTextures(const Scene& scene, bool materialRecords = true);

/// One kAttributeTexels record per BVH primitive (bvh.prims order, primShape): UVs, shading normals
/// and tangents of mesh triangles (object space for an instanced mesh's); zeros (flags 0: no
/// attributes) for every other primitive. After them, in primitive order, a two-texel TEXCOORD_1
/// record, (c0, c1) | (c2, 0, 0), per triangle that has TEXCOORD_1 (at the texel in the w of the
/// record's second texel) and a two-texel COLOR_0 record per triangle that has COLOR_0, RGBA of
/// each corner as half floats, packHalf2x16 (r, g), (b, a): (c0.rg, c0.ba, c1.rg, c1.ba) |
/// (c2.rg, c2.ba, 0, 0) (at the texel in the w of the record's third texel); 0: none. Only scenes
/// that have them pay for them.
std::vector<glm::uvec4> packVertexAttributes(const Scene& scene, const FlatBvh& bvh);

/// True if some kernel material of a shape in the scene reads a texture (HAS_TEXTURES).
bool sceneHasTextures(const Scene& scene);
/// True if some kernel material of a shape reads a KHR_materials_specular texture
/// (specularTexture, specularColorTexture) or a transmissionTexture that decides per hit
/// (transmissionTextured): HAS_EXTENSION_TEXTURES, constant_id 23.
bool sceneHasExtensionTextures(const Scene& scene);
/// True if some texture slot the kernel reads (packTextures) of a shape's material uses TEXCOORD_1
/// (HAS_TEXCOORD1, constant_id 24).
bool sceneHasTexCoord1(const Scene& scene);
/// True if some kernel material of a shape has alphaMode MASK or BLEND (HAS_ALPHA).
bool sceneHasAlpha(const Scene& scene);
/// True if some mesh triangle with a MAT_PBR kernel material has NORMAL or TEXCOORD_0
/// (HAS_VERTEX_ATTRIBUTES).
bool sceneHasVertexAttributes(const Scene& scene);
/// True if some mesh triangle with a MAT_PBR kernel material has COLOR_0 (HAS_VERTEX_COLORS).
bool sceneHasVertexColors(const Scene& scene);

}  // namespace vkp
