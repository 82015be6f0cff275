// A compute pipeline with one descriptor-set layout (one or more sets of it), push constants and
// specialization constants.
// Used by the path tracer and by the test kernels (shaders/tests/).
// The compiled pipeline (with its layouts) is shared: a second ComputePipeline on the same device
// with the same SPIR-V, specialization constants, bindings and push-constant size reuses the
// first one's (VulkanDevice::compiledPipelines) and only allocates descriptor sets of its own.
// Lavapipe spends up to seconds compiling the path tracer's SPIR-V to LLVM and machine code (at
// the pipeline's creation and its first dispatch), and compiling the same input again gives the
// same code; the tests build many renderers of one variant in a process. Before the driver sees
// it, the SPIR-V is specialized on the host (vk/spirv_specialize.h), which makes the pipeline's
// creation several times faster (ComputePipelineDesc::specializeOnHost).
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <tuple>
#include <vector>

#include "vk/device.h"

namespace vkp {

struct ComputePipelineDesc {
    std::span<const std::uint32_t> spirv;           ///< SPIR-V words (embedded at build time)
    std::vector<vk::DescriptorType> bindings;       ///< binding i has type bindings[i]
    std::uint32_t pushConstantBytes = 0;
    std::vector<std::uint32_t> specConstants;       ///< constant_id i = specConstants[i] (bool: 0/1)
    std::uint32_t descriptorSets = 1;               ///< sets of the layout to allocate (one per band of the path tracer)
    /// Bake the specialization constants into the SPIR-V and remove the code they make dead
    /// before the driver compiles it (vk/spirv_specialize.h); false: the driver specializes.
    /// Both compute the same; host specialization compiles the path tracer several times faster
    /// on lavapipe.
    bool specializeOnHost = true;
};

/// A compiled pipeline and its layouts, shared by the ComputePipeline objects built from the same
/// description (descriptorSets aside).
struct SharedPipeline {
    vk::raii::DescriptorSetLayout setLayout{nullptr};
    vk::raii::PipelineLayout layout{nullptr};
    vk::raii::ShaderModule module{nullptr};
    vk::raii::Pipeline pipeline{nullptr};
};

/// VulkanDevice::compiledPipelines: the pipelines of one device by (SPIR-V words, specialization
/// constants, binding types, push-constant bytes), the whole SPIR-V compared, not a hash of it.
/// The kKeep most recently used are kept (a ComputePipeline keeps its own alive in any case).
struct CompiledPipelines {
    static constexpr std::size_t kKeep = 16;
    using Key = std::tuple<std::vector<std::uint32_t>, std::vector<std::uint32_t>, std::vector<vk::DescriptorType>, std::uint32_t, bool>;
    struct Entry {
        std::shared_ptr<const SharedPipeline> pipeline;
        std::uint64_t lastUse = 0;
    };
    std::mutex mutex;
    std::map<Key, Entry> pipelines;
    std::uint64_t uses = 0;      ///< ComputePipeline objects built
    std::uint64_t compiled = 0;  ///< pipelines compiled for them (the others were reused)
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
    std::shared_ptr<const SharedPipeline> shared_;
    vk::raii::DescriptorPool pool_{nullptr};
    std::vector<vk::raii::DescriptorSet> sets_;
};

}  // namespace vkp
