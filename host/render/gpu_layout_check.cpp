// Compile-time checks that the GPU structs of shaders/shared/gpu_types.h are packed as the kernels
// read them: whole vec4 texels, no padding, the texel counts the fetches use.
#include <cstddef>

#include "shared/gpu_types.h"
#include "shared/instance.h"

namespace vkp::gpu {

static_assert(sizeof(GpuPrim) == GPU_PRIM_TEXELS * 16, "GpuPrim: GPU_PRIM_TEXELS vec4 texels");
static_assert(sizeof(GpuNode) == GPU_NODE_TEXELS * 16, "GpuNode: GPU_NODE_TEXELS vec4 texels");
static_assert(sizeof(GpuMaterial) == GPU_MATERIAL_TEXELS * 16, "GpuMaterial: GPU_MATERIAL_TEXELS vec4 texels");
static_assert(offsetof(GpuMaterial, m2) == 32 && offsetof(GpuMaterial, m3) == 48, "GpuMaterial texel order");
static_assert(sizeof(GpuLight) == GPU_LIGHT_TEXELS * 16, "GpuLight: GPU_LIGHT_TEXELS vec4 texels");
static_assert(sizeof(GpuFrame) == 12 * 16, "GpuFrame: twelve vec4 members (std140)");
static_assert(offsetof(GpuFrame, env) == 10 * 16 && offsetof(GpuFrame, envSize) == 11 * 16, "GpuFrame member order");
static_assert(sizeof(GpuInstance) == GPU_INSTANCE_TEXELS * 16, "GpuInstance: GPU_INSTANCE_TEXELS vec4 texels");
static_assert(offsetof(GpuInstance, w2o0) == 16 && offsetof(GpuInstance, o2w0) == 4 * 16 && offsetof(GpuInstance, o2w2) == 6 * 16,
              "GpuInstance texel order: info, world-to-object rows, object-to-world rows");
static_assert(sizeof(GpuPush) == 2 * 16 && offsetof(GpuPush, adaptive) == 16, "GpuPush: two uvec4 (push constants)");

}  // namespace vkp::gpu
