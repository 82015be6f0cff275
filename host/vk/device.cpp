#include "vk/device.h"

#include <cstdlib>
#include <cstring>

#include "core/disk_cache.h"
#include "core/errors.h"
#include "core/fnv1a.h"
#include "vk/compute_pipeline.h"
#include "vk/pipeline_cache_data.h"

namespace vkp {

VulkanDevice::VulkanDevice(VulkanInstance& instance, const std::string& selector) : instance_(&instance) {
    const DeviceChoice choice = selectDevice(instance.devices(), selector);
    if (!choice.index) throw DeviceError(choice.error);
    physical_ = &instance.physicalDevice(*choice.index);
    info_ = instance.devices()[*choice.index];
    memProps_ = physical_->getMemoryProperties();
    if (const char* noMap = std::getenv("VKPATH_NO_BUFFER_MAPPING")) mapsBuffers_ = std::string(noMap).empty() || std::string(noMap) == "0";

    const float priority = 1.0f;
    vk::DeviceQueueCreateInfo qci{};
    qci.queueFamilyIndex = *info_.computeQueueFamily;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    vk::DeviceCreateInfo dci{};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    // Buffer device addresses where the device has them (used by the BVH layout micro-benchmark).
    vk::PhysicalDeviceVulkan12Features v12{};
    v12.bufferDeviceAddress = VK_TRUE;
    if (info_.bufferDeviceAddress) dci.pNext = &v12;
    device_ = vk::raii::Device(*physical_, dci);
    queue_ = device_.getQueue(*info_.computeQueueFamily, 0);

    vk::CommandPoolCreateInfo pci{};
    pci.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer;
    pci.queueFamilyIndex = *info_.computeQueueFamily;
    pool_ = vk::raii::CommandPool(device_, pci);
    vk::CommandBufferAllocateInfo ai{};
    ai.commandPool = *pool_;
    ai.level = vk::CommandBufferLevel::ePrimary;
    ai.commandBufferCount = 1;
    cmd_ = std::move(vk::raii::CommandBuffers(device_, ai).front());
    fence_ = vk::raii::Fence(device_, vk::FenceCreateInfo{});
    compiled_ = std::make_shared<CompiledPipelines>();
}

namespace {
PipelineCacheIdentity identityOf(const vk::PhysicalDeviceProperties& p) {
    PipelineCacheIdentity id;
    id.vendorId = p.vendorID;
    id.deviceId = p.deviceID;
    id.driverVersion = p.driverVersion;
    std::memcpy(id.uuid, p.pipelineCacheUUID.data(), 16);
    return id;
}
}  // namespace

void VulkanDevice::useKernelCache(std::shared_ptr<DiskCache> cache) {
    kernelCache_ = std::move(cache);
    pipelineCache_ = vk::raii::PipelineCache(nullptr);
    pipelineCacheHash_ = 0;
    pipelineCacheBytesLoaded_ = 0;
    if (!kernelCache_) return;
    const PipelineCacheIdentity id = identityOf(physical_->getProperties());
    pipelineCacheKey_ = pipelineCacheKey(id);
    std::optional<std::string> data = kernelCache_->load("pipelines", pipelineCacheKey_);
    if (data) {
        const auto bytes = std::as_bytes(std::span<const char>(data->data(), data->size()));
        if (pipelineCacheDataFits(bytes, id)) {
            vk::PipelineCacheCreateInfo ci{};
            ci.initialDataSize = data->size();
            ci.pInitialData = data->data();
            try {
                pipelineCache_ = vk::raii::PipelineCache(device_, ci);
                pipelineCacheHash_ = fnv1a(bytes);
                pipelineCacheBytesLoaded_ = data->size();
                return;
            } catch (const vk::SystemError&) {
                // the driver refused the data: start empty
            }
        }
    }
    pipelineCache_ = vk::raii::PipelineCache(device_, vk::PipelineCacheCreateInfo{});
}

void VulkanDevice::savePipelineCache() {
    if (!kernelCache_ || !*pipelineCache_) return;
    const std::vector<std::uint8_t> data = pipelineCache_.getData();
    const auto bytes = std::as_bytes(std::span<const std::uint8_t>(data));
    if (!pipelineCacheDataHasPipelines(bytes)) return;
    const std::uint64_t h = fnv1a(bytes);
    if (h == pipelineCacheHash_) return;
    if (kernelCache_->store("pipelines", pipelineCacheKey_, std::string_view(reinterpret_cast<const char*>(data.data()), data.size())))
        pipelineCacheHash_ = h;
}

void VulkanDevice::submitAndWait(const std::function<void(vk::raii::CommandBuffer&)>& record) {
    cmd_.reset();
    vk::CommandBufferBeginInfo bi{};
    bi.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit;
    cmd_.begin(bi);
    record(cmd_);
    cmd_.end();
    vk::SubmitInfo si{};
    vk::CommandBuffer raw = *cmd_;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &raw;
    queue_.submit(si, *fence_);
    // Wait in slices so a device that never finishes is reported rather than hanging forever.
    for (int i = 0; i < 600; ++i) {
        if (device_.waitForFences(*fence_, VK_TRUE, 1'000'000'000ull) == vk::Result::eSuccess) {
            device_.resetFences(*fence_);
            return;
        }
    }
    throw VulkanError("a dispatch did not finish within 600 s (device hung?)");
}

std::uint32_t VulkanDevice::memoryType(std::uint32_t typeBits, vk::MemoryPropertyFlags required,
                                       vk::MemoryPropertyFlags preferred) const {
    std::int64_t fallback = -1;
    for (std::uint32_t i = 0; i < memProps_.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        const auto flags = memProps_.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (fallback < 0) fallback = i;
    }
    if (fallback < 0) throw VulkanError("no Vulkan memory type with the required properties");
    return std::uint32_t(fallback);
}

}  // namespace vkp
