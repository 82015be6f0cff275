#include "vk/buffer.h"

#include <cstring>

namespace vkp {

namespace {
constexpr auto kTransfer = vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst;

struct Staging {
    vk::raii::Buffer buffer{nullptr};
    vk::raii::DeviceMemory memory{nullptr};
    void* mapped = nullptr;
};

Staging makeStaging(VulkanDevice& dev, vk::DeviceSize size) {
    Staging s;
    vk::BufferCreateInfo bci{};
    bci.size = size;
    bci.usage = kTransfer;
    s.buffer = vk::raii::Buffer(dev.device(), bci);
    const auto req = s.buffer.getMemoryRequirements();
    vk::MemoryAllocateInfo mai{};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = dev.memoryType(req.memoryTypeBits,
                                         vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent,
                                         vk::MemoryPropertyFlagBits::eHostCached);
    s.memory = vk::raii::DeviceMemory(dev.device(), mai);
    s.buffer.bindMemory(*s.memory, 0);
    s.mapped = s.memory.mapMemory(0, size);
    return s;
}
}  // namespace

GpuBuffer::GpuBuffer(VulkanDevice& dev, vk::DeviceSize size, vk::BufferUsageFlags usage)
    : dev_(&dev), size_(size < 16 ? 16 : (size + 15) / 16 * 16) {
    vk::BufferCreateInfo bci{};
    bci.size = size_;
    bci.usage = usage | kTransfer;
    buffer_ = vk::raii::Buffer(dev.device(), bci);
    const auto req = buffer_.getMemoryRequirements();
    // Device-local, and host-visible+coherent as well where such memory exists.
    const auto devLocal = vk::MemoryPropertyFlagBits::eDeviceLocal;
    const auto hostVis = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
    std::uint32_t type = dev.memoryType(req.memoryTypeBits, devLocal, hostVis);
    vk::MemoryAllocateInfo mai{};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type;
    vk::MemoryAllocateFlagsInfo flags{};
    flags.flags = vk::MemoryAllocateFlagBits::eDeviceAddress;
    if (usage & vk::BufferUsageFlagBits::eShaderDeviceAddress) mai.pNext = &flags;
    memory_ = vk::raii::DeviceMemory(dev.device(), mai);
    buffer_.bindMemory(*memory_, 0);
    const auto props = dev.physical().getMemoryProperties().memoryTypes[type].propertyFlags;
    if ((props & hostVis) == hostVis) mapped_ = memory_.mapMemory(0, size_);
}

void GpuBuffer::upload(const void* data, std::size_t bytes) {
    if (bytes == 0) return;
    if (mapped_) {
        std::memcpy(mapped_, data, bytes);
        return;
    }
    Staging s = makeStaging(*dev_, bytes);
    std::memcpy(s.mapped, data, bytes);
    dev_->submitAndWait([&](vk::raii::CommandBuffer& cmd) { cmd.copyBuffer(*s.buffer, *buffer_, vk::BufferCopy{0, 0, bytes}); });
}

void GpuBuffer::download(void* dst, std::size_t bytes) {
    if (bytes == 0) return;
    if (mapped_) {
        std::memcpy(dst, mapped_, bytes);
        return;
    }
    Staging s = makeStaging(*dev_, bytes);
    dev_->submitAndWait([&](vk::raii::CommandBuffer& cmd) { cmd.copyBuffer(*buffer_, *s.buffer, vk::BufferCopy{0, 0, bytes}); });
    std::memcpy(dst, s.mapped, bytes);
}

vk::DeviceAddress GpuBuffer::deviceAddress() const {
    vk::BufferDeviceAddressInfo info{};
    info.buffer = *buffer_;
    return dev_->device().getBufferAddress(info);
}

vk::raii::BufferView GpuBuffer::texelView(vk::Format format) const {
    vk::BufferViewCreateInfo ci{};
    ci.buffer = *buffer_;
    ci.format = format;
    ci.offset = 0;
    ci.range = VK_WHOLE_SIZE;
    return vk::raii::BufferView(dev_->device(), ci);
}

}  // namespace vkp
