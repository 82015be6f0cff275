#include "render/renderer.h"

#include <algorithm>
#include <cstring>

#include "bvh/flatten.h"
#include "core/errors.h"
#include "pathtrace.spv.h"
#include "render/environment.h"
#include "render/gpu_scene.h"
#include "render/light_table.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp {

namespace {
// Binding numbers of shaders/lib/bindings.glsl.
enum : std::uint32_t {
    kBindingFrame = 0,
    kBindingNodes,
    kBindingPrims,
    kBindingMaterials,
    kBindingLights,
    kBindingSum,
    kBindingSumSq,
    kBindingCounters,
    kBindingEnvTexels,
    kBindingEnvDist,
};

template <class T>
std::unique_ptr<GpuBuffer> uploadTexels(VulkanDevice& dev, const std::vector<T>& data) {
    auto buf = std::make_unique<GpuBuffer>(dev, data.size() * sizeof(T), vk::BufferUsageFlagBits::eUniformTexelBuffer);
    buf->upload(data.data(), data.size() * sizeof(T));
    return buf;
}
}  // namespace

Image PixelSums::mean() const {
    Image img(width, height);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        const float n = sum[4 * i + 3];
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = n > 0.0f ? sum[4 * i + c] / n : 0.0f;
    }
    return img;
}

Image PixelSums::varianceOfMean() const {
    Image img(width, height);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        const double n = sum[4 * i + 3];
        for (int c = 0; c < 3; ++c) {
            if (n < 2) continue;
            const double m = sum[4 * i + c] / n;
            const double var = std::max(0.0, (sumSq[4 * i + c] / n - m * m) * n / (n - 1));
            img.rgb[3 * i + c] = float(var / n);
        }
    }
    return img;
}

struct Renderer::Impl {
    std::unique_ptr<GpuBuffer> frame, nodes, prims, materials, lights, sum, sumSq, counters, envTexels, envDist;
    vk::raii::BufferView nodesView{nullptr}, primsView{nullptr}, materialsView{nullptr}, lightsView{nullptr};
    vk::raii::BufferView envTexelsView{nullptr}, envDistView{nullptr};
    std::unique_ptr<ComputePipeline> pipeline;
};

Renderer::Renderer(VulkanDevice& device, const Scene& scene, const FlatBvh& bvh, const RendererOptions& options)
    : impl_(std::make_unique<Impl>()),
      dev_(&device),
      features_(sceneFeatures(scene, options.sampler, options.fullVariant)),
      width_(scene.camera.width),
      height_(scene.camera.height),
      spd_(options.samplesPerDispatch ? options.samplesPerDispatch : 1),
      autoSpd_(options.samplesPerDispatch == 0) {
    const std::uint64_t texelLimit = device.info().maxTexelBufferElements;
    if (bvh.nodes.size() * gpu::GPU_NODE_TEXELS > texelLimit || bvh.prims.size() * gpu::GPU_PRIM_TEXELS > texelLimit)
        throw VulkanError("scene too large for this device: " + std::to_string(bvh.prims.size()) +
                          " primitives need more than maxTexelBufferElements = " + std::to_string(texelLimit) + " texels");
    const EnvTables env = packEnvironment(scene);
    if (env.texels.size() > texelLimit || env.distribution.size() > texelLimit)
        throw VulkanError("environment map too large for this device: " + std::to_string(env.width) + "x" +
                          std::to_string(env.height) + " needs " + std::to_string(env.distribution.size()) +
                          " texels, more than maxTexelBufferElements = " + std::to_string(texelLimit));
    std::vector<std::uint32_t> primOfShape(scene.shapes.size(), 0);
    for (std::uint32_t i = 0; i < bvh.primToShape.size(); ++i) primOfShape[bvh.primToShape[i]] = i;

    const gpu::GpuFrame frame = packFrame(scene);
    impl_->frame = std::make_unique<GpuBuffer>(device, sizeof(frame), vk::BufferUsageFlagBits::eUniformBuffer);
    impl_->frame->upload(&frame, sizeof(frame));
    impl_->nodes = uploadTexels(device, bvh.nodes);
    impl_->prims = uploadTexels(device, bvh.prims);
    impl_->materials = uploadTexels(device, packMaterials(scene.materials));
    impl_->lights = uploadTexels(device, packLights(scene, primOfShape));
    impl_->nodesView = impl_->nodes->texelView();
    impl_->primsView = impl_->prims->texelView();
    impl_->materialsView = impl_->materials->texelView();
    impl_->lightsView = impl_->lights->texelView();
    impl_->envTexels = uploadTexels(device, env.texels);
    impl_->envDist = uploadTexels(device, env.distribution);
    impl_->envTexelsView = impl_->envTexels->texelView();
    impl_->envDistView = impl_->envDist->texelView(vk::Format::eR32Sfloat);

    const std::size_t pixelBytes = std::size_t(width_) * height_ * 4 * sizeof(float);
    impl_->sum = std::make_unique<GpuBuffer>(device, pixelBytes, vk::BufferUsageFlagBits::eStorageBuffer);
    impl_->sumSq = std::make_unique<GpuBuffer>(device, pixelBytes, vk::BufferUsageFlagBits::eStorageBuffer);
    impl_->counters = std::make_unique<GpuBuffer>(device, gpu::COUNTER_COUNT * 4, vk::BufferUsageFlagBits::eStorageBuffer);
    device.submitAndWait([&](vk::raii::CommandBuffer& cmd) {
        cmd.fillBuffer(impl_->sum->buffer(), 0, VK_WHOLE_SIZE, 0);
        cmd.fillBuffer(impl_->sumSq->buffer(), 0, VK_WHOLE_SIZE, 0);
        cmd.fillBuffer(impl_->counters->buffer(), 0, VK_WHOLE_SIZE, 0);
    });

    ComputePipelineDesc desc;
    desc.spirv = std::span<const std::uint32_t>(kPathtraceSpv, sizeof(kPathtraceSpv) / sizeof(kPathtraceSpv[0]));
    desc.bindings = {vk::DescriptorType::eUniformBuffer,      vk::DescriptorType::eUniformTexelBuffer,
                     vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eUniformTexelBuffer,
                     vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eStorageBuffer,
                     vk::DescriptorType::eStorageBuffer,      vk::DescriptorType::eStorageBuffer,
                     vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eUniformTexelBuffer};
    desc.pushConstantBytes = sizeof(gpu::GpuPush);
    desc.specConstants = features_.specConstants();
    impl_->pipeline = std::make_unique<ComputePipeline>(device, desc);
    auto& p = *impl_->pipeline;
    p.bindBuffer(kBindingFrame, impl_->frame->buffer());
    p.bindTexelView(kBindingNodes, *impl_->nodesView);
    p.bindTexelView(kBindingPrims, *impl_->primsView);
    p.bindTexelView(kBindingMaterials, *impl_->materialsView);
    p.bindTexelView(kBindingLights, *impl_->lightsView);
    p.bindBuffer(kBindingSum, impl_->sum->buffer());
    p.bindBuffer(kBindingSumSq, impl_->sumSq->buffer());
    p.bindBuffer(kBindingCounters, impl_->counters->buffer());
    p.bindTexelView(kBindingEnvTexels, *impl_->envTexelsView);
    p.bindTexelView(kBindingEnvDist, *impl_->envDistView);
    device.instance().throwIfValidationMessages("while setting up the renderer");
}

Renderer::~Renderer() = default;

void Renderer::addSamples(std::uint32_t count) {
    if (count == 0) return;
    try {
        dev_->submitAndWait([&](vk::raii::CommandBuffer& cmd) {
            cmd.fillBuffer(impl_->counters->buffer(), gpu::COUNTER_MAX_PASSES * 4, 4, 0);
            vk::MemoryBarrier mb{};
            mb.srcAccessMask = vk::AccessFlagBits::eTransferWrite;
            mb.dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite;
            cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, mb,
                                nullptr, nullptr);
            for (std::uint32_t s = 0; s < count; s += spd_) {
                gpu::GpuPush push{};
                push.batch = glm::uvec4(done_ + s, std::min(spd_, count - s), 0, 0);
                impl_->pipeline->recordDispatch8x8(cmd, width_, height_, &push, sizeof(push));
            }
        });
    } catch (const vk::SystemError& e) {
        throw VulkanError(std::string("rendering failed: ") + e.what());
    }
    done_ += count;
    dev_->instance().throwIfValidationMessages("while rendering");
    std::uint32_t raw[gpu::COUNTER_COUNT];
    impl_->counters->download(raw, sizeof(raw));
    maxPasses_ = raw[gpu::COUNTER_MAX_PASSES];
    if (autoSpd_) {
        // Passes grow about linearly with the samples per dispatch: aim the busiest invocation at
        // half of the 60,000-pass guard, at most doubling per step.
        constexpr double kTargetPasses = 30000.0;
        const std::uint32_t perDispatch = std::min(spd_, count);
        const double perSample = double(std::max<std::uint32_t>(maxPasses_, 1)) / perDispatch;
        const auto fit = std::uint32_t(std::clamp(kTargetPasses / perSample, 1.0, 8.0));
        spd_ = std::clamp<std::uint32_t>(fit, 1, 2 * spd_);
    }
}

PixelSums Renderer::readSums() {
    PixelSums s;
    s.width = width_;
    s.height = height_;
    s.sum.resize(std::size_t(width_) * height_ * 4);
    s.sumSq.resize(s.sum.size());
    impl_->sum->download(s.sum.data(), s.sum.size() * sizeof(float));
    impl_->sumSq->download(s.sumSq.data(), s.sumSq.size() * sizeof(float));
    return s;
}

RenderCounters Renderer::counters() {
    std::uint32_t raw[gpu::COUNTER_COUNT];
    impl_->counters->download(raw, sizeof(raw));
    RenderCounters c;
    c.nonfinite = raw[gpu::COUNTER_NONFINITE];
    c.rays = (std::uint64_t(raw[gpu::COUNTER_RAYS_HI]) << 32) | raw[gpu::COUNTER_RAYS_LO];
    c.loopGuard = raw[gpu::COUNTER_LOOP_GUARD];
    return c;
}

}  // namespace vkp
