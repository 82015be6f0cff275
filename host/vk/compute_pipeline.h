// A compute pipeline with one descriptor-set layout (one or more sets of it), push constants and
// specialization constants.
// Used by the path tracer and by the test kernels (shaders/tests/).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "vk/device.h"

namespace vkp {

struct ComputePipelineDesc {
    std::span<const std::uint32_t> spirv;           ///< SPIR-V words (embedded at build time)
    std::vector<vk::DescriptorType> bindings;       ///< binding i has type bindings[i]
    std::uint32_t pushConstantBytes = 0;
    std::vector<std::uint32_t> specConstants;       ///< constant_id i = specConstants[i] (bool: 0/1)
    std::uint32_t descriptorSets = 1;               ///< sets of the layout to allocate (one per band of the path tracer)
};

class ComputePipeline {
public:
    ComputePipeline(VulkanDevice& dev, const ComputePipelineDesc& desc);

    /// Point binding `b` of descriptor set `set` at a whole buffer (uniform or storage buffer bindings).
    void bindBuffer(std::uint32_t b, vk::Buffer buffer, std::uint32_t set = 0);
    /// Point binding `b` of descriptor set `set` at a texel-buffer view.
    void bindTexelView(std::uint32_t b, vk::BufferView view, std::uint32_t set = 0);

    /// Record: bind (descriptor set `set`), push constants, dispatch groupsX x groupsY x 1
    /// workgroups, and a barrier that makes the shader's writes visible to later dispatches,
    /// transfers and the host.
    void recordDispatch(vk::raii::CommandBuffer& cmd, std::uint32_t groupsX, std::uint32_t groupsY, const void* push,
                        std::uint32_t pushBytes, std::uint32_t set = 0) const;
    /// recordDispatch for a kernel of 8x8 workgroups covering an x by y grid of invocations.
    void recordDispatch8x8(vk::raii::CommandBuffer& cmd, std::uint32_t x, std::uint32_t y, const void* push,
                           std::uint32_t pushBytes) const {
        recordDispatch(cmd, (x + 7) / 8, (y + 7) / 8, push, pushBytes);
    }

private:
    VulkanDevice* dev_;
    std::vector<vk::DescriptorType> types_;
    vk::raii::DescriptorSetLayout setLayout_{nullptr};
    vk::raii::PipelineLayout layout_{nullptr};
    vk::raii::ShaderModule module_{nullptr};
    vk::raii::Pipeline pipeline_{nullptr};
    vk::raii::DescriptorPool pool_{nullptr};
    std::vector<vk::raii::DescriptorSet> sets_;
};

}  // namespace vkp
