#include "vk/buffer.h"

#include <cstring>
#include <optional>
#include <string>

#include "core/errors.h"
#include "vk/memory_choice.h"

namespace vkp {

namespace {
constexpr auto kTransfer = vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst;

constexpr vk::AccessFlags kWrites = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite;
constexpr vk::AccessFlags kReads = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eTransferRead;
constexpr vk::PipelineStageFlags kDeviceStages = vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer;

/// A global memory barrier: what src stages wrote with srcAccess is made visible to dst stages' dstAccess.
void barrier(vk::raii::CommandBuffer& cmd, vk::AccessFlags srcAccess, vk::AccessFlags dstAccess, vk::PipelineStageFlags src,
             vk::PipelineStageFlags dst) {
    vk::MemoryBarrier mb{};
    mb.srcAccessMask = srcAccess;
    mb.dstAccessMask = dstAccess;
    cmd.pipelineBarrier(src, dst, {}, mb, nullptr, nullptr);
}
}  // namespace

struct GpuBuffer::Staging {
    vk::raii::Buffer buffer{nullptr};
    vk::raii::DeviceMemory memory{nullptr};
    void* mapped = nullptr;
};

GpuBuffer::Staging& GpuBuffer::stagingFor(std::size_t bytes, std::unique_ptr<Staging>& temp) {
    dev_->countStagingCopy();
    const bool keep = size_ <= kKeptStagingBytes;
    if (keep && kept_) return *kept_;
    const vk::DeviceSize size = keep ? size_ : vk::DeviceSize(bytes);
    auto s = std::make_unique<Staging>();
    vk::BufferCreateInfo bci{};
    bci.size = size;
    bci.usage = kTransfer;
    s->buffer = vk::raii::Buffer(dev_->device(), bci);
    const auto req = s->buffer.getMemoryRequirements();
    vk::MemoryAllocateInfo mai{};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = dev_->memoryType(req.memoryTypeBits,
                                           vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent,
                                           vk::MemoryPropertyFlagBits::eHostCached);
    s->memory = vk::raii::DeviceMemory(dev_->device(), mai);
    s->buffer.bindMemory(*s->memory, 0);
    s->mapped = s->memory.mapMemory(0, size);
    (keep ? kept_ : temp) = std::move(s);
    return keep ? *kept_ : *temp;
}

GpuBuffer::GpuBuffer(VulkanDevice& dev, vk::DeviceSize size, vk::BufferUsageFlags usage)
    : dev_(&dev), size_(size < 16 ? 16 : (size + 15) / 16 * 16) {
    vk::BufferCreateInfo bci{};
    bci.size = size_;
    bci.usage = usage | kTransfer;
    buffer_ = vk::raii::Buffer(dev.device(), bci);
    const auto req = buffer_.getMemoryRequirements();
    const std::optional<BufferMemoryChoice> choice = chooseBufferMemory(dev.memoryProperties(), req.memoryTypeBits, dev.mapsBuffers());
    if (!choice) throw VulkanError("no Vulkan memory type can hold a buffer of " + std::to_string(size_) + " bytes");
    vk::MemoryAllocateInfo mai{};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = choice->type;
    vk::MemoryAllocateFlagsInfo flags{};
    flags.flags = vk::MemoryAllocateFlagBits::eDeviceAddress;
    if (usage & vk::BufferUsageFlagBits::eShaderDeviceAddress) mai.pNext = &flags;
    memory_ = vk::raii::DeviceMemory(dev.device(), mai);
    buffer_.bindMemory(*memory_, 0);
    if (choice->mapped) mapped_ = memory_.mapMemory(0, size_);
}

GpuBuffer::~GpuBuffer() = default;

void GpuBuffer::upload(const void* data, std::size_t bytes) {
    if (bytes == 0) return;
    if (mapped_) {
        std::memcpy(mapped_, data, bytes);
        return;
    }
    std::unique_ptr<Staging> temp;
    Staging& s = stagingFor(bytes, temp);
    std::memcpy(s.mapped, data, bytes);
    dev_->submitAndWait([&](vk::raii::CommandBuffer& cmd) {
        // Earlier work on the buffer (a dispatch, a fill) is done before the copy overwrites it ...
        barrier(cmd, kWrites, vk::AccessFlagBits::eTransferWrite, kDeviceStages, vk::PipelineStageFlagBits::eTransfer);
        cmd.copyBuffer(*s.buffer, *buffer_, vk::BufferCopy{0, 0, bytes});
        // ... and the copy's data is visible to every later command (later submissions included).
        barrier(cmd, vk::AccessFlagBits::eTransferWrite, kWrites | kReads, vk::PipelineStageFlagBits::eTransfer, kDeviceStages);
    });
}

void GpuBuffer::download(void* dst, std::size_t bytes) {
    if (bytes == 0) return;
    if (mapped_) {
        std::memcpy(dst, mapped_, bytes);
        return;
    }
    std::unique_ptr<Staging> temp;
    Staging& s = stagingFor(bytes, temp);
    dev_->submitAndWait([&](vk::raii::CommandBuffer& cmd) {
        barrier(cmd, kWrites, vk::AccessFlagBits::eTransferRead, kDeviceStages, vk::PipelineStageFlagBits::eTransfer);
        cmd.copyBuffer(*buffer_, *s.buffer, vk::BufferCopy{0, 0, bytes});
        // The copy's writes made visible to the host's reads below (after the fence).
        barrier(cmd, vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eHostRead, vk::PipelineStageFlagBits::eTransfer,
                vk::PipelineStageFlagBits::eHost);
    });
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
