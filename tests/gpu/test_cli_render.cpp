// The vkpath binary end to end on the device: outputs, progressive dumps, --time, info, devices,
// and the exit code for a device that does not exist. Validation layer on (--validate).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/disk_cache.h"
#include "core/image_io.h"
#include "gpu_env.h"
#include "render/gpu_arrays.h"
#include "render/workgroup.h"
#include "vk/pipeline_cache_data.h"
#include "image_checks.h"
#include "run_process.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

struct CliRender : ::testing::Test {
    std::filesystem::path dir = scratchDir("cli_render");
    ProcessResult run(const std::vector<std::string>& args) { return runProcess(vkpathBinary(), args, dir); }
    std::string scene(const char* name) { return (scenesDir() / name).string(); }
};

/// The path of `name` on PATH, or empty.
std::filesystem::path onPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "";
    for (std::size_t start = 0; start <= dirs.size();) {
        const std::size_t colon = std::min(dirs.find(':', start), dirs.size());
        const std::filesystem::path p = std::filesystem::path(dirs.substr(start, colon - start)) / name;
        if (!dirs.substr(start, colon - start).empty() && access(p.c_str(), X_OK) == 0) return p;
        start = colon + 1;
    }
    return {};
}

// Feature images: layers of the EXR (read back here and by OpenImageIO's oiiotool, which reads
// with the OpenEXR library), the same values as files beside the PNG, and one usage line for a bad list.
TEST_F(CliRender, FeatureImagesAreLayersOfTheExrAndFilesBesideThePng) {
    VKP_REQUIRE_DEVICE(dev);
    for (const char* f : {"f.exr", "f.png", "f.albedo.pfm", "f.spp.pfm"}) std::filesystem::remove(dir / f);
    const ProcessResult r = run({"render", scene("cornell-book3.json"), "--validate", "--spp", "4", "--width", "24",
                                 "--height", "16", "--aov", "all", "-o", "f.exr", "-o", "f.png", "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* layer : {"albedo", "normal", "depth", "position", "emission", "variance", "spp"}) {
        const Image inExr = readImageLayer(dir / "f.exr", layer);
        const Image beside = readImage(dir / (std::string("f.") + layer + ".pfm"));
        EXPECT_EQ(inExr.width, 24u);
        EXPECT_EQ(inExr.rgb, beside.rgb) << layer;
    }
    const Image spp = readImageLayer(dir / "f.exr", "spp");
    for (float v : spp.rgb) EXPECT_EQ(v, 4.0f);
    const Image albedo = readImageLayer(dir / "f.exr", "albedo");
    EXPECT_GT(*std::max_element(albedo.rgb.begin(), albedo.rgb.end()), 0.5f);
    EXPECT_FALSE(std::filesystem::exists(dir / "f.albedo.png"));

    const ProcessResult bad = run({"render", scene("cornell-book3.json"), "--aov", "albedo,shadows", "-o", "bad.exr"});
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("--aov: unknown AOV 'shadows'"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr"));

    // A standard tool reads the layers. That is a property of the file, not of the device, so
    // tools/gpu-check.sh (a GPU machine may have no package archive) lets it go where oiiotool is
    // missing (VKPATH_OIIOTOOL_OPTIONAL=1); elsewhere its absence skips, which fails in CI.
    const std::filesystem::path oiiotool = onPath("oiiotool");
    if (oiiotool.empty() && std::getenv("VKPATH_OIIOTOOL_OPTIONAL")) {
        std::printf("oiiotool is not installed: the EXR layers were not read by it here\n");
        return;
    }
    if (oiiotool.empty()) GTEST_SKIP() << "oiiotool (Debian's openimageio-tools, tools/deps.sh) is not installed";
    const ProcessResult info = runProcess(oiiotool, {"--info", "-v", "f.exr"}, dir);
    ASSERT_EQ(info.exitCode, 0) << info.err;
    for (const char* channel : {"albedo.R", "albedo.B", "normal.X", "normal.Z", "depth.Z", "position.Y", "variance.G", "spp.V"})
        EXPECT_NE(info.out.find(channel), std::string::npos) << channel << " in " << info.out;
    EXPECT_NE(info.out.find("20 channel"), std::string::npos) << info.out;
    // oiiotool pulls the albedo layer out as an image of its own: the same numbers.
    std::filesystem::remove(dir / "albedo-only.exr");
    const ProcessResult ch = runProcess(oiiotool, {"f.exr", "--ch", "albedo.R,albedo.G,albedo.B", "--chnames", "R,G,B", "-o", "albedo-only.exr"}, dir);
    ASSERT_EQ(ch.exitCode, 0) << ch.err;
    EXPECT_EQ(readImage(dir / "albedo-only.exr").rgb, albedo.rgb);
}

// --denoise: the raw image is written as without it (bit for bit), the denoised one beside it or
// where --denoise-output says, and the error log gains the denoised image's columns; the denoised
// image is closer to a converged one than the raw image at the same spp.
TEST_F(CliRender, DenoiseWritesBesideTheRawImageAndNeverOverIt) {
    VKP_REQUIRE_DEVICE(dev);
    for (const char* f : {"d.pfm", "d.denoised.pfm", "plain.pfm", "elsewhere.exr", "ref.pfm", "d.csv", "a.pfm", "a.denoised.pfm"})
        std::filesystem::remove(dir / f);
    const std::vector<std::string> common = {"render", scene("cornell-classic.json"), "--width", "48", "--height", "48", "--quiet"};
    auto with = [&](std::vector<std::string> more) {
        std::vector<std::string> args = common;
        args.insert(args.end(), more.begin(), more.end());
        return run(args);
    };
    ASSERT_EQ(with({"--spp", "1024", "-o", "ref.pfm"}).exitCode, 0);
    const ProcessResult r = with({"--validate", "--spp", "16", "-o", "d.pfm", "--denoise", "--reference", "ref.pfm", "--error-log", "d.csv"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // The raw image is untouched. `--denoise` renders the feature images, so the plain render asks
    // for one too: the same kernel variant, the same bits on any device (with and without feature
    // images the sums are compared in GpuAov, up to rounding where the device rounds otherwise).
    ASSERT_EQ(with({"--spp", "16", "-o", "plain.pfm", "--aov", "albedo"}).exitCode, 0);
    EXPECT_EQ(readImage(dir / "d.pfm").rgb, readImage(dir / "plain.pfm").rgb);
    const Image ref = readImage(dir / "ref.pfm"), raw = readImage(dir / "d.pfm"), den = readImage(dir / "d.denoised.pfm");
    auto relmse = [&](const Image& x) {
        double e = 0;
        for (std::size_t i = 0; i < x.rgb.size(); ++i) e += std::pow(x.rgb[i] - ref.rgb[i], 2) / (ref.rgb[i] * ref.rgb[i] + 0.01);
        return e / double(x.rgb.size());
    };
    EXPECT_LT(relmse(den), 0.5 * relmse(raw)) << relmse(den) << " vs " << relmse(raw);
    // --denoise-filter atrous: the a-trous filter alone, another image, also far closer than raw.
    ASSERT_EQ(with({"--spp", "16", "-o", "a.pfm", "--denoise", "--denoise-filter", "atrous"}).exitCode, 0);
    const Image atrous = readImage(dir / "a.denoised.pfm");
    EXPECT_LT(relmse(atrous), 0.5 * relmse(raw)) << relmse(atrous) << " vs " << relmse(raw);
    EXPECT_NE(atrous.rgb, den.rgb);
    std::ifstream log(dir / "d.csv");
    std::string header, row, last;
    std::getline(log, header);
    EXPECT_EQ(header, "spp,seconds,rmse,relmse,mean_r,mean_g,mean_b,rmse_denoised,relmse_denoised,denoise_seconds");
    while (std::getline(log, row)) last = row;
    EXPECT_EQ(last.rfind("16,", 0), 0u) << last;
    const ProcessResult o = with({"--spp", "4", "-o", "x.png", "--denoise", "--denoise-output", "elsewhere.exr"});
    ASSERT_EQ(o.exitCode, 0) << o.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "elsewhere.exr"));
    EXPECT_FALSE(std::filesystem::exists(dir / "x.denoised.png"));
}

TEST_F(CliRender, WritesEveryRequestedFormat) {
    VKP_REQUIRE_DEVICE(dev);
    for (const char* f : {"o.png", "o.exr", "o.pfm", "o.hdr"}) std::filesystem::remove(dir / f);
    const ProcessResult r = run({"render", scene("cornell-book3.json"), "--validate", "--spp", "2", "--width", "40",
                                 "--height", "30", "-o", "o.png", "-o", "o.exr", "-o", "o.pfm", "-o", "o.hdr"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : {"o.png", "o.exr", "o.pfm", "o.hdr"}) EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
    const Image img = readImage(dir / "o.pfm");
    EXPECT_EQ(img.width, 40u);
    EXPECT_EQ(img.height, 30u);
    EXPECT_NE(r.err.find("2 spp"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("0 non-finite samples dropped"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("rays/s"), std::string::npos) << r.err;
}

TEST_F(CliRender, ProgressiveDumps) {
    VKP_REQUIRE_DEVICE(dev);
    std::filesystem::remove_all(dir / "frames");
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--validate", "--spp", "6", "--width", "16",
                                 "--height", "16", "--dump-every", "2", "--dump-dir", "frames", "--dump-format", "pfm",
                                 "-o", "final.pfm", "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : {"frame-000002.png", "frame-000004.png", "frame-000006.png", "frame-000002.pfm",
                          "frame-000006.pfm"})
        EXPECT_TRUE(std::filesystem::exists(dir / "frames" / f)) << f;
    // The last dump is the final image.
    const Image last = readImage(dir / "frames" / "frame-000006.pfm");
    const Image fin = readImage(dir / "final.pfm");
    EXPECT_TRUE(litAndNotConstant(fin, "final.pfm"));  // two empty images would be equal
    EXPECT_EQ(last.rgb, fin.rgb);
    // A later frame differs from an earlier one (more samples).
    EXPECT_NE(readImage(dir / "frames" / "frame-000002.pfm").rgb, fin.rgb);
}

// --time stops the render by the clock, not by --spp: far fewer samples than asked, at least one,
// and the wall time (counted from process start, --stats-json seconds_total) near the limit. The
// session ends before a batch that would not fit in the time left (batches aim at 0.5 s), so the
// run may end a little before 3 s; the upper bound allows a loaded machine's JIT, a last batch
// and the writing of the outputs: a functional check that the limit works, not a measurement.
TEST_F(CliRender, TimeLimitStopsBeforeSpp) {
    VKP_REQUIRE_DEVICE(dev);
    std::filesystem::remove(dir / "t.json");
    // 16M spp (the most --spp takes): out of reach in 3 s on a fast GPU too (at most 8 samples per
    // dispatch: 2M dispatches), where 1M might not be.
    const ProcessResult r = run({"render", scene("cornell-book3.json"), "--spp", "16000000", "--time", "3", "--width",
                                 "32", "--height", "32", "-o", "t.png", "--stats-json", "t.json"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "t.png"));
    std::ifstream f(dir / "t.json");
    const nlohmann::json j = nlohmann::json::parse(f);
    const std::uint32_t spp = j["spp"];
    const double total = j["seconds_total"];
    EXPECT_GE(spp, 1u);
    EXPECT_LT(spp, 16000000u) << "the render reached --spp: --time did not stop it";
    EXPECT_EQ(j["time_limit"].get<double>(), 3.0);
    // The workgroup the kernel ran with: no --workgroup, so the device's (render/workgroup.h).
    const glm::uvec2 wg = autoWorkgroup(deviceLimits(dev.info()));
    EXPECT_EQ(j["workgroup"].get<std::string>(), std::to_string(wg.x) + "x" + std::to_string(wg.y));
    EXPECT_GE(total, 2.0) << "stopped well before the time limit";
    EXPECT_LE(total, 15.0) << "ran far beyond the time limit";
    EXPECT_NE(r.err.find(std::to_string(spp) + " spp in"), std::string::npos) << r.err;
}

TEST_F(CliRender, InfoNamesCountsBvhAndVariant) {
    const ProcessResult r = run({"info", scene("cornell-book3.json")});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("13 (1 spheres, 12 quads, 0 triangles)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("2 sampled objects (1 emitting)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("SAH cost"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("materials:lambertian+dielectric+emission"), std::string::npos) << r.out;
}

// `vkpath info` makes the render's own check against the chosen device's limits (fitProblem,
// planBands): a small image fits in one band, a 16384 x 16384 one needs several bands of rows on
// lavapipe (or is refused with the one line a render would print), a --device that names none fails.
TEST_F(CliRender, InfoChecksTheRenderAgainstTheDevice) {
    VKP_REQUIRE_DEVICE(dev);
    ProcessResult r = run({"info", scene("cornell-book3.json"), "--validate"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("device       " + dev.info().name + ": fits (1 band of rows"), std::string::npos) << r.out;
    const glm::uvec2 wg = autoWorkgroup(deviceLimits(dev.info()));
    EXPECT_NE(r.out.find("workgroup " + std::to_string(wg.x) + "x" + std::to_string(wg.y) + " (auto), subgroups of " +
                         std::to_string(dev.info().subgroupSize) + " lanes"),
              std::string::npos)
        << r.out;
    r = run({"info", scene("cornell-book3.json"), "--width", "16384", "--height", "16384"});
    if (r.exitCode == 0) {
        EXPECT_NE(r.out.find(": fits ("), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("(1 band of rows"), std::string::npos) << "16384^2 pixels cannot be one band: " << r.out;
    } else {
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.out.find("does not fit"), std::string::npos) << r.out;
    }
    r = run({"info", scene("cornell-book3.json"), "--device", "no-such-gpu-name"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
}

// Light from the command line, exactly: a pixel that sees only the background is the background;
// radiance is linear, so a map at strength 2 gives twice the image of strength 1 bit for bit (the
// sampling density is normalised, Russian roulette follows the throughput); --environment with the
// scene's own map, strength and rotation is the scene's own render; a rotation changes it.
TEST_F(CliRender, BackgroundAndEnvironmentFromTheCommandLine) {
    VKP_REQUIRE_DEVICE(dev);
    const std::string noLight = scene("gltf/no-camera.gltf");
    // render({SCENE, options...}, OUT): the scene first, then its options.
    auto render = [&](std::vector<std::string> sceneAndOptions, const char* out) {
        std::vector<std::string> args = {"render"};
        args.insert(args.end(), sceneAndOptions.begin(), sceneAndOptions.end());
        args.insert(args.end(), {"--validate", "--spp", "8", "--width", "32", "--height", "24", "--quiet", "-o", out});
        const ProcessResult r = run(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return readImage(dir / out);
    };
    const Image black = render({noLight}, "black.pfm");
    for (float x : black.rgb) ASSERT_EQ(x, 0.0f);
    const Image bg = render({noLight, "--background", "0.25,0.5,1"}, "bg.pfm");
    EXPECT_TRUE(litAndNotConstant(bg, "bg.pfm"));
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(bg.rgb[c], (std::array<float, 3>{0.25f, 0.5f, 1.0f}[c])) << "corner pixel, channel " << c;
    const std::string sky = (scenesDir() / "env" / "sky.hdr").string();
    const Image one = render({noLight, "--environment", sky}, "env1.pfm");
    const Image two = render({noLight, "--environment", sky, "--environment-strength", "2"}, "env2.pfm");
    EXPECT_TRUE(litAndNotConstant(one, "env1.pfm"));
    ASSERT_EQ(one.rgb.size(), two.rgb.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < one.rgb.size(); ++i) differ += two.rgb[i] != 2.0f * one.rgb[i];
    EXPECT_EQ(differ, 0u) << "strength 2 must double every pixel exactly";
    const Image own = render({scene("env-sky.json")}, "own.pfm");
    EXPECT_EQ(render({scene("env-sky.json"), "--environment", sky}, "same.pfm").rgb, own.rgb);
    EXPECT_EQ(render({scene("env-sky.json"), "--environment-rotate", "0"}, "rot0.pfm").rgb, own.rgb);
    EXPECT_NE(render({scene("env-sky.json"), "--environment-rotate", "90"}, "rot90.pfm").rgb, own.rgb);
    const Image twice = render({scene("env-sky.json"), "--environment-strength", "2"}, "own2.pfm");
    differ = 0;
    for (std::size_t i = 0; i < own.rgb.size(); ++i) differ += twice.rgb[i] != 2.0f * own.rgb[i];
    EXPECT_EQ(differ, 0u) << "the scene's own map at strength 2";
}

TEST_F(CliRender, DevicesAndBadDeviceSelection) {
    VKP_REQUIRE_DEVICE(dev);
    ProcessResult r = run({"devices", "--validate"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find(dev.info().name), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(default)"), std::string::npos) << r.out;
    // How the host reaches the device's buffers (docs/design.md "Buffer memory"): one of the two.
    const bool mapped = r.out.find("buffers mapped (unified memory)") != std::string::npos;
    const bool staged = r.out.find("buffers through staging copies") != std::string::npos;
    EXPECT_TRUE(mapped != staged) << r.out;
    EXPECT_EQ(mapped, dev.info().mappedBuffers) << r.out;
    r = run({"render", scene("cornell-book3.json"), "--device", "99", "-o", "never.png"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "never.png"));
    r = run({"render", scene("cornell-book3.json"), "--device", "no-such-gpu-name", "-o", "never.png"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
}


// Issue 15, defect 5: samples whose sums (of squares) could overflow float are dropped and counted,
// never added: a point light of 1e16 W sr^-1 a millimetre above a floor gives the floor below it
// samples of about 1e21 (their squares are infinite in float). The image stays finite, below
// MAX_SAMPLE_RADIANCE, and the summary counts the dropped samples.
TEST_F(CliRender, OverflowingSamplesAreDroppedAndCounted) {
    VKP_REQUIRE_DEVICE(dev);
    std::ofstream(dir / "hot.json") << R"({
      "camera": {"lookfrom": [0, 1, 0], "lookat": [0, 0, 0], "vup": [0, 0, -1], "vfov": 60, "width": 16, "height": 16},
      "render": {"spp": 4, "max_depth": 4},
      "materials": {"floor": {"type": "lambertian", "albedo": [0.8, 0.8, 0.8]}},
      "objects": [
        {"type": "quad", "Q": [-1, 0, 1], "u": [2, 0, 0], "v": [0, 0, -2], "material": "floor"},
        {"type": "point_light", "position": [0, 0.001, 0], "intensity": [1e16, 1e16, 1e16]}
      ]})";
    const ProcessResult r = run({"render", "hot.json", "--validate", "-o", "hot.pfm"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image img = readImage(dir / "hot.pfm");
    float worst = 0.0f;
    for (float x : img.rgb) {
        ASSERT_TRUE(std::isfinite(x));
        worst = std::max(worst, x);
    }
    EXPECT_LE(worst, 4e15f);
    EXPECT_GT(worst, 0.0f);  // the rest of the floor is lit
    EXPECT_EQ(r.err.find(" 0 non-finite samples dropped"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("pixels of the image are not finite"), std::string::npos) << r.err;
}

// The kernel cache (core/disk_cache.h, docs/design.md "The kernel cache"): the first render
// stores the specialized kernel, the second loads it; a damaged entry, a FIFO in its place or an
// entry of pipeline-cache data handed back to the driver change nothing in the image (bit for
// bit) and fail nothing; --cache-dir none and VKPATH_CACHE_DIR choose the folder.
TEST_F(CliRender, KernelCacheHitsOnTheSecondRunAndDamageChangesNothing) {
    VKP_REQUIRE_DEVICE(dev);
    namespace fs = std::filesystem;
    const fs::path cache = dir / "kcache";
    fs::remove_all(cache);
    struct Run {
        ProcessResult r;
        nlohmann::json stats;
        std::vector<float> rgb;
    };
    auto render = [&](const std::string& name, const std::vector<std::string>& extra, const std::string& env = "") {
        std::vector<std::string> args = {"render", scene("cornell-book3.json"), "--validate", "--spp", "4", "--width", "24",
                                         "--height", "16", "-o", name + ".pfm", "--stats-json", name + ".json"};
        args.insert(args.end(), extra.begin(), extra.end());
        Run out;
        out.r = runProcess(vkpathBinary(), args, dir, env);
        if (out.r.exitCode != 0) return out;
        std::ifstream f(dir / (name + ".json"));
        out.stats = nlohmann::json::parse(f);
        out.rgb = readImage(dir / (name + ".pfm")).rgb;
        return out;
    };
    auto spirvEntries = [&] {
        std::vector<fs::path> v;
        if (fs::exists(cache))
            for (const auto& e : fs::directory_iterator(cache))
                if (e.path().filename().string().rfind("spirv-", 0) == 0) v.push_back(e.path());
        return v;
    };

    const Run first = render("first", {"--cache-dir", "kcache", "--quiet"});
    ASSERT_EQ(first.r.exitCode, 0) << first.r.err;
    const nlohmann::json& k1 = first.stats["kernel_cache"];
    EXPECT_EQ(k1["dir"], "kcache");
    EXPECT_EQ(k1["hits"], 0);
    EXPECT_GE(k1["stores"].get<int>(), 1) << k1;
    EXPECT_EQ(k1["failed_stores"], 0);
    const std::vector<fs::path> entries = spirvEntries();
    ASSERT_EQ(entries.size(), 1u);  // one variant: one specialized kernel

    const Run second = render("second", {"--cache-dir", "kcache", "--quiet"});
    ASSERT_EQ(second.r.exitCode, 0) << second.r.err;
    EXPECT_GE(second.stats["kernel_cache"]["hits"].get<int>(), 1) << second.stats["kernel_cache"];
    EXPECT_EQ(second.stats["kernel_cache"]["stores"], 0) << second.stats["kernel_cache"];
    EXPECT_EQ(second.rgb, first.rgb);

    // A flipped byte in the stored kernel: a miss, compiled again, stored again, the same image.
    {
        std::fstream f(entries[0], std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(-1, std::ios::end);
        char c = 0;
        f.read(&c, 1);
        f.seekp(-1, std::ios::end);
        c = char(c ^ 0x40);
        f.write(&c, 1);
    }
    const Run damaged = render("damaged", {"--cache-dir", "kcache", "--quiet"});
    ASSERT_EQ(damaged.r.exitCode, 0) << damaged.r.err;
    EXPECT_EQ(damaged.stats["kernel_cache"]["hits"], 0) << damaged.stats["kernel_cache"];
    EXPECT_GE(damaged.stats["kernel_cache"]["stores"].get<int>(), 1) << damaged.stats["kernel_cache"];
    EXPECT_EQ(damaged.rgb, first.rgb);
    EXPECT_GE(render("mended", {"--cache-dir", "kcache", "--quiet"}).stats["kernel_cache"]["hits"].get<int>(), 1);

    // A FIFO where the entry was: no hang, the same image, and (without --quiet, the folder chosen)
    // one warning that the entry could not be written.
    fs::remove(entries[0]);
    ASSERT_EQ(::mkfifo(entries[0].c_str(), 0600), 0);
    const Run fifo = render("fifo", {"--cache-dir", "kcache"});
    ASSERT_EQ(fifo.r.exitCode, 0) << fifo.r.err;
    EXPECT_EQ(fifo.rgb, first.rgb);
    EXPECT_EQ(fifo.stats["kernel_cache"]["failed_stores"], 1) << fifo.stats["kernel_cache"];
    EXPECT_NE(fifo.r.err.find("vkpath: warning: the kernel cache could not be written: "), std::string::npos) << fifo.r.err;
    fs::remove(entries[0]);

    // Pipeline-cache data of this device and driver (a valid header, a payload no driver wrote) is
    // handed to vkCreatePipelineCache, under the validation layer; the image is the same.
    const vk::PhysicalDeviceProperties props = dev.physical().getProperties();
    PipelineCacheIdentity id;
    id.vendorId = props.vendorID;
    id.deviceId = props.deviceID;
    id.driverVersion = props.driverVersion;
    std::memcpy(id.uuid, props.pipelineCacheUUID.data(), 16);
    std::string data(32 + 64, '\x5a');
    const std::uint32_t head[4] = {32u, 1u, props.vendorID, props.deviceID};
    std::memcpy(data.data(), head, 16);
    std::memcpy(data.data() + 16, id.uuid, 16);
    ASSERT_TRUE(DiskCache(cache).store("pipelines", pipelineCacheKey(id), data));
    const Run handed = render("handed", {"--cache-dir", "kcache", "--quiet"});
    ASSERT_EQ(handed.r.exitCode, 0) << handed.r.err;
    EXPECT_EQ(handed.stats["kernel_cache"]["pipeline_cache_bytes_loaded"], data.size()) << handed.stats["kernel_cache"];
    EXPECT_EQ(handed.rgb, first.rgb);
    // Data whose header names another pipelineCacheUUID (another driver build), stored under this
    // device's key: not handed over.
    data[16] = char(data[16] ^ 1);
    fs::remove_all(cache);
    ASSERT_TRUE(DiskCache(cache).store("pipelines", pipelineCacheKey(id), data));
    const Run foreign = render("foreign", {"--cache-dir", "kcache", "--quiet"});
    ASSERT_EQ(foreign.r.exitCode, 0) << foreign.r.err;
    EXPECT_EQ(foreign.stats["kernel_cache"]["pipeline_cache_bytes_loaded"], 0) << foreign.stats["kernel_cache"];

    // --cache-dir none: no cache; VKPATH_CACHE_DIR: the folder when no --cache-dir is given.
    fs::remove_all(cache);
    const Run none = render("none", {"--cache-dir", "none", "--quiet"}, "VKPATH_CACHE_DIR=kcache");
    ASSERT_EQ(none.r.exitCode, 0) << none.r.err;
    EXPECT_TRUE(none.stats["kernel_cache"].is_null());
    EXPECT_FALSE(fs::exists(cache));
    EXPECT_EQ(none.rgb, first.rgb);
    const Run fromEnv = render("env", {"--quiet"}, "VKPATH_CACHE_DIR=kcache");
    ASSERT_EQ(fromEnv.r.exitCode, 0) << fromEnv.r.err;
    EXPECT_EQ(fromEnv.stats["kernel_cache"]["dir"], "kcache");
    EXPECT_EQ(spirvEntries().size(), 1u);
}

}  // namespace
}  // namespace vkp::test
