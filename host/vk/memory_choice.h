// Which Vulkan memory type a GpuBuffer lives in, and whether the host reaches it through a mapping
// or through staging copies: a pure function of the device's memory properties, so that the choice
// for devices vkpath has never run on (discrete GPUs with and without resizable BAR, integrated
// GPUs) is tested here (tests/unit/test_memory_choice.cpp). docs/design.md "Buffer memory".
#pragma once
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.hpp>

namespace vkp {

struct BufferMemoryChoice {
    std::uint32_t type = 0;  ///< index into VkPhysicalDeviceMemoryProperties::memoryTypes
    bool mapped = false;     ///< the host reads and writes it through a persistent mapping
};

/// The memory type of a buffer whose requirements allow `typeBits`:
///   - device-local memory that is also host-visible, coherent and cached, mapped, where the device
///     has it and `allowMapping` (unified memory: lavapipe, integrated GPUs): the host's reads of
///     the sums are ordinary cached reads and no copy is needed;
///   - otherwise device-local memory that is not host-visible, reached through staging buffers: a
///     discrete GPU's host-visible device-local window (the PCIe BAR) is left alone, because without
///     resizable BAR its heap is small (often 256 MB, far below what the device's largest heap,
///     which the render's fit check counts on, promises) and it is uncached, so reading sums back
///     from it is slow;
///   - otherwise any device-local type, then any type at all (a device without device-local
///     memory), unmapped unless cached, host-visible and coherent and `allowMapping`.
/// Among equals the type whose heap is largest wins, then the lowest index (the order Vulkan
/// asks drivers to list types in, best first). Returns nothing when typeBits admits no type.
std::optional<BufferMemoryChoice> chooseBufferMemory(const vk::PhysicalDeviceMemoryProperties& props, std::uint32_t typeBits,
                                                     bool allowMapping);

}  // namespace vkp
