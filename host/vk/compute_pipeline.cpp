#include "vk/compute_pipeline.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <map>
#include <stdexcept>
#include <string>

#include "core/disk_cache.h"
#include "vk/spirv_specialize.h"

namespace vkp {

namespace {

/// specializeSpirv's result, through the device's kernel cache where it has one (a hit skips
/// SPIRV-Tools: about 0.1 s for the path tracer on this project's machine).
std::vector<std::uint32_t> specializedSpirv(VulkanDevice& dev, const ComputePipelineDesc& desc) {
    DiskCache* cache = dev.kernelCache();
    const std::uint64_t key = cache ? specializationKey(desc.spirv, desc.specConstants) : 0;
    if (cache) {
        if (std::optional<std::string> blob = cache->load("spirv", key);
            blob && blob->size() % 4 == 0 && blob->size() >= 20 && blob->size() <= desc.spirv.size_bytes()) {
            std::vector<std::uint32_t> words(blob->size() / 4);
            std::memcpy(words.data(), blob->data(), blob->size());
            if (words[0] == desc.spirv[0]) return words;  // the SPIR-V magic number, in the host's order
        }
    }
    std::vector<std::uint32_t> words = specializeSpirv(desc.spirv, desc.specConstants).words;
    if (cache) cache->store("spirv", key, std::string_view(reinterpret_cast<const char*>(words.data()), words.size() * 4));
    return words;
}

std::shared_ptr<const SharedPipeline> compile(VulkanDevice& dev, const ComputePipelineDesc& desc) {
    auto& device = dev.device();
    auto out = std::make_shared<SharedPipeline>();
    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    for (std::uint32_t i = 0; i < desc.bindings.size(); ++i) {
        vk::DescriptorSetLayoutBinding b{};
        b.binding = i;
        b.descriptorType = desc.bindings[i];
        b.descriptorCount = 1;
        b.stageFlags = vk::ShaderStageFlagBits::eCompute;
        bindings.push_back(b);
    }
    vk::DescriptorSetLayoutCreateInfo lci{};
    lci.bindingCount = std::uint32_t(bindings.size());
    lci.pBindings = bindings.data();
    out->setLayout = vk::raii::DescriptorSetLayout(device, lci);

    vk::PushConstantRange pcr{};
    pcr.stageFlags = vk::ShaderStageFlagBits::eCompute;
    pcr.size = desc.pushConstantBytes;
    vk::PipelineLayoutCreateInfo plci{};
    vk::DescriptorSetLayout rawSet = *out->setLayout;
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &rawSet;
    plci.pushConstantRangeCount = desc.pushConstantBytes ? 1 : 0;
    plci.pPushConstantRanges = &pcr;
    out->layout = vk::raii::PipelineLayout(device, plci);

    std::vector<std::uint32_t> specialized;
    std::span<const std::uint32_t> code = desc.spirv;
    if (desc.specializeOnHost && !desc.specConstants.empty()) {
        try {
            specialized = specializedSpirv(dev, desc);
        } catch (const std::runtime_error& e) {
            throw std::runtime_error(std::string(e.what()) + " (`--specialize driver` leaves specialization to the driver)");
        }
        code = specialized;
    }
    vk::ShaderModuleCreateInfo smci{};
    smci.codeSize = code.size() * sizeof(std::uint32_t);
    smci.pCode = code.data();
    out->module = vk::raii::ShaderModule(device, smci);

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
    cpci.stage.module = *out->module;
    cpci.stage.pName = "main";
    cpci.stage.pSpecializationInfo = entries.empty() ? nullptr : &si;
    cpci.layout = *out->layout;
    out->pipeline = vk::raii::Pipeline(device, dev.pipelineCache(), cpci);
    dev.savePipelineCache();
    return out;
}

}  // namespace

ComputePipeline::ComputePipeline(VulkanDevice& dev, const ComputePipelineDesc& desc) : dev_(&dev), types_(desc.bindings) {
    auto& device = dev.device();
    std::map<vk::DescriptorType, std::uint32_t> counts;
    for (vk::DescriptorType t : types_) counts[t]++;
    {
        CompiledPipelines& cache = dev.compiledPipelines();
        CompiledPipelines::Key key{std::vector<std::uint32_t>(desc.spirv.begin(), desc.spirv.end()), desc.specConstants, desc.bindings,
                                   desc.pushConstantBytes, desc.specializeOnHost};
        const std::lock_guard<std::mutex> lock(cache.mutex);
        auto it = cache.pipelines.find(key);
        if (it == cache.pipelines.end()) {
            if (cache.pipelines.size() >= CompiledPipelines::kKeep)
                cache.pipelines.erase(std::min_element(cache.pipelines.begin(), cache.pipelines.end(), [](const auto& a, const auto& b) {
                    return a.second.lastUse < b.second.lastUse;
                }));
            it = cache.pipelines.emplace(std::move(key), CompiledPipelines::Entry{compile(dev, desc), 0}).first;
            ++cache.compiled;
        }
        it->second.lastUse = ++cache.uses;
        shared_ = it->second.pipeline;
    }
    const vk::DescriptorSetLayout rawSet = *shared_->setLayout;

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
    cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *shared_->pipeline);
    cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *shared_->layout, 0, {*sets_.at(set)}, {});
    if (pushBytes)
        cmd.pushConstants<std::uint8_t>(*shared_->layout, vk::ShaderStageFlagBits::eCompute, 0,
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
