// A Vulkan buffer with its own memory (both RAII). Device-local where the device has it; data moves
// through a mapping when that memory is also host-visible, coherent and cached (lavapipe, integrated
// GPUs), otherwise through a temporary staging buffer (discrete GPUs; VKPATH_NO_BUFFER_MAPPING=1 on
// any device): vk/memory_choice.h, docs/design.md "Buffer memory".
#pragma once
#include <cstddef>
#include <memory>

#include "vk/device.h"

namespace vkp {

class GpuBuffer {
public:
    /// size in bytes (0 is rounded up to 16 so that every binding is valid). A usage with
    /// eShaderDeviceAddress needs a device with VulkanDevice::info().bufferDeviceAddress.
    GpuBuffer(VulkanDevice& dev, vk::DeviceSize size, vk::BufferUsageFlags usage);
    ~GpuBuffer();
    GpuBuffer(const GpuBuffer&) = delete;
    GpuBuffer& operator=(const GpuBuffer&) = delete;

    vk::Buffer buffer() const { return *buffer_; }
    vk::DeviceSize size() const { return size_; }

    /// Copy `bytes` bytes from host memory into the buffer at offset 0.
    void upload(const void* data, std::size_t bytes);
    /// Copy `bytes` bytes from the buffer (offset 0) to host memory.
    void download(void* dst, std::size_t bytes);

    /// The buffer's device address (usage eShaderDeviceAddress only).
    vk::DeviceAddress deviceAddress() const;

    /// A view of the buffer as a uniform texel buffer, by default R32G32B32A32_UINT (usamplerBuffer).
    vk::raii::BufferView texelView(vk::Format format = vk::Format::eR32G32B32A32Uint) const;

    /// Buffers of at most this many bytes keep their staging buffer from the first transfer on (the
    /// renderer reads its counters back after every batch); larger ones make one per transfer.
    static constexpr vk::DeviceSize kKeptStagingBytes = 64 * 1024;

private:
    struct Staging;
    /// The staging buffer for a transfer of `bytes`: the kept one (kKeptStagingBytes), else a new one
    /// held in `temp` for this transfer. Counts the transfer (VulkanDevice::stagingCopies).
    Staging& stagingFor(std::size_t bytes, std::unique_ptr<Staging>& temp);

    VulkanDevice* dev_;
    vk::DeviceSize size_;
    vk::raii::Buffer buffer_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
    void* mapped_ = nullptr;
    std::unique_ptr<Staging> kept_;
};

}  // namespace vkp
