// The driver's VkPipelineCache data as vkpath keeps it on disk (core/disk_cache.h, kind
// "pipelines"): which device an entry is for, and whether data read back fits this device before
// it is handed to vkCreatePipelineCache (Vulkan 1.3 spec, "Pipeline Cache": the header of version
// VK_PIPELINE_CACHE_HEADER_VERSION_ONE).
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

namespace vkp {

/// The identity of a device's pipeline-cache data: what the header names plus the driver version.
struct PipelineCacheIdentity {
    std::uint32_t vendorId = 0, deviceId = 0, driverVersion = 0;
    std::uint8_t uuid[16] = {};  ///< VkPhysicalDeviceProperties::pipelineCacheUUID
};

/// The disk cache's key of a device's entry (FNV-1a of the identity): one entry per device and driver.
std::uint64_t pipelineCacheKey(const PipelineCacheIdentity& id);

/// Whether `data` starts with a version-one header of at least 32 bytes, no longer than the data,
/// that names this vendor, device and pipelineCacheUUID. Data that fails is not passed to the driver.
bool pipelineCacheDataFits(std::span<const std::byte> data, const PipelineCacheIdentity& id);

/// Whether `data` holds more than its header: a driver that keeps nothing in its pipeline cache
/// (lavapipe in Mesa 22.3 returns a bare header) has nothing worth a file.
bool pipelineCacheDataHasPipelines(std::span<const std::byte> data);

}  // namespace vkp
