#include "vk/pipeline_cache_data.h"

#include <cstring>

#include "core/fnv1a.h"

namespace vkp {

namespace {
std::uint32_t word(std::span<const std::byte> data, std::size_t offset) {
    std::uint32_t v = 0;
    std::memcpy(&v, data.data() + offset, 4);  // the header is in the host's byte order (Vulkan spec)
    return v;
}
constexpr std::size_t kHeaderOneBytes = 16 + 16;  // headerSize, headerVersion, vendorID, deviceID, UUID
}  // namespace

std::uint64_t pipelineCacheKey(const PipelineCacheIdentity& id) {
    Fnv1a h;
    h.add(std::string_view("VkPipelineCache"));
    h.add(std::uint64_t(id.vendorId));
    h.add(std::uint64_t(id.deviceId));
    h.add(std::uint64_t(id.driverVersion));
    h.add(std::as_bytes(std::span<const std::uint8_t>(id.uuid, 16)));
    return h.h;
}

bool pipelineCacheDataFits(std::span<const std::byte> data, const PipelineCacheIdentity& id) {
    if (data.size() < kHeaderOneBytes) return false;
    const std::uint32_t headerSize = word(data, 0);
    if (headerSize < kHeaderOneBytes || headerSize > data.size()) return false;
    if (word(data, 4) != 1u) return false;  // VK_PIPELINE_CACHE_HEADER_VERSION_ONE
    if (word(data, 8) != id.vendorId || word(data, 12) != id.deviceId) return false;
    return std::memcmp(data.data() + 16, id.uuid, 16) == 0;
}

bool pipelineCacheDataHasPipelines(std::span<const std::byte> data) {
    if (data.size() < kHeaderOneBytes) return false;
    return data.size() > word(data, 0);
}

}  // namespace vkp
