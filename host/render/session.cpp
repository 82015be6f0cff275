#include "render/session.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/errors.h"
#include "core/interrupt.h"
#include "render/accum_file.h"

namespace vkp {

namespace {
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string humanRate(double v) {
    char buf[32];
    if (v >= 1e9) std::snprintf(buf, sizeof buf, "%.2f G", v / 1e9);
    else if (v >= 1e6) std::snprintf(buf, sizeof buf, "%.2f M", v / 1e6);
    else if (v >= 1e3) std::snprintf(buf, sizeof buf, "%.2f k", v / 1e3);
    else std::snprintf(buf, sizeof buf, "%.0f ", v);
    return buf;
}

class Progress {
public:
    Progress(bool quiet, std::uint32_t target) : quiet_(quiet), tty_(isatty(2) == 1), target_(target) {}
    void update(std::uint32_t spp, double renderSeconds, double samples, double rays, double eta, bool force) {
        if (quiet_) return;
        const double now = secondsSince(start_);
        if (!force && now - last_ < (tty_ ? 0.2 : 5.0)) return;
        last_ = now;
        char line[256];
        std::snprintf(line, sizeof line, "%u/%u spp  %ssamples/s  %srays/s  ETA %.1f s", spp, target_,
                      humanRate(samples / std::max(renderSeconds, 1e-9)).c_str(),
                      humanRate(rays / std::max(renderSeconds, 1e-9)).c_str(), std::max(eta, 0.0));
        if (tty_) {
            const int width = 24;
            const int filled = int(width * double(spp) / std::max<std::uint32_t>(target_, 1));
            std::string bar(std::size_t(std::clamp(filled, 0, width)), '#');
            bar.resize(width, '.');
            std::fprintf(stderr, "\r[%s] %s\033[K", bar.c_str(), line);
        } else {
            std::fprintf(stderr, "vkpath: %s\n", line);
        }
        std::fflush(stderr);
    }
    void finish() {
        if (!quiet_ && tty_) std::fprintf(stderr, "\n");
    }

private:
    bool quiet_, tty_;
    std::uint32_t target_;
    Clock::time_point start_ = Clock::now();
    double last_ = -1e9;
};

}  // namespace

std::vector<std::pair<std::string, std::string>> imageMetadata(std::uint32_t first, std::uint32_t next, int signal) {
    std::vector<std::pair<std::string, std::string>> m;
    m.emplace_back("vkpath.version", VKPATH_VERSION);
    m.emplace_back("vkpath.spp", std::to_string(next - first));
    m.emplace_back("vkpath.samples", std::to_string(first) + ":" + std::to_string(next));
    if (signal) m.emplace_back("vkpath.interrupted", signalName(signal));
    return m;
}

std::string dumpFileName(std::uint32_t spp, ImageFormat format) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "frame-%06u%s", spp, imageFormatExtension(format));
    return buf;
}

namespace {
/// The smallest power of two strictly greater than n (n < 2^31).
std::uint32_t nextPowerOfTwoAbove(std::uint32_t n) {
    std::uint32_t p = 1;
    while (p <= n) p <<= 1;
    return p;
}

/// The image of the render at one moment, with what its outputs need besides.
struct Frame {
    PixelSums sums;
    Image image;
    std::unique_ptr<FeatureImages> features;  ///< with RenderOptions::aov
    std::unique_ptr<Image> denoised;
    double denoiseSeconds = 0.0;
};

/// Dumps at `spp`: the image in every dump format, EXR with the AOV layers; the denoised image
/// beside it when there is one.
void writeDumps(const Frame& fr, const SessionOptions& o, std::uint32_t spp) {
    std::filesystem::create_directories(o.dumpDir);
    for (ImageFormat f : o.dumpFormats) {
        WriteOptions wo;
        wo.exposure = o.exposure;
        if (f == ImageFormat::Exr) wo.layers = aovLayers(o.aovs, fr.features.get(), fr.sums);
        const std::filesystem::path p = o.dumpDir / dumpFileName(spp, f);
        writeImage(fr.image, p, wo);
        if (fr.denoised) {
            wo.layers.clear();
            writeImage(*fr.denoised, denoisedPath(p), wo);
        }
    }
}
}  // namespace

std::filesystem::path denoisedPath(const std::filesystem::path& path) {
    std::filesystem::path p = path;
    p.replace_filename(path.stem().string() + ".denoised" + path.extension().string());
    return p;
}

std::vector<std::filesystem::path> denoisedOutputs(const SessionOptions& o) {
    if (!o.denoiseOutput.empty()) return {o.denoiseOutput};
    std::vector<std::filesystem::path> paths;
    for (const std::filesystem::path& p : o.outputs) paths.push_back(denoisedPath(p));
    return paths;
}

void addDenoisedWrites(const Image& denoised, const SessionOptions& o, WriteOptions options, std::vector<AtomicWrite>& writes) {
    options.layers.clear();
    options.metadata.emplace_back("vkpath.denoised", "yes: biased (the raw image is not)");
    for (const std::filesystem::path& p : denoisedOutputs(o))
        writes.push_back({p, [&denoised, options, p](std::ostream& out) {
                              encodeImage(denoised, imageFormatFromPath(p), options, out, p.string());
                          }});
}

SessionResult runSession(Renderer& renderer, const SessionOptions& o, Clock::time_point processStart) {
    SessionResult res;
    const std::uint32_t first = renderer.firstSample();
    Progress progress(o.quiet, o.spp - std::min(o.spp, first));
    const std::uint64_t pixels = renderer.readSums().sum.size() / 4;
    res.pixels = pixels;
    const bool powersOfTwo = o.onCheckpoint && o.checkpointPowersOfTwo && o.dumpEvery == 0;
    std::uint32_t lastCheckpoint = 0;
    const bool kernelAovs = renderer.features().aov;
    if (o.denoiser && !kernelAovs) throw std::logic_error("runSession: the denoiser needs the feature images (RenderOptions::aov)");
    double denoiseTotal = 0.0;  // seconds spent denoising at checkpoints: not in the log's wall time
    // Reads the image back (with its sums, feature images and, when `denoise`, the denoised
    // image), hands it to onCheckpoint and returns it for dumps or outputs. `state`: the render's
    // state when already read back (the image is then made from it).
    auto checkpoint = [&](std::uint32_t spp, const RenderState* state, bool denoise) {
        const auto t0 = Clock::now();
        Frame fr;
        fr.sums = state ? state->pixelSums() : renderer.readSums();
        fr.image = fr.sums.mean();
        if (kernelAovs) {
            const std::vector<float> aov = state ? state->aov : renderer.readAovSums();
            fr.features = std::make_unique<FeatureImages>(featureImages(aov, fr.sums.width, fr.sums.height, o.aovFrame));
        }
        const double at = secondsSince(processStart) - denoiseTotal;
        if (denoise && o.denoiser) {
            const auto t1 = Clock::now();
            const Image variance = fr.sums.varianceOfMean();
            fr.denoised = std::make_unique<Image>(o.denoiser(DenoiseRequest{fr.image, variance, *fr.features}));
            fr.denoiseSeconds = secondsSince(t1);
            denoiseTotal += fr.denoiseSeconds;
        }
        if (o.onCheckpoint && spp != lastCheckpoint) {
            o.onCheckpoint(Checkpoint{spp, at, fr.image, fr.denoised.get(), fr.denoiseSeconds});
            lastCheckpoint = spp;
            ++res.checkpoints;
        }
        res.checkpointSeconds += secondsSince(t0);
        return fr;
    };
    double perSample = 0.0;  // seconds per spp, measured
    int batches = 0;
    constexpr double kBatchSeconds = 0.5;  // aim for a submit this long: progress stays live
    auto lastStateWrite = Clock::now();
    // With adaptive sampling the render also ends when every pixel has converged.
    while (renderer.samplesDone() < o.spp && renderer.activePixels() > 0 && !interruptSignal()) {
        const std::uint32_t done = renderer.samplesDone();
        std::uint32_t n = 1;  // the first batch is one sample: time to first pixel, JIT included
        if (perSample > 0.0) n = std::uint32_t(std::clamp(kBatchSeconds / perSample, 1.0, 256.0));
        n = std::min(n, o.spp - done);
        if (o.dumpEvery) n = std::min(n, o.dumpEvery - done % o.dumpEvery);
        if (powersOfTwo && done < (1u << 30)) n = std::min(n, nextPowerOfTwoAbove(done) - done);
        if (o.timeLimit > 0.0 && done > 0) {
            const double left = o.timeLimit - secondsSince(processStart);
            if (left <= 0.0) break;
            const double fit = std::floor(left / std::max(perSample, 1e-9));
            if (fit < 1.0) break;
            n = std::min<std::uint32_t>(n, std::uint32_t(std::min(fit, 1e9)));
        }
        const auto t0 = Clock::now();
        renderer.addSamples(n);
        const double dt = secondsSince(t0);
        if (batches == 0) {
            res.firstBatchSeconds = dt;
            res.firstSampleAt = secondsSince(processStart);
        }
        res.renderSeconds += dt;
        // The first batch includes the shader JIT: trust it only until the second batch is measured.
        const double measured = dt / n;
        perSample = batches < 2 ? measured : 0.5 * perSample + 0.5 * measured;
        ++batches;
        const std::uint32_t now = renderer.samplesDone();
        const RenderCounters c = renderer.counters();
        if (batches == 1) res.firstBatchRays = c.rays;
        res.longestDispatchSeconds = renderer.longestDispatchSeconds();
        res.pixelsPerInvocation = renderer.maxPixelsPerInvocation();
        const double eta = double(o.spp - now) * perSample;
        progress.update(now - first, res.renderSeconds, double(renderer.samplesTaken()), double(c.rays), eta,
                        now == o.spp || renderer.activePixels() == 0);
        if (!o.checkpoint.empty() && now < o.spp && secondsSince(lastStateWrite) >= o.checkpointEvery && !interruptSignal()) {
            const auto t1 = Clock::now();
            writeAccumFile(o.checkpoint, o.key, renderer.state());
            ++res.stateWrites;
            lastStateWrite = Clock::now();
            res.checkpointSeconds += secondsSince(t1);
        }
        if (now < o.spp && !interruptSignal()) {
            const bool dump = o.dumpEvery && now % o.dumpEvery == 0;
            const bool power = powersOfTwo && (now & (now - 1)) == 0;
            if (dump || power) {
                const Frame fr = checkpoint(now, nullptr, (dump && o.denoiseDumps) || o.denoiseCheckpoints);
                if (dump) {
                    const auto t1 = Clock::now();
                    writeDumps(fr, o, now);
                    res.outputSeconds += secondsSince(t1);
                }
            }
        }
        if (o.timeLimit > 0.0 && secondsSince(processStart) >= o.timeLimit) break;
    }
    progress.finish();
    res.signal = interruptSignal();
    // The partial and the checkpoint need the state; read the device once and make the image from it.
    std::shared_ptr<const RenderState> state;
    if (!o.partial.empty() || !o.checkpoint.empty()) state = std::make_shared<const RenderState>(renderer.state());
    const Frame fr = checkpoint(renderer.samplesDone(), state.get(), o.denoiser != nullptr);
    const Image& img = fr.image;
    for (std::size_t i = 0; i < img.pixelCount(); ++i)
        res.nonfinitePixels += !(std::isfinite(img.rgb[3 * i]) && std::isfinite(img.rgb[3 * i + 1]) && std::isfinite(img.rgb[3 * i + 2]));
    const auto t1 = Clock::now();
    if (o.dumpEvery && !res.signal) writeDumps(fr, o, renderer.samplesDone());
    // The outputs, the partial and the checkpoint: all or none.
    std::vector<AtomicWrite> states;
    for (const std::filesystem::path& p : {o.partial, o.checkpoint})
        if (!p.empty()) states.push_back({p, [state, &o, p](std::ostream& out) { encodeAccumFile(out, p, o.key, *state); }});
    res.stateWrites += !o.checkpoint.empty();
    WriteOptions wo;
    wo.exposure = o.exposure;
    wo.metadata = imageMetadata(first, renderer.samplesDone(), res.signal);
    // The denoised image: beside every output, or where --denoise-output says; never a raw one.
    if (fr.denoised) addDenoisedWrites(*fr.denoised, o, wo, states);
    wo.layers = aovLayers(o.aovs, fr.features.get(), fr.sums);
    writeImages(img, o.outputs, wo, std::move(states));
    res.outputSeconds += secondsSince(t1);
    res.denoiseSeconds = fr.denoiseSeconds;
    res.firstSample = first;
    res.spp = renderer.samplesDone();
    res.samplesTaken = renderer.samplesTaken();
    res.activePixels = renderer.activePixels();
    res.counters = renderer.counters();
    res.seconds = secondsSince(processStart);
    return res;
}

}  // namespace vkp
