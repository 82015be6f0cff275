// The descriptor bindings of the path-tracing kernel as the host creates them: one table, in
// binding order, of the numbers declared in shaders/shared/kernel_interface.h (the GLSL side:
// shaders/lib/bindings.glsl). No Vulkan here: render/renderer.cpp maps the kinds to
// vk::DescriptorType.
#pragma once
#include <cstdint>
#include <iterator>

#include "shared/kernel_interface.h"

namespace vkp {

enum class BindingKind : std::uint8_t { UniformBuffer, UniformTexelBuffer, StorageBuffer };

struct KernelBinding {
    std::uint32_t binding;  ///< VKP_BINDING_*
    BindingKind kind;
    const char* name;       ///< the GLSL name, for messages
};

inline constexpr KernelBinding kKernelBindings[] = {
    {VKP_BINDING_FRAME, BindingKind::UniformBuffer, "frame"},
    {VKP_BINDING_NODES, BindingKind::UniformTexelBuffer, "uNodes"},
    {VKP_BINDING_PRIMS, BindingKind::UniformTexelBuffer, "uPrims"},
    {VKP_BINDING_MATERIALS, BindingKind::UniformTexelBuffer, "uMaterials"},
    {VKP_BINDING_LIGHTS, BindingKind::UniformTexelBuffer, "uLights"},
    {VKP_BINDING_ACCUM_SUM, BindingKind::StorageBuffer, "accumSum"},
    {VKP_BINDING_ACCUM_SQ, BindingKind::StorageBuffer, "accumSq"},
    {VKP_BINDING_COUNTERS, BindingKind::StorageBuffer, "counters"},
    {VKP_BINDING_ENV_TEXELS, BindingKind::UniformTexelBuffer, "uEnvTexels"},
    {VKP_BINDING_ENV_DIST, BindingKind::UniformTexelBuffer, "uEnvDist"},
    {VKP_BINDING_DECISION, BindingKind::StorageBuffer, "decisionSums"},
    {VKP_BINDING_ACTIVE, BindingKind::StorageBuffer, "activePixels"},
    {VKP_BINDING_ATTRIBUTES, BindingKind::UniformTexelBuffer, "uAttributes"},
    {VKP_BINDING_TEX_INFO, BindingKind::UniformTexelBuffer, "uTexInfo"},
    {VKP_BINDING_TEXELS, BindingKind::UniformTexelBuffer, "uTexels"},
    {VKP_BINDING_INSTANCES, BindingKind::UniformTexelBuffer, "uInstances"},
};
static_assert(std::size(kKernelBindings) == VKP_BINDING_COUNT, "one entry per binding of shared/kernel_interface.h");

/// True if entry i of kKernelBindings is binding i.
constexpr bool kernelBindingsInOrder() {
    for (std::uint32_t i = 0; i < std::size(kKernelBindings); ++i)
        if (kKernelBindings[i].binding != i) return false;
    return true;
}
static_assert(kernelBindingsInOrder(), "kKernelBindings in binding order, without gaps");

}  // namespace vkp
