// The memory type of a GpuBuffer (vk/memory_choice.h) on the memory layouts of devices vkpath has
// never run on: the layouts below are those that lavapipe, NVIDIA's and AMD's discrete drivers and
// Intel's integrated driver report (type flags and heaps as vulkaninfo lists them, sizes rounded).
#include <gtest/gtest.h>

#include <initializer_list>
#include <utility>

#include "vk/memory_choice.h"

namespace vkp {
namespace {

using Bit = vk::MemoryPropertyFlagBits;
using Flags = vk::MemoryPropertyFlags;
constexpr vk::DeviceSize MiB = 1024ull * 1024ull;
constexpr vk::DeviceSize GiB = 1024ull * MiB;
const Flags DL = Bit::eDeviceLocal;
const Flags HV = Bit::eHostVisible;
const Flags HC = Bit::eHostCoherent;
const Flags CA = Bit::eHostCached;

/// Memory properties from heaps (size, device-local) and types (flags, heap index).
vk::PhysicalDeviceMemoryProperties layout(std::initializer_list<std::pair<vk::DeviceSize, bool>> heaps,
                                          std::initializer_list<std::pair<Flags, std::uint32_t>> types) {
    vk::PhysicalDeviceMemoryProperties p{};
    for (const auto& [size, local] : heaps) {
        p.memoryHeaps[p.memoryHeapCount].size = size;
        if (local) p.memoryHeaps[p.memoryHeapCount].flags = vk::MemoryHeapFlagBits::eDeviceLocal;
        ++p.memoryHeapCount;
    }
    for (const auto& [flags, heap] : types) {
        p.memoryTypes[p.memoryTypeCount].propertyFlags = flags;
        p.memoryTypes[p.memoryTypeCount].heapIndex = heap;
        ++p.memoryTypeCount;
    }
    return p;
}

constexpr std::uint32_t kAll = 0xffffffffu;

/// chooseBufferMemory(p, typeBits, allowMapping) picks `type`, mapped or not.
::testing::AssertionResult chooses(const vk::PhysicalDeviceMemoryProperties& p, std::uint32_t typeBits, bool allowMapping,
                                   std::uint32_t type, bool mapped) {
    const auto c = chooseBufferMemory(p, typeBits, allowMapping);
    if (!c) return ::testing::AssertionFailure() << "no type chosen";
    if (c->type != type || c->mapped != mapped)
        return ::testing::AssertionFailure() << "type " << c->type << (c->mapped ? " mapped" : " unmapped") << ", expected " << type
                                             << (mapped ? " mapped" : " unmapped");
    return ::testing::AssertionSuccess();
}

TEST(MemoryChoice, LavapipeMapsItsOneUnifiedType) {
    const auto p = layout({{2 * GiB, true}}, {{DL | HV | HC | CA, 0}});
    EXPECT_TRUE(chooses(p, kAll, true, 0u, true));
    // VKPATH_NO_BUFFER_MAPPING: the same memory, reached through staging copies.
    EXPECT_TRUE(chooses(p, kAll, false, 0u, false));
}

// NVIDIA without resizable BAR: the host-visible device-local window is a 246 MB heap of its own.
// Taking it would put every buffer there (a 300 MB scene would fail to allocate on an 8 GB card)
// and make each read of the sums an uncached read across PCIe.
TEST(MemoryChoice, DiscreteGpuLeavesTheSmallBarWindowAlone) {
    const auto p = layout({{8 * GiB, true}, {16 * GiB, false}, {246 * MiB, true}},
                          {{Flags{}, 1}, {DL, 0}, {HV | HC, 1}, {HV | HC | CA, 1}, {DL | HV | HC, 2}});
    for (bool allow : {true, false}) EXPECT_TRUE(chooses(p, kAll, allow, 1u, false));
    // Only the window allowed by the buffer's requirements: device-local still, through staging.
    EXPECT_TRUE(chooses(p, (1u << 2) | (1u << 4), true, 4u, false));
}

// AMD with resizable BAR (Smart Access Memory): all of VRAM is host-visible, but uncached.
TEST(MemoryChoice, ResizableBarIsNotMappedForReading) {
    const auto p = layout({{16 * GiB, true}, {32 * GiB, false}}, {{DL, 0}, {HV | HC, 1}, {DL | HV | HC, 0}, {HV | HC | CA, 1}});
    EXPECT_TRUE(chooses(p, kAll, true, 0u, false));
}

// Intel's integrated GPUs share system memory: the cached, coherent device-local type is mapped.
TEST(MemoryChoice, IntegratedGpuMapsItsCachedCoherentType) {
    const auto p = layout({{12 * GiB, true}}, {{DL, 0}, {DL | HV | HC, 0}, {DL | HV | HC | CA, 0}});
    EXPECT_TRUE(chooses(p, kAll, true, 2u, true));
    EXPECT_TRUE(chooses(p, kAll, false, 0u, false));  // device-local without host visibility exists: the staging path uses it
    // Cached but not coherent: never mapped (vkpath does not flush or invalidate ranges).
    const auto nc = layout({{4 * GiB, true}}, {{DL | HV | CA, 0}});
    EXPECT_TRUE(chooses(nc, kAll, true, 0u, false));
}

TEST(MemoryChoice, LargestHeapAmongEqualTypesThenLowestIndex) {
    const auto p = layout({{1 * GiB, true}, {8 * GiB, true}}, {{DL, 0}, {DL, 1}, {DL, 1}});
    EXPECT_TRUE(chooses(p, kAll, true, 1u, false));
}

TEST(MemoryChoice, WithoutDeviceLocalMemoryAnyAdmittedType) {
    const auto p = layout({{4 * GiB, false}}, {{HV | HC, 0}, {HV | HC | CA, 0}});
    EXPECT_TRUE(chooses(p, 1u << 1, true, 1u, true));
    EXPECT_TRUE(chooses(p, 1u << 0, true, 0u, false));  // uncached: staging copies
    EXPECT_FALSE(chooseBufferMemory(p, 0u, true));       // nothing admitted
    EXPECT_FALSE(chooseBufferMemory(p, 1u << 5, true));  // bits beyond the type count
}

}  // namespace
}  // namespace vkp
