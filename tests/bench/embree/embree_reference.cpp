// embree_reference: the benchmark suite's CPU reference (docs/performance.md "The Embree
// reference"). Loads a scene with vkpath's own loader, traces it with Embree 3 on N threads
// (reference_path.h: path tracing with next-event estimation and MIS, as vkpath's `mis`), and
// writes the mean image and a --stats-json with rays/s counted as vkpath counts them.
//
// Usage: embree_reference SCENE [--width W] [--height H] [--spp N] [--time S] [--threads N]
//          [--seed N] [-o IMAGE.pfm|.exr] [--variance IMAGE.pfm|.exr] [--stats-json FILE] [--quiet]
// Exit status: 0 done, 1 bad input (one line on stderr), 2 any other failure.
#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/image.h"
#include "core/image_io.h"
#include "embree_scene.h"
#include "reference_path.h"
#include "reference_scene.h"
#include "scene/gltf.h"

namespace vkp::embree_ref {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kUsage =
    "usage: embree_reference SCENE [--width W] [--height H] [--spp N] [--time S] [--threads N] [--seed N] "
    "[-o IMAGE.pfm|.exr] [--variance IMAGE.pfm|.exr] [--stats-json FILE] [--quiet]";

struct Options {
    std::filesystem::path scene;
    std::optional<std::uint32_t> width, height, spp, seed;
    double seconds = 0.0;        ///< --time: stop starting samples after this many seconds of rendering (0: none)
    std::uint32_t threads = 0;   ///< 0: LP_NUM_THREADS if set (0 there: 1), else every hardware thread (lavapipe's default)
    std::filesystem::path output, variance, stats;
    bool quiet = false;
};

std::uint32_t parseCount(std::string_view flag, std::string_view text, std::uint32_t min) {
    std::uint32_t v = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || v < min)
        throw InputError(std::string(flag) + ": want an integer >= " + std::to_string(min) + ", got '" + std::string(text) + "'");
    return v;
}

Options parseArgs(int argc, char** argv) {
    Options o;
    std::vector<std::string_view> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string_view a = args[i];
        auto value = [&]() -> std::string_view {
            if (i + 1 >= args.size()) throw InputError(std::string(a) + ": needs a value (" + kUsage + ")");
            return args[++i];
        };
        if (a == "--width") o.width = parseCount(a, value(), 1);
        else if (a == "--height") o.height = parseCount(a, value(), 1);
        else if (a == "--spp") o.spp = parseCount(a, value(), 1);
        else if (a == "--seed") o.seed = parseCount(a, value(), 0);
        else if (a == "--threads") o.threads = parseCount(a, value(), 1);
        else if (a == "--time") {
            std::string text(value());
            char* end = nullptr;
            o.seconds = std::strtod(text.c_str(), &end);
            if (end != text.c_str() + text.size() || !(o.seconds > 0.0) || !std::isfinite(o.seconds))
                throw InputError("--time: want seconds > 0, got '" + text + "'");
        } else if (a == "-o" || a == "--output") o.output = value();
        else if (a == "--variance") o.variance = value();
        else if (a == "--stats-json") o.stats = value();
        else if (a == "--quiet") o.quiet = true;
        else if (!a.empty() && a[0] == '-') throw InputError("unknown option '" + std::string(a) + "' (" + kUsage + ")");
        else if (o.scene.empty()) o.scene = a;
        else throw InputError("more than one scene ('" + o.scene.string() + "', '" + std::string(a) + "')");
    }
    if (o.scene.empty()) throw InputError(kUsage);
    if (o.threads == 0) {
        const char* lp = std::getenv("LP_NUM_THREADS");
        // LP_NUM_THREADS=0: lavapipe renders on the calling thread alone, i.e. one thread.
        o.threads = lp && *lp ? std::max(1u, parseCount("LP_NUM_THREADS", lp, 0)) : std::max(1u, std::thread::hardware_concurrency());
    }
    for (const auto& p : {o.output, o.variance})
        if (!p.empty()) imageFormatFromPath(p);  // an unknown extension fails now, not after the render
    return o;
}

Scene load(const Options& o) {
    std::string ext = o.scene.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    Scene s;
    if (ext == ".gltf" || ext == ".glb") {
        GltfOptions g;
        g.width = o.width;
        g.height = o.height;
        s = loadSceneGltf(o.scene, g);
    } else {
        SceneJsonOptions j;
        j.width = o.width;
        j.height = o.height;
        s = loadSceneJson(o.scene, j);
    }
    if (o.width) s.camera.width = *o.width;
    if (o.height) s.camera.height = *o.height;
    if (o.spp) s.render.spp = *o.spp;
    if (o.seed) s.render.seed = *o.seed;
    return s;
}

/// One thread's sums: per pixel R, G, B and their squares (double), and its sample count.
struct Sums {
    std::vector<double> sum, sq;
    std::vector<std::uint32_t> n;
    std::uint64_t rays = 0;
};

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

int run(const Options& o) {
    const auto t0 = Clock::now();
    Scene scene = load(o);
    checkSupported(scene);
    const LightTable lights = buildLightTable(scene);
    const auto t1 = Clock::now();
    EmbreeScene rt(scene, "threads=" + std::to_string(o.threads));
    const auto t2 = Clock::now();
    const PathTracer tracer(scene, rt, lights);

    // Work items: (pass, tile) in order; a thread takes the next one until the spp or the time is
    // reached, so every pixel gets spp samples, or (with --time) spp or one less.
    const std::uint32_t W = scene.camera.width, H = scene.camera.height, tile = 8;
    const std::uint32_t tilesX = (W + tile - 1) / tile, tiles = tilesX * ((H + tile - 1) / tile);
    const std::uint64_t items = std::uint64_t(scene.render.spp) * tiles;
    std::atomic<std::uint64_t> next{0};
    std::vector<Sums> sums(o.threads);
    const auto start = Clock::now();
    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.seconds));
    auto work = [&](Sums& mine) {
        mine.sum.assign(3 * std::size_t(W) * H, 0.0);
        mine.sq.assign(3 * std::size_t(W) * H, 0.0);
        mine.n.assign(std::size_t(W) * H, 0);
        for (;;) {
            if (o.seconds > 0.0 && Clock::now() >= deadline) return;
            const std::uint64_t k = next.fetch_add(1);
            if (k >= items) return;
            const auto pass = std::uint32_t(k / tiles), t = std::uint32_t(k % tiles);
            const std::uint32_t x0 = (t % tilesX) * tile, y0 = (t / tilesX) * tile;
            for (std::uint32_t y = y0; y < std::min(H, y0 + tile); ++y)
                for (std::uint32_t x = x0; x < std::min(W, x0 + tile); ++x) {
                    const glm::vec3 L = tracer.sample(x, y, pass, mine.rays);
                    const std::size_t p = std::size_t(y) * W + x;
                    for (int c = 0; c < 3; ++c) {
                        mine.sum[3 * p + c] += L[c];
                        mine.sq[3 * p + c] += double(L[c]) * L[c];
                    }
                    ++mine.n[p];
                }
        }
    };
    std::vector<std::thread> pool;
    for (std::uint32_t i = 0; i < o.threads; ++i) pool.emplace_back(work, std::ref(sums[i]));
    for (std::thread& th : pool) th.join();
    const auto end = Clock::now();

    // Per pixel: the mean and the variance of that mean; the image mean and its standard error.
    Image mean(W, H), var(W, H);
    std::uint64_t samples = 0, rays = 0;
    std::uint32_t minSpp = ~0u;
    double imageMean[3] = {0, 0, 0}, imageVar[3] = {0, 0, 0};
    for (const Sums& s : sums) rays += s.rays;
    for (std::size_t p = 0; p < std::size_t(W) * H; ++p) {
        std::uint32_t n = 0;
        for (const Sums& s : sums) n += s.n[p];
        samples += n;
        minSpp = std::min(minSpp, n);
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0, sq = 0.0;
            for (const Sums& s : sums) {
                sum += s.sum[3 * p + c];
                sq += s.sq[3 * p + c];
            }
            const double m = n ? sum / n : 0.0;
            const double v = n > 1 ? std::max(0.0, (sq - n * m * m) / (double(n) - 1.0)) / n : 0.0;
            mean.rgb[3 * p + c] = float(m);
            var.rgb[3 * p + c] = float(v);
            imageMean[c] += m;
            imageVar[c] += v;
        }
    }
    if (minSpp == 0) throw InputError("--time " + std::to_string(o.seconds) + ": too short for one sample per pixel");
    const double P = double(W) * H, render = seconds(start, end);
    nlohmann::json st;
    st["renderer"] = "embree_reference";
    st["embree_version"] = embreeVersion();
    st["scene"] = o.scene.string();
    st["width"] = W;
    st["height"] = H;
    st["threads"] = o.threads;
    st["spp"] = minSpp;
    st["samples"] = samples;
    st["rays"] = rays;
    st["max_depth"] = scene.render.maxDepth;
    st["roulette_depth"] = scene.render.rouletteDepth;
    st["seed"] = scene.render.seed;
    st["primitives"] = scene.shapes.size();
    st["lights"] = lights.lights.size();
    st["seconds_scene_load"] = seconds(t0, t1);
    st["seconds_bvh_build"] = seconds(t1, t2);
    st["seconds_render"] = render;
    st["rays_per_second"] = rays / render;
    st["samples_per_second"] = samples / render;
    st["mean"] = {imageMean[0] / P, imageMean[1] / P, imageMean[2] / P};
    st["mean_stderr"] = {std::sqrt(imageVar[0]) / P, std::sqrt(imageVar[1]) / P, std::sqrt(imageVar[2]) / P};
    if (!o.output.empty()) writeImage(mean, o.output);
    if (!o.variance.empty()) writeImage(var, o.variance);
    if (!o.stats.empty()) writeFileAtomic(o.stats, [&](std::ostream& out) { out << st.dump(1) << "\n"; });
    if (!o.quiet)
        std::printf("embree_reference: %s %ux%u, %u spp, %u threads, Embree %s: %.3g rays in %.2f s = %.4g M rays/s "
                    "(load %.2f s, BVH %.2f s); mean %.5g %.5g %.5g\n",
                    o.scene.filename().string().c_str(), W, H, minSpp, o.threads, embreeVersion().c_str(), double(rays), render,
                    rays / render / 1e6, seconds(t0, t1), seconds(t1, t2), imageMean[0] / P, imageMean[1] / P,
                    imageMean[2] / P);
    return 0;
}

}  // namespace
}  // namespace vkp::embree_ref

int main(int argc, char** argv) {
    try {
        return vkp::embree_ref::run(vkp::embree_ref::parseArgs(argc, argv));
    } catch (const vkp::InputError& e) {
        std::fprintf(stderr, "embree_reference: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "embree_reference: %s\n", e.what());
        return 2;
    }
}
