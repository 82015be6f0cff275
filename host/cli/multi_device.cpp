#include "cli/multi_device.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <thread>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/interrupt.h"
#include "render/accum_file.h"
#include "render/aov.h"
#include "cli/denoise_hook.h"
#include "render/merge.h"
#include "render/renderer.h"
#include "vk/device.h"
#include "vk/device_select.h"
#include "vk/instance.h"

namespace vkp {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

std::vector<std::string> deviceSelectors(const std::string& option) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = option.find(',', start);
        out.push_back(option.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

int renderOnDevices(const CliArgs& a, RenderJob& job, const GpuArrays& arrays, std::uint32_t first,
                    const std::vector<std::string>& selectors, Clock::time_point processStart) {
    SessionOptions& o = job.session;
    const char* oneDevice = job.options.adaptive() ? "--adaptive"
                            : !o.checkpoint.empty() ? "--checkpoint"
                            : !a.resume.empty()     ? "--resume"
                            : o.dumpEvery           ? "--dump-every"
                            : !a.reference.empty()  ? "--reference"
                            : !a.statsJson.empty()  ? "--stats-json"
                                                    : nullptr;
    if (oneDevice) throw InputError(std::string("usage: ") + oneDevice + " works on one device, not with --device " + a.device);
    VulkanInstance instance(a.validate);
    std::vector<std::string> names;
    if (selectors.size() == 1 && selectors[0] == "all") {
        for (const DeviceInfo& d : instance.devices())
            if (unusableReason(d).empty()) names.push_back(std::to_string(d.index));
        if (names.empty()) throw DeviceError("--device all: no usable Vulkan device");
    } else {
        for (const std::string& s : selectors)
            if (s.empty() || s == "all") throw InputError("usage: --device wants 'all', an index or a name, or a list of them: got '" + a.device + "'");
        names = selectors;
    }
    std::vector<std::unique_ptr<VulkanDevice>> devices;
    std::vector<std::unique_ptr<Renderer>> renderers;
    const std::shared_ptr<DiskCache> kernelCache = openKernelCache(a);
    for (const std::string& n : names) {
        devices.push_back(std::make_unique<VulkanDevice>(instance, n));
        devices.back()->useKernelCache(kernelCache);
        renderers.push_back(std::make_unique<Renderer>(*devices.back(), arrays, job.options));
    }
    // --denoise: on the first device, once the samples are merged.
    std::unique_ptr<Denoiser> denoiser;
    if (a.denoise) {
        denoiser = std::make_unique<Denoiser>(*devices.front(), denoiseOptions(a.denoiseFilter));
        o.denoiser = denoiseHook(*denoiser);
    }
    const std::uint32_t end = o.spp;
    if (!o.quiet) {
        std::string list;
        for (const auto& d : devices) list += (list.empty() ? "" : ", ") + d->info().name;
        std::fprintf(stderr, "vkpath: %s, %ux%u, samples [%u:%u) on %zu devices: %s\n", a.scene.string().c_str(), arrays.width,
                     arrays.height, first, end, devices.size(), list.c_str());
    }
    if (const int sig = interruptSignal()) return stoppedEarly(sig);
    const std::uint32_t count = std::uint32_t(renderers.size());
    std::uint32_t next = first;
    double perRound = 0.0;  // seconds per sample per device in a round, measured
    double renderSeconds = 0.0;
    double lastProgress = 0.0;
    while (next < end && !interruptSignal()) {
        std::uint32_t n = 1;  // samples per device in this round
        if (perRound > 0.0) n = std::uint32_t(std::clamp(0.5 / perRound, 1.0, 256.0));
        n = std::min<std::uint32_t>(n, (end - next + count - 1) / count);
        if (o.timeLimit > 0.0 && next > first) {
            const double left = o.timeLimit - since(processStart);
            if (left < perRound) break;
            n = std::min<std::uint32_t>(n, std::uint32_t(std::max(1.0, left / std::max(perRound, 1e-9))));
        }
        std::vector<std::exception_ptr> errors(count);
        std::vector<std::thread> threads;
        const auto t0 = Clock::now();
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t from = std::min(end, next + k * n), to = std::min(end, from + n);
            if (from >= to) continue;
            threads.emplace_back([&, k, from, to] {
                try {
                    renderers[k]->jumpTo(from);
                    renderers[k]->addSamples(to - from);
                } catch (...) {
                    errors[k] = std::current_exception();
                }
            });
        }
        for (std::thread& t : threads) t.join();
        for (const std::exception_ptr& e : errors)
            if (e) std::rethrow_exception(e);
        const double dt = since(t0);
        renderSeconds += dt;
        perRound = dt / n;
        next = std::min(end, next + count * n);
        if (!o.quiet && (since(processStart) - lastProgress >= 5.0 || next == end)) {
            lastProgress = since(processStart);
            std::fprintf(stderr, "vkpath: %u/%u spp\n", next - first, end - first);
        }
        if (o.timeLimit > 0.0 && since(processStart) >= o.timeLimit) break;
    }
    const int signal = interruptSignal();
    std::vector<RenderState> states;
    for (auto& r : renderers) states.push_back(r->state());
    std::vector<const RenderState*> ptrs;
    for (const RenderState& s : states) ptrs.push_back(&s);
    const RenderState total = addStates(ptrs, first, next);
    WriteOptions wo;
    wo.exposure = o.exposure;
    wo.metadata = imageMetadata(first, next, signal);
    std::vector<AtomicWrite> more;
    if (!o.partial.empty()) more.push_back({o.partial, [&](std::ostream& out) { encodeAccumFile(out, o.partial, o.key, total); }});
    if (next > first) {
        const PixelSums sums = total.pixelSums();
        const Image image = sums.mean();
        std::unique_ptr<FeatureImages> features;
        if (!total.aov.empty()) features = std::make_unique<FeatureImages>(featureImages(total.aov, total.width, total.height, o.aovFrame));
        wo.layers = aovLayers(o.aovs, features.get(), sums);
        std::unique_ptr<Image> denoised;
        if (o.denoiser && features) {
            const Image variance = sums.varianceOfMean();
            denoised = std::make_unique<Image>(o.denoiser(DenoiseRequest{image, variance, *features}));
            addDenoisedWrites(*denoised, o, wo, more);
        }
        writeImages(image, o.outputs, wo, std::move(more));
    }
    if (signal) std::fprintf(stderr, "vkpath: %s: stopped at sample %u of %u\n", signalName(signal), next, end);
    std::fprintf(stderr, "vkpath: %u spp on %u devices in %.2f s (rendering %.2f s): %.3f M samples/s, %.3f M rays/s, %llu non-finite samples dropped\n",
                 next - first, count, since(processStart), renderSeconds, double(total.samplesTaken) / std::max(renderSeconds, 1e-9) / 1e6,
                 double(total.counters.rays) / std::max(renderSeconds, 1e-9) / 1e6, static_cast<unsigned long long>(total.counters.nonfinite));
    if (next > first) {
        for (const auto& out : o.outputs) std::fprintf(stderr, "vkpath: wrote %s\n", out.string().c_str());
        if (!o.partial.empty()) std::fprintf(stderr, "vkpath: wrote %s\n", o.partial.string().c_str());
    }
    reportKernelCache(a, kernelCache.get());
    return signal ? exitCodeForSignal(signal) : kExitOk;
}

}  // namespace vkp
