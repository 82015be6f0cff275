#include "render/renderer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "bvh/flatten.h"
#include "bvh/wide_pack.h"
#include "core/errors.h"
#include "pathtrace.spv.h"
#include "render/environment.h"
#include "render/adaptive.h"
#include "render/ggx_albedo_table.h"
#include "render/gpu_scene.h"
#include "render/kernel_bindings.h"
#include "render/light_table.h"
#include "render/texture_pack.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp {

namespace {
vk::DescriptorType descriptorType(BindingKind k) {
    switch (k) {
        case BindingKind::UniformBuffer: return vk::DescriptorType::eUniformBuffer;
        case BindingKind::UniformTexelBuffer: return vk::DescriptorType::eUniformTexelBuffer;
        case BindingKind::StorageBuffer: return vk::DescriptorType::eStorageBuffer;
    }
    return vk::DescriptorType::eStorageBuffer;
}

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
        const double n = sum[4 * i + 3];
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = n > 0.0 ? float(sum[4 * i + c] / n) : 0.0f;
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
    std::unique_ptr<GpuBuffer> frame, nodes, prims, materials, lights, sum, sumSq, counters, envTexels, envDist, decision, active;
    std::unique_ptr<GpuBuffer> attributes, texInfo, texels, instances;
    vk::raii::BufferView instancesView{nullptr};
    vk::raii::BufferView nodesView{nullptr}, primsView{nullptr}, materialsView{nullptr}, lightsView{nullptr};
    vk::raii::BufferView attributesView{nullptr}, texInfoView{nullptr}, texelsView{nullptr};
    vk::raii::BufferView envTexelsView{nullptr}, envDistView{nullptr};
    std::unique_ptr<ComputePipeline> pipeline;
};

std::uint64_t Renderer::sceneBufferBytes() const {
    std::uint64_t n = 0;
    for (const auto* b : {&impl_->nodes, &impl_->prims, &impl_->materials, &impl_->lights, &impl_->envTexels, &impl_->envDist,
                          &impl_->attributes, &impl_->texInfo, &impl_->texels})
        if (*b) n += (*b)->size();
    return n;
}

Renderer::Renderer(VulkanDevice& device, const Scene& scene, const FlatBvh& bvh, const RendererOptions& options)
    : impl_(std::make_unique<Impl>()),
      dev_(&device),
      features_(sceneFeatures(scene, options.sampler, options.fullVariant)),
      width_(scene.camera.width),
      height_(scene.camera.height),
      spd_(options.samplesPerDispatch ? options.samplesPerDispatch : 1),
      autoSpd_(options.samplesPerDispatch == 0),
      active_(scene.camera.width * scene.camera.height),
      adaptiveThreshold_(options.adaptiveThreshold),
      adaptiveMinSpp_(options.adaptiveMinSpp) {
    features_.sequence = options.sequence;
    features_.lightSampling = options.lightSampling;
    features_.solidAngleMinSize = options.solidAngleMinSize;
    features_.workgroupX = options.workgroupX;
    features_.workgroupY = options.workgroupY;
    const DeviceInfo& limits = device.info();
    if (options.workgroupX == 0 || options.workgroupY == 0 || options.workgroupX > limits.maxComputeWorkGroupSize[0] ||
        options.workgroupY > limits.maxComputeWorkGroupSize[1] ||
        options.workgroupX * options.workgroupY > limits.maxComputeWorkGroupInvocations)
        throw VulkanError("workgroup " + std::to_string(options.workgroupX) + "x" + std::to_string(options.workgroupY) +
                          " is beyond this device's limits (" + std::to_string(limits.maxComputeWorkGroupSize[0]) + "x" +
                          std::to_string(limits.maxComputeWorkGroupSize[1]) + ", " +
                          std::to_string(limits.maxComputeWorkGroupInvocations) + " invocations)");
    if (bvh.instances.size() != scene.instances.size())
        throw std::invalid_argument("Renderer: the BVH was not built with the scene's instances (use buildSceneBvh)");
    const std::uint64_t texelLimit = device.info().maxTexelBufferElements;
    // The kernel traverses the 4-wide layout (lib/traverse.glsl): FlatBvh::wideNodes, or collapsed here
    // for a FlatBvh that came from flattenBvh alone.
    const std::vector<gpu::GpuWideNode> collapsed = bvh.wideNodes.empty() ? buildWideNodes(bvh) : std::vector<gpu::GpuWideNode>{};
    const std::vector<gpu::GpuWideNode>& wideNodes = bvh.wideNodes.empty() ? collapsed : bvh.wideNodes;
    if (wideNodes.size() * gpu::GPU_WIDE_NODE_TEXELS > texelLimit || bvh.prims.size() * gpu::GPU_PRIM_TEXELS > texelLimit)
        throw VulkanError("scene too large for this device: " + std::to_string(bvh.prims.size()) +
                          " primitives need more than maxTexelBufferElements = " + std::to_string(texelLimit) + " texels");
    const EnvTables env = packEnvironment(scene);
    if (env.texels.size() > texelLimit || env.distribution.size() > texelLimit)
        throw VulkanError("environment map too large for this device: " + std::to_string(env.width) + "x" +
                          std::to_string(env.height) + " needs " + std::to_string(env.distribution.size()) +
                          " texels, more than maxTexelBufferElements = " + std::to_string(texelLimit));
    // Textures and vertex attributes (lib/surface.glsl): only what the variant reads is uploaded
    // in full; the others get a token texel.
    TexturePack tex;
    if (features_.textures || features_.alpha) tex = packTextures(scene);
    if (tex.info.empty()) tex.info.assign(1, glm::uvec4(0));
    if (tex.texels.empty()) tex.texels.assign(1, 0u);
    std::vector<glm::uvec4> attributes(1, glm::uvec4(0));
    if (features_.vertexAttributes) attributes = packVertexAttributes(scene, bvh);
    if (const std::string problem = texelLimitProblem(scene, tex, attributes.size(), texelLimit); !problem.empty())
        throw VulkanError(problem);
    std::vector<std::uint32_t> primOfShape(scene.shapes.size(), 0);
    for (std::uint32_t i = 0; i < bvh.primToShape.size(); ++i) {
        const bool topShape = (bvh.primMesh.empty() || bvh.primMesh[i] == 0) && bvh.primToShape[i] != FlatBvh::kNotAShape;
        if (topShape) primOfShape[bvh.primToShape[i]] = i;
    }
    // Instances (two-level BVH): a token record when there are none (HAS_INSTANCES is then false).
    std::vector<gpu::GpuInstance> instances = bvh.instances;
    if (instances.empty()) instances.resize(1, gpu::GpuInstance{});
    if (instances.size() * gpu::GPU_INSTANCE_TEXELS > texelLimit)
        throw VulkanError("scene too large for this device: " + std::to_string(instances.size()) +
                          " instances need more than maxTexelBufferElements = " + std::to_string(texelLimit) + " texels");

    gpu::GpuFrame frame = packFrame(scene, options.lightPick, glm::uvec2(options.workgroupX, options.workgroupY), options.linearTiles);
    // Material texels, then (for glTF BRDF variants) the GGX albedo table at texel counts.w.
    std::vector<glm::vec4> materialTexels;
    for (const gpu::GpuMaterial& m : packMaterials(scene.materials))
        for (const glm::vec4& t : {m.m0, m.m1, m.m2, m.m3}) materialTexels.push_back(t);
    static_assert(gpu::GPU_MATERIAL_TEXELS == 4, "one push_back per GpuMaterial member");
    frame.counts.w = std::uint32_t(materialTexels.size());
    if (features_.hasMaterial(gpu::MAT_PBR)) {
        const std::vector<glm::vec4>& table = ggxAlbedoTable();
        materialTexels.insert(materialTexels.end(), table.begin(), table.end());
    }
    impl_->frame = std::make_unique<GpuBuffer>(device, sizeof(frame), vk::BufferUsageFlagBits::eUniformBuffer);
    impl_->frame->upload(&frame, sizeof(frame));
    impl_->nodes = uploadTexels(device, wideNodes);
    impl_->prims = uploadTexels(device, bvh.prims);
    impl_->materials = uploadTexels(device, materialTexels);
    impl_->lights = uploadTexels(device, packLights(scene, primOfShape, options.lightPick));
    impl_->nodesView = impl_->nodes->texelView();
    impl_->primsView = impl_->prims->texelView();
    impl_->materialsView = impl_->materials->texelView();
    impl_->lightsView = impl_->lights->texelView();
    impl_->envTexels = uploadTexels(device, env.texels);
    impl_->envDist = uploadTexels(device, env.distribution);
    impl_->envTexelsView = impl_->envTexels->texelView();
    impl_->envDistView = impl_->envDist->texelView(vk::Format::eR32Sfloat);
    impl_->attributes = uploadTexels(device, attributes);
    impl_->texInfo = uploadTexels(device, tex.info);
    impl_->texels = uploadTexels(device, tex.texels);
    impl_->attributesView = impl_->attributes->texelView();
    impl_->texInfoView = impl_->texInfo->texelView();
    impl_->texelsView = impl_->texels->texelView(vk::Format::eR32Uint);
    impl_->instances = uploadTexels(device, instances);
    impl_->instancesView = impl_->instances->texelView();

    // Two vec4 per pixel: the sum and its compensation (shaders/shared/compensated_sum.h).
    const std::size_t pixelBytes = std::size_t(width_) * height_ * 2 * 4 * sizeof(float);
    impl_->sum = std::make_unique<GpuBuffer>(device, pixelBytes, vk::BufferUsageFlagBits::eStorageBuffer);
    impl_->sumSq = std::make_unique<GpuBuffer>(device, pixelBytes, vk::BufferUsageFlagBits::eStorageBuffer);
    impl_->counters = std::make_unique<GpuBuffer>(device, gpu::COUNTER_COUNT * 4, vk::BufferUsageFlagBits::eStorageBuffer);
    // Adaptive sampling: decision-stream sums and the active-pixel list (a token size when off).
    const std::size_t pixels = std::size_t(width_) * height_;
    impl_->decision = std::make_unique<GpuBuffer>(device, adaptive() ? pixelBytes : 16, vk::BufferUsageFlagBits::eStorageBuffer);
    impl_->active = std::make_unique<GpuBuffer>(device, adaptive() ? pixels * 4 : 16, vk::BufferUsageFlagBits::eStorageBuffer);
    if (adaptive()) {
        activeMask_.assign(pixels, 1);
        const std::vector<std::uint32_t> list = activePixelList(activeMask_, width_, height_);
        impl_->active->upload(list.data(), list.size() * 4);
    }
    device.submitAndWait([&](vk::raii::CommandBuffer& cmd) {
        cmd.fillBuffer(impl_->decision->buffer(), 0, VK_WHOLE_SIZE, 0);
        cmd.fillBuffer(impl_->sum->buffer(), 0, VK_WHOLE_SIZE, 0);
        cmd.fillBuffer(impl_->sumSq->buffer(), 0, VK_WHOLE_SIZE, 0);
        cmd.fillBuffer(impl_->counters->buffer(), 0, VK_WHOLE_SIZE, 0);
    });

    ComputePipelineDesc desc;
    desc.spirv = std::span<const std::uint32_t>(kPathtraceSpv, sizeof(kPathtraceSpv) / sizeof(kPathtraceSpv[0]));
    for (const KernelBinding& b : kKernelBindings) desc.bindings.push_back(descriptorType(b.kind));
    desc.pushConstantBytes = sizeof(gpu::GpuPush);
    desc.specConstants = features_.specConstants();
    impl_->pipeline = std::make_unique<ComputePipeline>(device, desc);
    auto& p = *impl_->pipeline;
    p.bindBuffer(VKP_BINDING_FRAME, impl_->frame->buffer());
    p.bindTexelView(VKP_BINDING_NODES, *impl_->nodesView);
    p.bindTexelView(VKP_BINDING_PRIMS, *impl_->primsView);
    p.bindTexelView(VKP_BINDING_MATERIALS, *impl_->materialsView);
    p.bindTexelView(VKP_BINDING_LIGHTS, *impl_->lightsView);
    p.bindBuffer(VKP_BINDING_ACCUM_SUM, impl_->sum->buffer());
    p.bindBuffer(VKP_BINDING_ACCUM_SQ, impl_->sumSq->buffer());
    p.bindBuffer(VKP_BINDING_COUNTERS, impl_->counters->buffer());
    p.bindTexelView(VKP_BINDING_ENV_TEXELS, *impl_->envTexelsView);
    p.bindTexelView(VKP_BINDING_ENV_DIST, *impl_->envDistView);
    p.bindBuffer(VKP_BINDING_DECISION, impl_->decision->buffer());
    p.bindBuffer(VKP_BINDING_ACTIVE, impl_->active->buffer());
    p.bindTexelView(VKP_BINDING_ATTRIBUTES, *impl_->attributesView);
    p.bindTexelView(VKP_BINDING_TEX_INFO, *impl_->texInfoView);
    p.bindTexelView(VKP_BINDING_TEXELS, *impl_->texelsView);
    p.bindTexelView(VKP_BINDING_INSTANCES, *impl_->instancesView);
    device.instance().throwIfValidationMessages("while setting up the renderer");
}

Renderer::~Renderer() = default;

void Renderer::addSamples(std::uint32_t count) {
    // Adaptive decisions are taken at fixed sample counts (adaptiveMinSpp, then every
    // kAdaptiveStep), never where a caller's batch happens to end, so the image does not depend on
    // how the samples were split into calls.
    while (count > 0 && active_ > 0) {
        std::uint32_t n = count;
        if (adaptive()) {
            const std::uint32_t next = done_ < adaptiveMinSpp_
                                           ? adaptiveMinSpp_
                                           : adaptiveMinSpp_ + ((done_ - adaptiveMinSpp_) / kAdaptiveStep + 1) * kAdaptiveStep;
            n = std::min(n, next - done_);
        }
        submitSamples(n);
        count -= n;
        if (adaptive() && done_ >= adaptiveMinSpp_ && (done_ - adaptiveMinSpp_) % kAdaptiveStep == 0) updateAdaptive();
    }
}

void Renderer::submitSamples(std::uint32_t count) {
    // With adaptive sampling: 1D list of the active pixels, one per invocation, slots scrambled.
    const std::uint32_t perGroup = features_.workgroupX * features_.workgroupY;
    const std::uint32_t groups = (active_ + perGroup - 1) / perGroup;
    const std::uint32_t groupsX = std::min<std::uint32_t>(groups, 4096);
    const std::uint32_t groupsY = (groups + groupsX - 1) / groupsX;
    const glm::uvec4 adaptivePush = adaptive() ? glm::uvec4(active_, groups, tileStride(groups), groupsX) : glm::uvec4(0);
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
                push.adaptive = adaptivePush;
                if (adaptive())
                    impl_->pipeline->recordDispatch(cmd, groupsX, groupsY, &push, sizeof(push));
                else
                    impl_->pipeline->recordDispatch(cmd, (width_ + features_.workgroupX - 1) / features_.workgroupX,
                                                    (height_ + features_.workgroupY - 1) / features_.workgroupY, &push, sizeof(push));
            }
        });
    } catch (const vk::SystemError& e) {
        throw VulkanError(std::string("rendering failed: ") + e.what());
    }
    done_ += count;
    taken_ += std::uint64_t(count) * active_;
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

void Renderer::updateAdaptive() {
    std::vector<float> decision(std::size_t(width_) * height_ * 8);
    impl_->decision->download(decision.data(), decision.size() * sizeof(float));
    const std::uint32_t before = active_;
    active_ = updateActivePixels(activeMask_, decision, width_, height_, adaptiveThreshold_, done_);
    if (active_ != before && active_ > 0) {
        const std::vector<std::uint32_t> list = activePixelList(activeMask_, width_, height_);
        impl_->active->upload(list.data(), list.size() * 4);
    }
}

PixelSums Renderer::readSums() {
    PixelSums s;
    s.width = width_;
    s.height = height_;
    const std::size_t pixels = std::size_t(width_) * height_;
    std::vector<float> raw(pixels * 8);
    // Combines each pixel's (hi, lo) pair in double (shaders/lib/bindings.glsl).
    auto combine = [&](GpuBuffer& buffer, std::vector<double>& out) {
        buffer.download(raw.data(), raw.size() * sizeof(float));
        out.resize(pixels * 4);
        for (std::size_t i = 0; i < pixels; ++i)
            for (int c = 0; c < 4; ++c) out[4 * i + c] = double(raw[8 * i + c]) + double(raw[8 * i + 4 + c]);
    };
    combine(*impl_->sum, s.sum);
    combine(*impl_->sumSq, s.sumSq);
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
