#include "vk/compute_pipeline.h"

#include <algorithm>
#include <map>

namespace vkp {

ComputePipeline::ComputePipeline(VulkanDevice& dev, const ComputePipelineDesc& desc) : dev_(&dev), types_(desc.bindings) {
    auto& device = dev.device();
    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    std::map<vk::DescriptorType, std::uint32_t> counts;
    for (std::uint32_t i = 0; i < types_.size(); ++i) {
        vk::DescriptorSetLayoutBinding b{};
        b.binding = i;
        b.descriptorType = types_[i];
        b.descriptorCount = 1;
        b.stageFlags = vk::ShaderStageFlagBits::eCompute;
        bindings.push_back(b);
        counts[types_[i]]++;
    }
    vk::DescriptorSetLayoutCreateInfo lci{};
    lci.bindingCount = std::uint32_t(bindings.size());
    lci.pBindings = bindings.data();
    setLayout_ = vk::raii::DescriptorSetLayout(device, lci);

    vk::PushConstantRange pcr{};
    pcr.stageFlags = vk::ShaderStageFlagBits::eCompute;
    pcr.size = desc.pushConstantBytes;
    vk::PipelineLayoutCreateInfo plci{};
    vk::DescriptorSetLayout rawSet = *setLayout_;
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &rawSet;
    plci.pushConstantRangeCount = desc.pushConstantBytes ? 1 : 0;
    plci.pPushConstantRanges = &pcr;
    layout_ = vk::raii::PipelineLayout(device, plci);

    vk::ShaderModuleCreateInfo smci{};
    smci.codeSize = desc.spirv.size() * sizeof(std::uint32_t);
    smci.pCode = desc.spirv.data();
    module_ = vk::raii::ShaderModule(device, smci);

    std::vector<vk::SpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < desc.specConstants.size(); ++i)
        entries.push_back(vk::SpecializationMapEntry{i, i * 4u, 4u});
    vk::SpecializationInfo si{};
    si.mapEntryCount = std::uint32_t(entries.size());
    si.pMapEntries = entries.data();
    si.dataSize = desc.specConstants.size() * 4u;
    si.pData = desc.specConstants.data();

    vk::ComputePipelineCreateInfo cpci{};
    cpci.stage.stage = vk::ShaderStageFlagBits::eCompute;
    cpci.stage.module = *module_;
    cpci.stage.pName = "main";
    cpci.stage.pSpecializationInfo = entries.empty() ? nullptr : &si;
    cpci.layout = *layout_;
    pipeline_ = vk::raii::Pipeline(device, nullptr, cpci);

    std::vector<vk::DescriptorPoolSize> sizes;
    const std::uint32_t sets = std::max<std::uint32_t>(desc.descriptorSets, 1);
    for (auto [t, n] : counts) sizes.push_back(vk::DescriptorPoolSize{t, n * sets});
    vk::DescriptorPoolCreateInfo dpci{};
    dpci.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet;
    dpci.maxSets = sets;
    dpci.poolSizeCount = std::uint32_t(sizes.size());
    dpci.pPoolSizes = sizes.data();
    pool_ = vk::raii::DescriptorPool(device, dpci);
    const std::vector<vk::DescriptorSetLayout> layouts(sets, rawSet);
    vk::DescriptorSetAllocateInfo dsai{};
    dsai.descriptorPool = *pool_;
    dsai.descriptorSetCount = sets;
    dsai.pSetLayouts = layouts.data();
    for (auto& set : vk::raii::DescriptorSets(device, dsai)) sets_.push_back(std::move(set));
}

void ComputePipeline::bindBuffer(std::uint32_t b, vk::Buffer buffer, std::uint32_t set) {
    vk::DescriptorBufferInfo info{buffer, 0, VK_WHOLE_SIZE};
    vk::WriteDescriptorSet w{};
    w.dstSet = *sets_.at(set);
    w.dstBinding = b;
    w.descriptorCount = 1;
    w.descriptorType = types_.at(b);
    w.pBufferInfo = &info;
    dev_->device().updateDescriptorSets(w, nullptr);
}

void ComputePipeline::bindTexelView(std::uint32_t b, vk::BufferView view, std::uint32_t set) {
    vk::WriteDescriptorSet w{};
    w.dstSet = *sets_.at(set);
    w.dstBinding = b;
    w.descriptorCount = 1;
    w.descriptorType = types_.at(b);
    w.pTexelBufferView = &view;
    dev_->device().updateDescriptorSets(w, nullptr);
}

void ComputePipeline::recordDispatch(vk::raii::CommandBuffer& cmd, std::uint32_t groupsX, std::uint32_t groupsY, const void* push,
                                     std::uint32_t pushBytes, std::uint32_t set) const {
    cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_);
    cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout_, 0, {*sets_.at(set)}, {});
    if (pushBytes)
        cmd.pushConstants<std::uint8_t>(*layout_, vk::ShaderStageFlagBits::eCompute, 0,
                                        vk::ArrayProxy<const std::uint8_t>(pushBytes, static_cast<const std::uint8_t*>(push)));
    cmd.dispatch(groupsX, groupsY, 1);
    vk::MemoryBarrier mb{};
    mb.srcAccessMask = vk::AccessFlagBits::eShaderWrite;
    mb.dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite |
                       vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eHostRead;
    cmd.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                        vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer |
                            vk::PipelineStageFlagBits::eHost,
                        {}, mb, nullptr, nullptr);
}

}  // namespace vkp
