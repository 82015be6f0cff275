// Compile-time checks that the GPU structs of shaders/shared/gpu_types.h are packed as the kernels
// read them: whole vec4 texels, no padding, the texel counts the fetches use.
#include <cstddef>

#include "shared/gpu_types.h"
#include "shared/instance.h"
#include "shared/medium.h"
#include "shared/texture_record.h"

namespace vkp::gpu {

static_assert(sizeof(GpuPrim) == GPU_PRIM_TEXELS * 16, "GpuPrim: GPU_PRIM_TEXELS vec4 texels");
static_assert(sizeof(GpuNode) == GPU_NODE_TEXELS * 16, "GpuNode: GPU_NODE_TEXELS vec4 texels");
static_assert(sizeof(GpuMotion) == GPU_MOTION_TEXELS * 16, "GpuMotion: GPU_MOTION_TEXELS vec4 texels");
static_assert(sizeof(GpuMaterial) == GPU_MATERIAL_TEXELS * 16, "GpuMaterial: GPU_MATERIAL_TEXELS vec4 texels");
static_assert(offsetof(GpuMaterial, m2) == 32 && offsetof(GpuMaterial, m3) == 48 && offsetof(GpuMaterial, m4) == 64 &&
                  offsetof(GpuMaterial, m5) == 80,
              "GpuMaterial texel order");
static_assert(sizeof(GpuLight) == GPU_LIGHT_TEXELS * 16, "GpuLight: GPU_LIGHT_TEXELS vec4 texels");
static_assert(sizeof(GpuPunctualLight) == GPU_PUNCTUAL_TEXELS * 16 && offsetof(GpuPunctualLight, q3) == 48,
              "GpuPunctualLight: GPU_PUNCTUAL_TEXELS vec4 texels, in order");
static_assert(GPU_PUNCTUAL_TEXELS % GPU_LIGHT_TEXELS == 0, "punctual records are whole GpuLight entries of the lights buffer");
static_assert(sizeof(GpuFrame) == 13 * 16, "GpuFrame: thirteen vec4 members (std140)");
static_assert(offsetof(GpuFrame, env) == 9 * 16 && offsetof(GpuFrame, envSize) == 10 * 16 &&
                  offsetof(GpuFrame, punctual) == 11 * 16 && offsetof(GpuFrame, media) == 12 * 16,
              "GpuFrame member order");
static_assert(sizeof(GpuInstance) == GPU_INSTANCE_TEXELS * 16, "GpuInstance: GPU_INSTANCE_TEXELS vec4 texels");
static_assert(offsetof(GpuInstance, w2o0) == 16 && offsetof(GpuInstance, o2w0) == 4 * 16 && offsetof(GpuInstance, o2w2) == 6 * 16,
              "GpuInstance texel order: info, world-to-object rows, object-to-world rows");
static_assert(sizeof(GpuMedium) == GPU_MEDIUM_TEXELS * 16 && offsetof(GpuMedium, params) == 48,
              "GpuMedium: GPU_MEDIUM_TEXELS vec4 texels, the three rows then the parameters");
static_assert(sizeof(GpuPush) == 3 * 16 && offsetof(GpuPush, adaptive) == 16 && offsetof(GpuPush, band) == 32,
              "GpuPush: three uvec4 (push constants)");

static_assert(MAT_TEX_TEXELS == 2 * TEX_SLOTS + 2 && MAT_TEX_ALPHA_TEXEL == 2 * TEX_SLOTS && MAT_TEX_LAYER_TEXEL == 2 * TEX_SLOTS + 1,
              "texture record: two texels per slot, then the alpha texel, then the layer texel");
static_assert(TEX_SLOT_BASE_COLOR == 0 && TEX_SLOT_METALLIC_ROUGHNESS == 1 && TEX_SLOT_NORMAL == 2 && TEX_SLOT_EMISSIVE == 3 &&
                  TEX_SLOT_SPECULAR == 4 && TEX_SLOT_SPECULAR_COLOR == 5 && TEX_SLOT_TRANSMISSION == 6 &&
                  TEX_SLOT_CLEARCOAT == 7 && TEX_SLOT_CLEARCOAT_ROUGHNESS == 8 && TEX_SLOT_CLEARCOAT_NORMAL == 9 &&
                  TEX_SLOT_SHEEN_COLOR == 10 && TEX_SLOT_SHEEN_ROUGHNESS == 11 && TEX_SLOTS == 12,
              "texture record: slot order (host/render/texture_pack.cpp packs them in this order)");

}  // namespace vkp::gpu
