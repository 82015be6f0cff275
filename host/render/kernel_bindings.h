// The descriptor bindings of the path-tracing kernel as the host creates them: one table, in
// binding order, of the numbers declared in shaders/shared/kernel_interface.h (the GLSL side:
// shaders/lib/bindings.glsl), with the descriptor kind and the texel format of each. No Vulkan
// here: render/renderer.cpp maps them to vk::DescriptorType and vk::Format, render/gpu_arrays.h
// sizes every buffer by them.
#pragma once
#include <cstdint>
#include <iterator>

#include "shared/kernel_interface.h"

namespace vkp {

enum class BindingKind : std::uint8_t { UniformBuffer, UniformTexelBuffer, StorageBuffer };
/// The format of a texel buffer's view (None for the other kinds).
enum class TexelFormat : std::uint8_t { None, Rgba32Uint, R32Float, R32Uint };

/// Bytes of one texel of `f` (0 for None).
constexpr std::uint32_t texelBytes(TexelFormat f) { return f == TexelFormat::Rgba32Uint ? 16u : f == TexelFormat::None ? 0u : 4u; }

struct KernelBinding {
    std::uint32_t binding;  ///< VKP_BINDING_*
    BindingKind kind;
    TexelFormat format;
    const char* name;       ///< the GLSL name, for messages
};

inline constexpr KernelBinding kKernelBindings[] = {
    {VKP_BINDING_FRAME, BindingKind::UniformBuffer, TexelFormat::None, "frame"},
    {VKP_BINDING_NODES, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uNodes"},
    {VKP_BINDING_PRIMS, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uPrims"},
    {VKP_BINDING_MATERIALS, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uMaterials"},
    {VKP_BINDING_LIGHTS, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uLights"},
    {VKP_BINDING_ACCUM_SUM, BindingKind::StorageBuffer, TexelFormat::None, "accumSum"},
    {VKP_BINDING_ACCUM_SQ, BindingKind::StorageBuffer, TexelFormat::None, "accumSq"},
    {VKP_BINDING_COUNTERS, BindingKind::StorageBuffer, TexelFormat::None, "counters"},
    {VKP_BINDING_ENV_TEXELS, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uEnvTexels"},
    {VKP_BINDING_ENV_DIST, BindingKind::UniformTexelBuffer, TexelFormat::R32Float, "uEnvDist"},
    {VKP_BINDING_DECISION, BindingKind::StorageBuffer, TexelFormat::None, "decisionSums"},
    {VKP_BINDING_ACTIVE, BindingKind::StorageBuffer, TexelFormat::None, "activePixels"},
    {VKP_BINDING_ATTRIBUTES, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uAttributes"},
    {VKP_BINDING_TEX_INFO, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uTexInfo"},
    {VKP_BINDING_TEXELS, BindingKind::UniformTexelBuffer, TexelFormat::R32Uint, "uTexels"},
    {VKP_BINDING_INSTANCES, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uInstances"},
    {VKP_BINDING_MOTION, BindingKind::UniformTexelBuffer, TexelFormat::Rgba32Uint, "uMotion"},
    {VKP_BINDING_AOV, BindingKind::StorageBuffer, TexelFormat::None, "aovSums"},
};
static_assert(std::size(kKernelBindings) == VKP_BINDING_COUNT, "one entry per binding of shared/kernel_interface.h");

/// True if entry i of kKernelBindings is binding i.
constexpr bool kernelBindingsInOrder() {
    for (std::uint32_t i = 0; i < std::size(kKernelBindings); ++i)
        if (kKernelBindings[i].binding != i) return false;
    return true;
}
static_assert(kernelBindingsInOrder(), "kKernelBindings in binding order, without gaps");

/// The kernel's bindings of kind k.
constexpr std::uint32_t kernelBindingCount(BindingKind k) {
    std::uint32_t n = 0;
    for (const KernelBinding& b : kKernelBindings) n += b.kind == k ? 1u : 0u;
    return n;
}

/// The bindings that hold something per pixel (accumulation, adaptive sampling, feature images):
/// sized by the image, one buffer of each per band of rows (render/gpu_arrays.h planBands).
constexpr bool isPerPixelBinding(std::uint32_t binding) {
    return binding == VKP_BINDING_ACCUM_SUM || binding == VKP_BINDING_ACCUM_SQ || binding == VKP_BINDING_DECISION ||
           binding == VKP_BINDING_ACTIVE || binding == VKP_BINDING_AOV;
}

}  // namespace vkp
