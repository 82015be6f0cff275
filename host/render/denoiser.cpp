// The denoiser's host side: input checks, bands, packing to vec4 per pixel, the dispatches of
// shaders/denoise.comp (demodulate, then one dispatch per level, ping-ponging between two buffers:
// the non-local means pass or an a-trous level of step 1, then a-trous levels) and the read-back.
#include "render/denoiser.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "denoise.spv.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp {

namespace {

/// Must match `push` in shaders/denoise.comp.
struct DenoisePush {
    std::uint32_t width, rows, step, remodulate;
    float sigmaL, sigmaN, sigmaZ, albedoEps, ridge, normalNoise, fireflyBound;
    std::uint32_t radius;
    float patchK, brighterSigma;
};
static_assert(sizeof(DenoisePush) == 56);

/// Bytes per pixel of every buffer: one vec4.
constexpr std::uint64_t kBytesPerPixel = 16;
/// Binding numbers of shaders/denoise.comp.
enum Binding : std::uint32_t { kColor, kVariance, kAlbedo, kGuide, kIllumIn, kIllumOut, kBindingCount };

void checkImage(const Image* img, const char* name, std::uint32_t w, std::uint32_t h) {
    if (!img) throw std::invalid_argument(std::string("denoiser: no ") + name + " image");
    img->checkConsistent();
    if (img->width != w || img->height != h)
        throw std::invalid_argument(std::string("denoiser: the ") + name + " image is " + std::to_string(img->width) + "x" +
                                    std::to_string(img->height) + ", the color image " + std::to_string(w) + "x" +
                                    std::to_string(h));
}

void checkOptions(const DenoiseOptions& o) {
    if (o.filter != DenoiseFilter::NonLocalMeans && o.filter != DenoiseFilter::ATrous)
        throw std::invalid_argument("denoiser: unknown filter " + std::to_string(static_cast<std::uint32_t>(o.filter)));
    if (o.iterations > 10)
        throw std::invalid_argument("denoiser: iterations must be in 1..10 (0: the default), not " + std::to_string(o.iterations));
    if (o.nlmRadius < 1 || o.nlmRadius > 15)
        throw std::invalid_argument("denoiser: nlmRadius must be in 1..15, not " + std::to_string(o.nlmRadius));
    if (!std::isfinite(o.nlmPatchK) || o.nlmPatchK <= 0.0f || !std::isfinite(o.nlmBrighterSigma) || o.nlmBrighterSigma <= 0.0f)
        throw std::invalid_argument("denoiser: nlmPatchK and nlmBrighterSigma must be > 0");
    const auto positive = [](float v) { return std::isfinite(v) && v > 0.0f; };
    if (!positive(o.sigmaLuminance) || !positive(o.sigmaDepth) || !positive(o.albedoEpsilon) ||
        !std::isfinite(o.sigmaNormal) || o.sigmaNormal < 0.0f || !std::isfinite(o.localLinearRidge) ||
        !std::isfinite(o.fireflyBound) || o.fireflyBound < 0.0f)
        throw std::invalid_argument(
            "denoiser: sigmaLuminance, sigmaDepth and albedoEpsilon must be > 0, sigmaNormal and fireflyBound >= 0, localLinearRidge finite");
}

}  // namespace

std::uint32_t filterRadius(std::uint32_t iterations) { return 2u * ((1u << iterations) - 1u) + 1u; }

std::uint32_t levels(const DenoiseOptions& options) {
    if (options.iterations) return options.iterations;
    return options.filter == DenoiseFilter::NonLocalMeans ? 2u : 4u;
}

std::uint32_t filterRadius(const DenoiseOptions& options) {
    const std::uint32_t n = levels(options);
    if (options.filter != DenoiseFilter::NonLocalMeans) return filterRadius(n);
    return options.nlmRadius + 2u + 2u * ((1u << n) - 2u);
}

std::vector<DenoiseBand> planDenoiseBands(std::uint32_t height, std::uint32_t maxRows, std::uint32_t halo) {
    if (height <= maxRows) return {DenoiseBand{0, height, 0, height}};
    if (maxRows <= 2 * halo)
        throw std::invalid_argument("denoiser: a band of " + std::to_string(maxRows) + " rows holds no row beside its halos of " +
                                    std::to_string(halo));
    std::vector<DenoiseBand> bands;
    const std::uint32_t step = maxRows - 2 * halo;
    for (std::uint32_t y0 = 0; y0 < height; y0 += step) {
        DenoiseBand b;
        b.y0 = y0;
        b.y1 = std::min(height, y0 + step);
        b.loadY0 = y0 > halo ? y0 - halo : 0;
        b.loadY1 = std::min(height, b.y1 + halo);
        bands.push_back(b);
    }
    return bands;
}

struct Denoiser::Impl {
    std::unique_ptr<ComputePipeline> demodulate;  ///< PASS 0: one descriptor set
    std::unique_ptr<ComputePipeline> atrous;      ///< PASS 1: set 0 reads ping, writes pong; set 1 the reverse
    std::unique_ptr<ComputePipeline> nlm;         ///< PASS 2: reads ping, writes pong (null: the a-trous filter alone)
    std::uint64_t capacity = 0;                   ///< pixels every buffer holds
    std::unique_ptr<GpuBuffer> in[4];             ///< color, variance, albedo, guide
    std::unique_ptr<GpuBuffer> illum[2];          ///< ping, pong
    std::vector<vk::raii::BufferView> views;      ///< texel views of in[0..3], illum[0..1]

    void reserve(VulkanDevice& dev, std::uint64_t pixels) {
        if (pixels <= capacity) return;
        views.clear();
        const vk::DeviceSize bytes = pixels * kBytesPerPixel;
        for (auto& b : in) b = std::make_unique<GpuBuffer>(dev, bytes, vk::BufferUsageFlagBits::eUniformTexelBuffer);
        for (auto& b : illum)
            b = std::make_unique<GpuBuffer>(dev, bytes, vk::BufferUsageFlagBits::eUniformTexelBuffer |
                                                            vk::BufferUsageFlagBits::eStorageBuffer);
        for (auto& b : in) views.push_back(b->texelView(vk::Format::eR32G32B32A32Sfloat));
        for (auto& b : illum) views.push_back(b->texelView(vk::Format::eR32G32B32A32Sfloat));
        for (std::uint32_t k = 0; k < 4; ++k) {
            demodulate->bindTexelView(k, *views[k]);
            if (nlm) nlm->bindTexelView(k, *views[k]);
            for (std::uint32_t set = 0; set < 2; ++set) atrous->bindTexelView(k, *views[k], set);
        }
        // Every binding of every set is valid; a dispatch never reads the buffer it writes.
        demodulate->bindTexelView(kIllumIn, *views[5]);
        demodulate->bindBuffer(kIllumOut, illum[0]->buffer());
        atrous->bindTexelView(kIllumIn, *views[4], 0);
        atrous->bindBuffer(kIllumOut, illum[1]->buffer(), 0);
        atrous->bindTexelView(kIllumIn, *views[5], 1);
        atrous->bindBuffer(kIllumOut, illum[0]->buffer(), 1);
        if (nlm) {
            nlm->bindTexelView(kIllumIn, *views[4]);
            nlm->bindBuffer(kIllumOut, illum[1]->buffer());
        }
        capacity = pixels;
    }
};

Denoiser::Denoiser(VulkanDevice& device, const DenoiseOptions& options)
    : impl_(std::make_unique<Impl>()), dev_(&device), options_(options) {
    checkOptions(options_);
    ComputePipelineDesc desc;
    desc.spirv = std::span<const std::uint32_t>(kDenoiseSpv, sizeof(kDenoiseSpv) / sizeof(kDenoiseSpv[0]));
    desc.bindings.assign(kIllumOut, vk::DescriptorType::eUniformTexelBuffer);
    desc.bindings.push_back(vk::DescriptorType::eStorageBuffer);
    desc.pushConstantBytes = sizeof(DenoisePush);
    desc.specConstants = {0};
    impl_->demodulate = std::make_unique<ComputePipeline>(device, desc);
    if (options_.filter == DenoiseFilter::NonLocalMeans) {  // only the pipelines the filter runs
        desc.specConstants = {2};
        impl_->nlm = std::make_unique<ComputePipeline>(device, desc);
    }
    desc.specConstants = {1};
    desc.descriptorSets = 2;
    impl_->atrous = std::make_unique<ComputePipeline>(device, desc);
    device.instance().throwIfValidationMessages("while setting up the denoiser");
}

Denoiser::~Denoiser() = default;

Image Denoiser::run(const DenoiseInput& input) {
    if (!input.color) throw std::invalid_argument("denoiser: no color image");
    const std::uint32_t w = input.color->width, h = input.color->height;
    checkImage(input.color, "color", w, h);
    checkImage(input.variance, "variance", w, h);
    checkImage(input.albedo, "albedo", w, h);
    checkImage(input.normal, "normal", w, h);
    if (!input.depth) throw std::invalid_argument("denoiser: no depth image");
    if (input.depth->size() != input.color->pixelCount())
        throw std::invalid_argument("denoiser: the depth image has " + std::to_string(input.depth->size()) +
                                    " values, the color image " + std::to_string(input.color->pixelCount()) + " pixels");
    Image out(w, h);
    lastBands_ = 0;
    if (out.empty()) return out;

    // How many rows one band may load: every buffer within one storage-buffer binding, one texel
    // view, one allocation; the dispatch within the workgroup counts; pixel indices within int.
    const DeviceInfo& info = dev_->info();
    if ((w + 7) / 8 > info.maxComputeWorkGroupCount[0])
        throw DeviceError("denoiser: an image " + std::to_string(w) + " pixels wide needs " + std::to_string((w + 7) / 8) +
                          " workgroups per row, more than this device's maxComputeWorkGroupCount[0] = " +
                          std::to_string(info.maxComputeWorkGroupCount[0]));
    std::uint64_t maxPixels = std::min<std::uint64_t>(info.maxStorageBufferRange / kBytesPerPixel, info.maxTexelBufferElements);
    if (info.maxMemoryAllocationSize) maxPixels = std::min<std::uint64_t>(maxPixels, info.maxMemoryAllocationSize / kBytesPerPixel);
    maxPixels = std::min<std::uint64_t>(maxPixels, std::numeric_limits<std::int32_t>::max());
    std::uint64_t maxRows = std::min<std::uint64_t>(maxPixels / w, 8ull * info.maxComputeWorkGroupCount[1]);
    if (options_.maxBandRows) maxRows = std::min<std::uint64_t>(maxRows, options_.maxBandRows);
    const std::uint32_t halo = filterRadius(options_), levelCount = levels(options_);
    if (h > maxRows && maxRows <= 2ull * halo)
        throw DeviceError("denoiser: an image " + std::to_string(w) + " pixels wide fits only " + std::to_string(maxRows) +
                          " rows in one buffer (maxStorageBufferRange " + std::to_string(info.maxStorageBufferRange) +
                          " bytes); bands need more than " + std::to_string(2 * halo) + " (twice the filter's radius)");
    const std::vector<DenoiseBand> bands = planDenoiseBands(h, std::uint32_t(std::min<std::uint64_t>(maxRows, h)), halo);
    std::uint32_t mostRows = 0;
    for (const DenoiseBand& b : bands) mostRows = std::max(mostRows, b.loadY1 - b.loadY0);
    impl_->reserve(*dev_, std::uint64_t(w) * mostRows);

    std::vector<float> packed(std::size_t(w) * mostRows * 4);
    for (const DenoiseBand& band : bands) {
        const std::uint32_t rows = band.loadY1 - band.loadY0;
        const std::size_t first = std::size_t(band.loadY0) * w, count = std::size_t(rows) * w;
        const std::size_t bytes = count * kBytesPerPixel;
        const auto upload = [&](std::uint32_t k, const Image& img) {
            for (std::size_t i = 0; i < count; ++i) {
                const float* p = img.rgb.data() + 3 * (first + i);
                std::copy(p, p + 3, packed.data() + 4 * i);
                packed[4 * i + 3] = 0.0f;
            }
            impl_->in[k]->upload(packed.data(), bytes);
        };
        upload(kColor, *input.color);
        upload(kVariance, *input.variance);
        upload(kAlbedo, *input.albedo);
        // The guide: the normal (0 where the mean normal is shorter than minNormalLength or not
        // finite) and the depth, -1 where no sample hit. The normal's direction is the mean's; its
        // length 1 / (1 + theta^2) carries the variance theta^2 of that direction (normalNoise;
        // 1 without DenoiseInput::samples).
        const float minLength = std::max(options_.minNormalLength, 1e-6f);
        for (std::size_t i = 0; i < count; ++i) {
            const float* n = input.normal->rgb.data() + 3 * (first + i);
            const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            float s = std::isfinite(len) && len >= minLength ? 1.0f / len : 0.0f;
            if (s > 0.0f && input.samples && (*input.samples)[first + i] >= 1.0f) {
                const float l2 = std::min(len * len, 1.0f);
                const float theta2 = (1.0f - l2) / ((*input.samples)[first + i] * l2);
                s /= 1.0f + theta2;
            }
            for (int c = 0; c < 3; ++c) packed[4 * i + c] = n[c] * s;
            const float z = (*input.depth)[first + i];
            packed[4 * i + 3] = std::isfinite(z) && z >= 0.0f ? z : -1.0f;
        }
        impl_->in[kGuide]->upload(packed.data(), bytes);

        dev_->submitAndWait([&](vk::raii::CommandBuffer& cmd) {
            DenoisePush push{w, rows, 0, 0, options_.sigmaLuminance, options_.sigmaNormal, options_.sigmaDepth,
                             options_.albedoEpsilon, options_.localLinearRidge, options_.normalNoise,
                             options_.fireflyBound, options_.nlmRadius, options_.nlmPatchK,
                             options_.nlmBrighterSigma};
            impl_->demodulate->recordDispatch8x8(cmd, w, rows, &push, sizeof push);
            for (std::uint32_t level = 0; level < levelCount; ++level) {
                push.step = 1u << level;
                push.remodulate = level + 1 == levelCount ? 1u : 0u;
                // Level 0 reads ping (written by the demodulation) and writes pong (set 0), then alternately.
                if (level == 0 && impl_->nlm)
                    impl_->nlm->recordDispatch8x8(cmd, w, rows, &push, sizeof push);
                else
                    impl_->atrous->recordDispatch(cmd, (w + 7) / 8, (rows + 7) / 8, &push, sizeof push, level % 2);
            }
        });
        dev_->instance().throwIfValidationMessages("while denoising");
        // The last level wrote pong (set 0) after an odd number of levels, ping after an even one.
        GpuBuffer& result = *impl_->illum[levelCount % 2 == 1 ? 1 : 0];
        result.download(packed.data(), bytes);
        for (std::uint32_t y = band.y0; y < band.y1; ++y)
            for (std::uint32_t x = 0; x < w; ++x) {
                const float* p = packed.data() + 4 * (std::size_t(y - band.loadY0) * w + x);
                std::copy(p, p + 3, out.rgb.data() + out.offset(x, y));
            }
    }
    lastBands_ = bands.size();
    return out;
}

}  // namespace vkp
