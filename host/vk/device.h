// The logical device: one compute queue, a command pool and a fence for submit-and-wait.
#pragma once
#include <functional>
#include <memory>
#include <string>

#include "vk/instance.h"

namespace vkp {

struct CompiledPipelines;  // vk/compute_pipeline.h
class DiskCache;           // core/disk_cache.h

class VulkanDevice {
public:
    /// Picks a device with selectDevice(instance.devices(), selector) and creates it.
    /// Throws DeviceError (with the reason every candidate was refused) if none is usable.
    VulkanDevice(VulkanInstance& instance, const std::string& selector);

    vk::raii::Device& device() { return device_; }
    vk::raii::PhysicalDevice& physical() { return *physical_; }
    const DeviceInfo& info() const { return info_; }
    VulkanInstance& instance() { return *instance_; }

    /// Records commands with `record` into a fresh primary command buffer, submits it and waits.
    void submitAndWait(const std::function<void(vk::raii::CommandBuffer&)>& record);

    /// Index of a memory type with all of `required` properties among `typeBits`, preferring
    /// one that also has `preferred`. Throws VulkanError if none.
    std::uint32_t memoryType(std::uint32_t typeBits, vk::MemoryPropertyFlags required,
                             vk::MemoryPropertyFlags preferred = {}) const;

    /// The device's memory types and heaps (vk/memory_choice.h picks a buffer's type from them).
    const vk::PhysicalDeviceMemoryProperties& memoryProperties() const { return memProps_; }
    /// Whether buffers in host-visible, coherent, cached device-local memory are mapped (the
    /// default) or, with VKPATH_NO_BUFFER_MAPPING=1 in the environment, reached through staging
    /// copies as on a discrete GPU: the tests run that path on lavapipe (docs/design.md "Buffer memory").
    bool mapsBuffers() const { return mapsBuffers_; }
    /// Uploads and read-backs that went through a staging buffer so far (GpuBuffer): 0 where every
    /// buffer is mapped (lavapipe), one per transfer on a discrete GPU (`--stats-json`'s staging_copies).
    std::uint64_t stagingCopies() const { return stagingCopies_; }
    void countStagingCopy() { ++stagingCopies_; }

    /// The compute pipelines compiled on this device, by what they were built from
    /// (vk/compute_pipeline.h): a ComputePipeline of the same SPIR-V, specialization constants,
    /// bindings and push-constant size as an earlier one reuses its VkPipeline.
    CompiledPipelines& compiledPipelines() { return *compiled_; }

    /// Keeps compiled kernels in `cache` across processes (docs/design.md "The kernel cache"):
    /// ComputePipeline looks up and stores its specialized SPIR-V there, and the device's
    /// VkPipelineCache starts from the data stored for this device and driver (when it fits them:
    /// vk/pipeline_cache_data.h). Call before creating pipelines. Never throws for the cache's
    /// sake: data that does not fit or that the driver refuses leaves an empty pipeline cache.
    void useKernelCache(std::shared_ptr<DiskCache> cache);
    /// The cache of useKernelCache, or nullptr.
    DiskCache* kernelCache() { return kernelCache_.get(); }
    /// The VkPipelineCache every pipeline of this device is created with (a null handle without a
    /// kernel cache).
    const vk::raii::PipelineCache& pipelineCache() const { return pipelineCache_; }
    /// Stores the VkPipelineCache's data in the kernel cache if the driver keeps anything in it
    /// and it changed since it was loaded or last stored. Call after compiling pipelines.
    void savePipelineCache();
    /// Bytes of stored VkPipelineCache data the driver accepted at useKernelCache (0: none).
    std::uint64_t pipelineCacheBytesLoaded() const { return pipelineCacheBytesLoaded_; }

private:
    VulkanInstance* instance_;
    vk::raii::PhysicalDevice* physical_;
    DeviceInfo info_;
    vk::raii::Device device_{nullptr};
    vk::raii::Queue queue_{nullptr};
    vk::raii::CommandPool pool_{nullptr};
    vk::raii::CommandBuffer cmd_{nullptr};
    vk::raii::Fence fence_{nullptr};
    vk::PhysicalDeviceMemoryProperties memProps_{};
    bool mapsBuffers_ = true;
    std::uint64_t stagingCopies_ = 0;
    std::shared_ptr<CompiledPipelines> compiled_;  // declared after device_: destroyed before it
    std::shared_ptr<DiskCache> kernelCache_;
    vk::raii::PipelineCache pipelineCache_{nullptr};  // after device_: destroyed before it
    std::uint64_t pipelineCacheKey_ = 0;  ///< the kernel cache's key of this device's entry (pipelineCacheKey)
    std::uint64_t pipelineCacheBytesLoaded_ = 0;
    std::uint64_t pipelineCacheHash_ = 0;  ///< FNV-1a of the data last loaded or stored (0: none)
};

}  // namespace vkp
