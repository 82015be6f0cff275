#include "vk/memory_choice.h"

namespace vkp {

namespace {
using Flags = vk::MemoryPropertyFlags;
using Bit = vk::MemoryPropertyFlagBits;

constexpr Flags kHostMappable = Bit::eHostVisible | Bit::eHostCoherent | Bit::eHostCached;

/// The admitted type that `accept` takes with the largest heap (the lowest index among equals).
template <class Accept>
std::optional<std::uint32_t> best(const vk::PhysicalDeviceMemoryProperties& props, std::uint32_t typeBits, Accept accept) {
    std::optional<std::uint32_t> found;
    vk::DeviceSize foundHeap = 0;
    for (std::uint32_t i = 0; i < props.memoryTypeCount && i < 32; ++i) {
        if (!(typeBits & (1u << i)) || !accept(props.memoryTypes[i].propertyFlags)) continue;
        const std::uint32_t heap = props.memoryTypes[i].heapIndex;
        const vk::DeviceSize size = heap < props.memoryHeapCount ? props.memoryHeaps[heap].size : 0;
        if (!found || size > foundHeap) {
            found = i;
            foundHeap = size;
        }
    }
    return found;
}
}  // namespace

std::optional<BufferMemoryChoice> chooseBufferMemory(const vk::PhysicalDeviceMemoryProperties& props, std::uint32_t typeBits,
                                                     bool allowMapping) {
    auto has = [](Flags f, Flags want) { return (f & want) == want; };
    if (allowMapping)
        if (auto t = best(props, typeBits, [&](Flags f) { return has(f, Bit::eDeviceLocal | kHostMappable); }))
            return BufferMemoryChoice{*t, true};
    if (auto t = best(props, typeBits, [&](Flags f) { return has(f, Bit::eDeviceLocal) && !has(f, Bit::eHostVisible); }))
        return BufferMemoryChoice{*t, false};
    auto t = best(props, typeBits, [&](Flags f) { return has(f, Bit::eDeviceLocal); });
    if (!t) t = best(props, typeBits, [](Flags) { return true; });
    if (!t) return std::nullopt;
    return BufferMemoryChoice{*t, allowMapping && has(props.memoryTypes[*t].propertyFlags, kHostMappable)};
}

}  // namespace vkp
