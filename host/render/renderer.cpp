#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "core/errors.h"
#include "pathtrace.spv.h"
#include "render/adaptive.h"
#include "render/gpu_arrays.h"
#include "render/gpu_scene.h"
#include "render/kernel_bindings.h"
#include "render/render_state.h"
#include "render/workgroup.h"
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

vk::BufferUsageFlags bufferUsage(BindingKind k) {
    switch (k) {
        case BindingKind::UniformBuffer: return vk::BufferUsageFlagBits::eUniformBuffer;
        case BindingKind::UniformTexelBuffer: return vk::BufferUsageFlagBits::eUniformTexelBuffer;
        case BindingKind::StorageBuffer: return vk::BufferUsageFlagBits::eStorageBuffer;
    }
    return vk::BufferUsageFlagBits::eStorageBuffer;
}

vk::Format texelFormat(TexelFormat f) {
    switch (f) {
        case TexelFormat::R32Float: return vk::Format::eR32Sfloat;
        case TexelFormat::R32Uint: return vk::Format::eR32Uint;
        default: return vk::Format::eR32G32B32A32Uint;
    }
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
    /// One band of rows with its own per-pixel buffers and descriptor set (the set's index).
    struct BandBuffers {
        Band band;
        std::unique_ptr<GpuBuffer> sum, sumSq, decision, active, aov;
        std::uint32_t activeCount = 0;  ///< adaptive sampling: entries of `active`
        GpuBuffer& at(std::uint32_t binding) {
            return binding == VKP_BINDING_ACCUM_SUM ? *sum : binding == VKP_BINDING_ACCUM_SQ ? *sumSq
                   : binding == VKP_BINDING_DECISION ? *decision : binding == VKP_BINDING_AOV ? *aov : *active;
        }
    };
    std::vector<std::unique_ptr<GpuBuffer>> shared;  ///< per binding; null for the per-pixel ones
    std::vector<BandBuffers> bands;
    std::vector<vk::raii::BufferView> views;  ///< the texel buffers' views
    std::unique_ptr<ComputePipeline> pipeline;       // one pixel per invocation (PIXEL_SLOTS false)
    std::unique_ptr<ComputePipeline> slotPipeline;   // several (PIXEL_SLOTS true): made when first needed
    ComputePipelineDesc desc;                         // what both are made from
    GpuBuffer& counters() { return *shared.at(VKP_BINDING_COUNTERS); }
    /// Timestamps around every dispatch of a submission (submitSamples); grown on demand. Null
    /// where the compute queue has no timestamps (DeviceInfo::timestampValidBits 0).
    vk::raii::QueryPool timestamps{nullptr};
    std::uint32_t timestampCapacity = 0;
    AovFrame aovFrame;  ///< GpuArrays::aovFrame, for state() (RenderState::aovFrame)
};

Renderer::Renderer(VulkanDevice& device, const GpuArrays& arrays, const RenderOptions& options, const DeviceLimits* limits)
    : impl_(std::make_unique<Impl>()),
      dev_(&device),
      features_(arrays.features),
      width_(arrays.width),
      height_(arrays.height),
      spd_(options.samplesPerDispatch ? options.samplesPerDispatch : 1),
      pixelsPerInvocation_(options.pixelsPerInvocation),
      cpuDevice_(device.info().kind == DeviceKind::Cpu),
      autoSpd_(options.samplesPerDispatch == 0),
      targetDispatch_(options.targetDispatchSeconds >= 0.0 ? options.targetDispatchSeconds
                      : device.info().kind == DeviceKind::Cpu ? 0.0
                                                           : kTargetDispatchSeconds),
      linearTiles_(options.linearTiles),
      sceneBytes_(arrays.sceneBytes()),
      active_(arrays.width * arrays.height),
      adaptiveThreshold_(options.adaptiveThreshold),
      adaptiveMinSpp_(options.adaptiveMinSpp) {
    const DeviceLimits own = deviceLimits(device.info());
    const DeviceLimits& lim = limits ? *limits : own;
    if (const std::string problem = fitProblem(arrays, lim); !problem.empty()) throw DeviceError(problem);
    const glm::uvec2 workgroup = kernelWorkgroup(arrays.features, lim);  // `--workgroup`, else the device's
    features_.workgroupX = workgroup.x;
    features_.workgroupY = workgroup.y;
    impl_->aovFrame = arrays.aovFrame;
    // The read-only buffers once, uploaded; the per-pixel ones per band, zeroed below.
    ComputePipelineDesc desc;
    for (const BufferSize& size : arrays.sizes()) {
        const KernelBinding& b = *size.binding;
        desc.bindings.push_back(descriptorType(b.kind));
        if (isPerPixelBinding(b.binding)) {
            impl_->shared.push_back(nullptr);
            continue;
        }
        auto buffer = std::make_unique<GpuBuffer>(device, size.bytes, bufferUsage(b.kind));
        if (const std::span<const std::byte> data = arrays.hostData(b.binding); !data.empty())
            buffer->upload(data.data(), data.size());
        impl_->shared.push_back(std::move(buffer));
    }
    if (adaptive()) activeMask_.assign(std::size_t(width_) * height_, 1);
    if (const char* inject = std::getenv("VKPATH_INJECT_DEVICE_LOST")) injectDeviceLostAt_ = std::uint32_t(std::strtoul(inject, nullptr, 10));
    for (const Band& band : planBands(arrays, lim)) {
        Impl::BandBuffers bb;
        bb.band = band;
        const std::uint64_t pixels = std::uint64_t(width_) * band.rows;
        auto make = [&](std::uint32_t binding) {
            return std::make_unique<GpuBuffer>(device, pixels * arrays.bytesPerPixel(binding), vk::BufferUsageFlagBits::eStorageBuffer);
        };
        bb.sum = make(VKP_BINDING_ACCUM_SUM);
        bb.sumSq = make(VKP_BINDING_ACCUM_SQ);
        bb.decision = make(VKP_BINDING_DECISION);  // 16-byte tokens without adaptive sampling
        bb.active = make(VKP_BINDING_ACTIVE);
        bb.aov = make(VKP_BINDING_AOV);  // 16-byte tokens without feature images
        impl_->bands.push_back(std::move(bb));
    }
    if (adaptive()) uploadActiveLists();
    device.submitAndWait([&](vk::raii::CommandBuffer& cmd) {
        cmd.fillBuffer(impl_->counters().buffer(), 0, VK_WHOLE_SIZE, 0);
        for (Impl::BandBuffers& bb : impl_->bands)
            for (GpuBuffer* b : {bb.sum.get(), bb.sumSq.get(), bb.decision.get(), bb.aov.get()}) cmd.fillBuffer(b->buffer(), 0, VK_WHOLE_SIZE, 0);
    });

    desc.spirv = std::span<const std::uint32_t>(kPathtraceSpv, sizeof(kPathtraceSpv) / sizeof(kPathtraceSpv[0]));
    desc.pushConstantBytes = sizeof(gpu::GpuPush);
    desc.specConstants = features_.specConstants();
    desc.specializeOnHost = options.specializeOnHost;
    desc.descriptorSets = std::uint32_t(impl_->bands.size());
    impl_->desc = desc;
    impl_->views.reserve(std::size(kKernelBindings));  // views are bound by handle below
    for (const KernelBinding& b : kKernelBindings)
        if (b.kind == BindingKind::UniformTexelBuffer) impl_->views.push_back(impl_->shared.at(b.binding)->texelView(texelFormat(b.format)));
    // A forced pixel count needs only the pipeline that takes several pixels.
    if (pixelsPerInvocation_ > 1) slotPipeline();
    else impl_->pipeline = makePipeline(false);
    device.instance().throwIfValidationMessages("while setting up the renderer");
}

std::unique_ptr<ComputePipeline> Renderer::makePipeline(bool pixelSlots) {
    ComputePipelineDesc desc = impl_->desc;
    Features f = features_;
    f.pixelSlots = pixelSlots;
    desc.specConstants = f.specConstants();
    auto pipeline = std::make_unique<ComputePipeline>(*dev_, desc);
    for (std::uint32_t set = 0; set < impl_->bands.size(); ++set) {
        std::size_t view = 0;
        for (const KernelBinding& b : kKernelBindings) {
            if (b.kind == BindingKind::UniformTexelBuffer) pipeline->bindTexelView(b.binding, *impl_->views[view++], set);
            else if (isPerPixelBinding(b.binding)) pipeline->bindBuffer(b.binding, impl_->bands[set].at(b.binding).buffer(), set);
            else pipeline->bindBuffer(b.binding, impl_->shared.at(b.binding)->buffer(), set);
        }
    }
    return pipeline;
}

ComputePipeline& Renderer::slotPipeline() {
    if (!impl_->slotPipeline) impl_->slotPipeline = makePipeline(true);
    return *impl_->slotPipeline;
}

std::uint32_t Renderer::pixelsPerInvocation(std::uint32_t count) const {
    if (pixelsPerInvocation_ > 0) return pixelsPerInvocation_;
    // Automatic: only on a CPU device (lavapipe), where a SIMD batch of 8 lanes runs until its
    // longest path ends, so one sample per invocation leaves most lanes idle for most passes
    // (docs/performance.md "Dispatch size"). A GPU keeps one pixel per invocation, and with it
    // its occupancy.
    // And only where a dispatch of spd_ samples per pixel would take longer than a submission
    // should (the last submission's time per sample says so): a small image's submissions that
    // happen to hold few samples (the last before a dump or `--time`'s end) keep the one pipeline.
    // The samples of one invocation are then made up to min(spd_, kSlotSamples): more samples of
    // one pixel need no slots, whose switch costs ~10 % per sample (docs/performance.md).
    const std::uint32_t wanted = std::min(spd_, kSlotSamples);
    if (!cpuDevice_ || count >= wanted || secondsPerSample_ * spd_ < kSlotSeconds) return 1;
    return (wanted + count - 1) / count;
}

Renderer::~Renderer() = default;

std::uint32_t Renderer::bandCount() const { return std::uint32_t(impl_->bands.size()); }

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
    const std::uint32_t perGroup = features_.workgroupX * features_.workgroupY;
    const std::uint32_t groupsX = (width_ + features_.workgroupX - 1) / features_.workgroupX;
    std::uint32_t dispatches = 0;
    // Device timestamps before the first dispatch and after each (each dispatch ends in a barrier,
    // ComputePipeline::recordDispatch): what every dispatch took on the device.
    const DeviceInfo& info = dev_->info();
    const bool timed = info.timestampValidBits > 0 && info.timestampPeriodNs > 0.0;
    const std::uint32_t slots = pixelsPerInvocation(count);
    ComputePipeline& pipeline = slots > 1 || !impl_->pipeline ? slotPipeline() : *impl_->pipeline;
    maxSlots_ = std::max(maxSlots_, slots);
    // Samples per pixel of one dispatch: with several pixels per invocation, all of them at once.
    const std::uint32_t perPixel = slots > 1 ? std::min(count, spd_) : spd_;
    const std::uint32_t planned = std::uint32_t(impl_->bands.size()) * ((count + perPixel - 1) / perPixel);
    if (timed && impl_->timestampCapacity < planned + 1) {
        impl_->timestampCapacity = std::max(planned + 1, 2 * impl_->timestampCapacity);
        vk::QueryPoolCreateInfo qi{};
        qi.queryType = vk::QueryType::eTimestamp;
        qi.queryCount = impl_->timestampCapacity;
        impl_->timestamps = vk::raii::QueryPool(dev_->device(), qi);
    }
    const auto t0 = std::chrono::steady_clock::now();
    try {
        if (++submissions_ == injectDeviceLostAt_) throw vk::DeviceLostError("vkQueueSubmit (injected by VKPATH_INJECT_DEVICE_LOST)");
        dev_->submitAndWait([&](vk::raii::CommandBuffer& cmd) {
            cmd.fillBuffer(impl_->counters().buffer(), gpu::COUNTER_MAX_PASSES * 4, 4, 0);
            vk::MemoryBarrier mb{};
            mb.srcAccessMask = vk::AccessFlagBits::eTransferWrite;
            mb.dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite;
            cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, mb,
                                nullptr, nullptr);
            if (timed) {
                cmd.resetQueryPool(*impl_->timestamps, 0, planned + 1);
                cmd.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *impl_->timestamps, 0);
            }
            for (std::uint32_t set = 0; set < impl_->bands.size(); ++set) {
                const Impl::BandBuffers& bb = impl_->bands[set];
                gpu::GpuPush push{};
                const std::uint32_t groupsY = (bb.band.rows + features_.workgroupY - 1) / features_.workgroupY;
                const std::uint32_t tiles = groupsX * groupsY;
                push.band = glm::uvec4(bb.band.firstRow, bb.band.rows, tiles, linearTiles_ ? 1u : tileStride(tiles));
                // With adaptive sampling: the band's list of active pixels, one per invocation, slots scrambled.
                std::uint32_t groups = tiles;
                if (adaptive()) {
                    if (bb.activeCount == 0) continue;
                    groups = (bb.activeCount + perGroup - 1) / perGroup;
                    push.adaptive = glm::uvec4(bb.activeCount, groups, tileStride(groups), 0);
                }
                // The dispatch: the band's tiles as they lie, or else (a packed list, several
                // pixels per invocation: workgroup g takes the virtual workgroups g * slots to
                // g * slots + slots - 1, shaders/pathtrace.comp) rows of at most
                // kAdaptiveGroupsPerRow workgroups; the kernel numbers them by gl_NumWorkGroups.
                std::uint32_t dispatchX = groupsX, dispatchY = groupsY;
                if (adaptive() || slots > 1) {
                    const std::uint32_t real = (groups + slots - 1) / slots;
                    dispatchX = std::min<std::uint32_t>(real, kAdaptiveGroupsPerRow);
                    dispatchY = (real + dispatchX - 1) / dispatchX;
                }
                for (std::uint32_t s = 0; s < count; s += perPixel) {
                    push.batch = glm::uvec4(done_ + s, std::min(perPixel, count - s), slots, 0);
                    pipeline.recordDispatch(cmd, dispatchX, dispatchY, &push, sizeof(push), set);
                    ++dispatches;
                    if (timed) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *impl_->timestamps, dispatches);
                }
            }
        });
    } catch (const vk::SystemError& e) {
        throw VulkanError(std::string("rendering failed: ") + e.what());
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    double slowest = dispatches > 0 ? seconds / dispatches : 0.0;  // without timestamps: the mean
    if (timed && dispatches > 0) {
        const auto [result, ticks] = impl_->timestamps.getResults<std::uint64_t>(
            0, dispatches + 1, sizeof(std::uint64_t) * (dispatches + 1), sizeof(std::uint64_t),
            vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
        if (result == vk::Result::eSuccess) {
            const std::uint64_t mask = info.timestampValidBits >= 64 ? ~0ull : (1ull << info.timestampValidBits) - 1;
            slowest = 0.0;
            for (std::uint32_t k = 0; k < dispatches; ++k)
                slowest = std::max(slowest, double((ticks[k + 1] - ticks[k]) & mask) * info.timestampPeriodNs * 1e-9);
        }
    }
    if (submissions_ > 1 && dispatches > 0) longestDispatch_ = std::max(longestDispatch_, slowest);
    if (submissions_ > 1 && count > 0) secondsPerSample_ = seconds / count;  // the first holds the JIT
    done_ += count;
    taken_ += std::uint64_t(count) * active_;
    dev_->instance().throwIfValidationMessages("while rendering");
    std::uint32_t raw[gpu::COUNTER_COUNT];
    impl_->counters().download(raw, sizeof(raw));
    maxPasses_ = raw[gpu::COUNTER_MAX_PASSES];
    if (autoSpd_) {
        // Passes grow about linearly with the samples per dispatch: aim the busiest invocation at
        // half of the 60,000-pass guard; and time does too: on a GPU aim the slowest dispatch
        // (device timestamps; the first submission's, which holds the shader JIT, left out) at
        // targetDispatch_, so that no dispatch approaches a watchdog's seconds. At most doubling
        // per step, 1 to maxAutoSamplesPerDispatch() samples.
        constexpr double kTargetPasses = 30000.0;
        const std::uint32_t perDispatch = slots * std::min(perPixel, count);  // samples per invocation
        const double perSample = double(std::max<std::uint32_t>(maxPasses_, 1)) / perDispatch;
        double fit = kTargetPasses / perSample;
        if (timed && targetDispatch_ > 0.0 && submissions_ > 1 && slowest > 0.0)
            fit = std::min(fit, targetDispatch_ * perDispatch / slowest);
        spd_ = std::clamp<std::uint32_t>(std::uint32_t(std::clamp(fit, 1.0, double(maxAutoSamplesPerDispatch()))), 1, 2 * spd_);
    }
}

namespace {
/// Reads one per-pixel binding of every band into `out` (`floats` per pixel: kStateFloatsPerPixel
/// for the accumulation buffers, kAovFloatsPerPixel for the feature images).
template <class Bands>
void downloadPerPixel(Bands& bands, std::uint32_t binding, std::uint32_t width, std::vector<float>& out,
                      std::size_t floats = kStateFloatsPerPixel) {
    for (auto& bb : bands)
        bb.at(binding).download(out.data() + std::size_t(bb.band.firstRow) * width * floats,
                                std::size_t(bb.band.rows) * width * floats * sizeof(float));
}
template <class Bands>
void uploadPerPixel(Bands& bands, std::uint32_t binding, std::uint32_t width, const std::vector<float>& in,
                    std::size_t floats = kStateFloatsPerPixel) {
    for (auto& bb : bands)
        bb.at(binding).upload(in.data() + std::size_t(bb.band.firstRow) * width * floats,
                              std::size_t(bb.band.rows) * width * floats * sizeof(float));
}

/// Combines each pixel's compensated pairs (kStateFloatsPerPixel floats: hi.rgba, lo.rgba;
/// shared/compensated_sum.h) into 4 doubles per pixel.
void combinePairs(const std::vector<float>& raw, std::vector<double>& out) {
    const std::size_t pixels = raw.size() / kStateFloatsPerPixel;
    out.resize(pixels * 4);
    for (std::size_t i = 0; i < pixels; ++i)
        for (std::size_t c = 0; c < 4; ++c) out[4 * i + c] = double(raw[8 * i + c]) + double(raw[8 * i + 4 + c]);
}
}  // namespace

void Renderer::updateAdaptive() {
    std::vector<float> decision(std::size_t(width_) * height_ * kStateFloatsPerPixel);
    downloadPerPixel(impl_->bands, VKP_BINDING_DECISION, width_, decision);
    const std::uint32_t before = active_;
    active_ = updateActivePixels(activeMask_, decision, width_, height_, adaptiveThreshold_, done_);
    if (active_ == before || active_ == 0) return;
    uploadActiveLists();
}

void Renderer::uploadActiveLists() {
    for (Impl::BandBuffers& bb : impl_->bands) {
        const std::vector<std::uint32_t> list = activePixelList(activeMask_, width_, height_, bb.band.firstRow, bb.band.rows);
        if (!list.empty()) bb.active->upload(list.data(), list.size() * 4);
        bb.activeCount = std::uint32_t(list.size());
    }
}

void Renderer::startAt(std::uint32_t first) {
    if (done_ != first_ || taken_ != 0) throw std::logic_error("Renderer::startAt after samples were added");
    if (adaptive() && first != 0) throw std::logic_error("Renderer::startAt: adaptive sampling starts at sample 0");
    first_ = done_ = first;
}

void Renderer::jumpTo(std::uint32_t next) {
    if (adaptive()) throw std::logic_error("Renderer::jumpTo with adaptive sampling");
    done_ = next;
}


RenderState Renderer::state() {
    RenderState st;
    st.width = width_;
    st.height = height_;
    st.firstSample = first_;
    st.nextSample = done_;
    st.samplesTaken = taken_;
    st.counters = counters();
    const std::size_t floats = std::size_t(width_) * height_ * kStateFloatsPerPixel;
    st.sum.resize(floats);
    st.sumSq.resize(floats);
    downloadPerPixel(impl_->bands, VKP_BINDING_ACCUM_SUM, width_, st.sum);
    downloadPerPixel(impl_->bands, VKP_BINDING_ACCUM_SQ, width_, st.sumSq);
    if (adaptive()) {
        st.decision.resize(floats);
        downloadPerPixel(impl_->bands, VKP_BINDING_DECISION, width_, st.decision);
        st.active = activeMask_;
    }
    if (features_.aov) {
        st.aov = readAovSums();
        st.aovFrame = impl_->aovFrame;
    }
    return st;
}

std::vector<float> Renderer::readAovSums() {
    if (!features_.aov) return {};
    std::vector<float> out(std::size_t(width_) * height_ * kAovFloatsPerPixel);
    downloadPerPixel(impl_->bands, VKP_BINDING_AOV, width_, out, kAovFloatsPerPixel);
    return out;
}

void Renderer::restore(const RenderState& st, const std::string& what) {
    if (st.width != width_ || st.height != height_)
        throw InputError(what + ": the state is of a " + std::to_string(st.width) + "x" + std::to_string(st.height) +
                         " image, this render is " + std::to_string(width_) + "x" + std::to_string(height_));
    if (st.adaptive() != adaptive())
        throw InputError(what + (adaptive() ? ": the state has no adaptive sampling, this render has"
                                            : ": the state has adaptive sampling, this render has not"));
    const std::size_t floats = std::size_t(width_) * height_ * kStateFloatsPerPixel;
    if (st.sum.size() != floats || st.sumSq.size() != floats || (adaptive() && (st.decision.size() != floats || st.active.size() != floats / kStateFloatsPerPixel)))
        throw InputError(what + ": the state's arrays do not match its size");
    if (st.nextSample < st.firstSample) throw InputError(what + ": the state's next sample precedes its first");
    if (!st.aov.empty() != features_.aov)
        throw InputError(what + (features_.aov ? ": the state has no feature images, this render has (--aov)"
                                               : ": the state has feature images (--aov), this render has not"));
    if (features_.aov && st.aov.size() != floats / kStateFloatsPerPixel * kAovFloatsPerPixel)
        throw InputError(what + ": the state's feature images do not match its size");
    if (features_.aov) uploadPerPixel(impl_->bands, VKP_BINDING_AOV, width_, st.aov, kAovFloatsPerPixel);
    uploadPerPixel(impl_->bands, VKP_BINDING_ACCUM_SUM, width_, st.sum);
    uploadPerPixel(impl_->bands, VKP_BINDING_ACCUM_SQ, width_, st.sumSq);
    std::uint32_t raw[gpu::COUNTER_COUNT] = {};
    raw[gpu::COUNTER_NONFINITE] = std::uint32_t(st.counters.nonfinite);
    raw[gpu::COUNTER_RAYS_LO] = std::uint32_t(st.counters.rays);
    raw[gpu::COUNTER_RAYS_HI] = std::uint32_t(st.counters.rays >> 32);
    raw[gpu::COUNTER_LOOP_GUARD] = std::uint32_t(st.counters.loopGuard);
    impl_->counters().upload(raw, sizeof(raw));
    first_ = st.firstSample;
    done_ = st.nextSample;
    taken_ = st.samplesTaken;
    if (adaptive()) {
        uploadPerPixel(impl_->bands, VKP_BINDING_DECISION, width_, st.decision);
        activeMask_ = st.active;
        active_ = std::uint32_t(std::count_if(activeMask_.begin(), activeMask_.end(), [](std::uint8_t a) { return a != 0; }));
        uploadActiveLists();
    }
}

PixelSums RenderState::pixelSums() const {
    PixelSums s;
    s.width = width;
    s.height = height;
    combinePairs(sum, s.sum);
    combinePairs(sumSq, s.sumSq);
    return s;
}

PixelSums Renderer::readSums() {
    PixelSums s;
    s.width = width_;
    s.height = height_;
    std::vector<float> raw(std::size_t(width_) * height_ * kStateFloatsPerPixel);  // reused for both
    downloadPerPixel(impl_->bands, VKP_BINDING_ACCUM_SUM, width_, raw);
    combinePairs(raw, s.sum);
    downloadPerPixel(impl_->bands, VKP_BINDING_ACCUM_SQ, width_, raw);
    combinePairs(raw, s.sumSq);
    return s;
}

RenderCounters Renderer::counters() {
    std::uint32_t raw[gpu::COUNTER_COUNT];
    impl_->counters().download(raw, sizeof(raw));
    RenderCounters c;
    c.nonfinite = raw[gpu::COUNTER_NONFINITE];
    c.rays = (std::uint64_t(raw[gpu::COUNTER_RAYS_HI]) << 32) | raw[gpu::COUNTER_RAYS_LO];
    c.loopGuard = raw[gpu::COUNTER_LOOP_GUARD];
    return c;
}

}  // namespace vkp
