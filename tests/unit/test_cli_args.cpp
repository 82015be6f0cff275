// Command-line parsing: every flag, and one clear usage error for each kind of mistake.
#include <gtest/gtest.h>

#include "cli/args.h"
#include "core/errors.h"

namespace vkp {
namespace {

CliArgs parse(std::vector<std::string> a) { return parseArgs(a); }

std::string errorOf(std::vector<std::string> a) {
    try {
        parseArgs(a);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(CliArgs, RenderWithEveryFlag) {
    const CliArgs a = parse({"render", "s.json", "-o", "a.png", "-o", "b.exr", "--spp", "16", "--time", "2.5", "--width", "64",
                             "--height", "32", "--max-depth", "7", "--seed", "9", "--sampler", "light", "--variant", "full",
                             "--device", "llvm", "--validate", "--exposure", "-1", "--dump-every", "4", "--dump-dir", "d",
                             "--dump-format", "exr", "--quiet", "--samples-per-dispatch", "2", "--rr-depth", "5",
                             "--adaptive", "0.03", "--adaptive-min-spp", "32"});
    EXPECT_EQ(a.command, Command::Render);
    EXPECT_EQ(a.scene, "s.json");
    ASSERT_EQ(a.session.outputs.size(), 2u);
    EXPECT_EQ(*a.spp, 16u);
    EXPECT_DOUBLE_EQ(a.session.timeLimit, 2.5);
    EXPECT_EQ(*a.width, 64u);
    EXPECT_EQ(*a.height, 32u);
    EXPECT_EQ(*a.maxDepth, 7u);
    EXPECT_EQ(*a.seed, 9u);
    EXPECT_EQ(a.render.sampler, Sampler::Light);
    EXPECT_TRUE(a.render.fullVariant);
    EXPECT_EQ(a.device, "llvm");
    EXPECT_TRUE(a.validate);
    EXPECT_DOUBLE_EQ(a.session.exposure, -1.0);
    EXPECT_EQ(a.session.dumpEvery, 4u);
    EXPECT_EQ(a.session.dumpDir, "d");
    ASSERT_EQ(a.session.dumpFormats.size(), 2u);
    EXPECT_EQ(a.session.dumpFormats[1], ImageFormat::Exr);
    EXPECT_TRUE(a.session.quiet);
    EXPECT_EQ(a.render.samplesPerDispatch, 2u);
    EXPECT_EQ(*a.rouletteDepth, 5u);
    EXPECT_DOUBLE_EQ(a.render.adaptiveThreshold, 0.03);
    EXPECT_EQ(a.render.adaptiveMinSpp, 32u);
}

TEST(CliArgs, DefaultsAndOtherCommands) {
    const CliArgs a = parse({"render", "s.json"});
    EXPECT_EQ(a.render.sampler, Sampler::Mis);
    EXPECT_FALSE(a.spp);
    EXPECT_EQ(parse({}).command, Command::Help);
    EXPECT_EQ(parse({"--version"}).command, Command::Version);
    EXPECT_EQ(parse({"devices", "--device", "1"}).command, Command::Devices);
    EXPECT_EQ(parse({"info", "s.json"}).command, Command::Info);
}

TEST(CliArgs, Specialize) {
    EXPECT_TRUE(parseArgs({"render", "s.json"}).render.specializeOnHost);
    EXPECT_TRUE(parseArgs({"render", "s.json", "--specialize", "host"}).render.specializeOnHost);
    EXPECT_FALSE(parseArgs({"render", "s.json", "--specialize", "driver"}).render.specializeOnHost);
    EXPECT_NE(errorOf({"render", "s.json", "--specialize", "gpu"}).find("--specialize must be host or driver"), std::string::npos);
}

TEST(CliArgs, Sequence) {
    EXPECT_EQ(parseArgs({"render", "s.json", "--sequence", "random"}).render.sequence, Sequence::Random);
    EXPECT_EQ(parseArgs({"render", "s.json", "--sequence", "sobol"}).render.sequence, Sequence::Sobol);
}

TEST(CliArgs, LightPickAndSampling) {
    const CliArgs d = parseArgs({"render", "s.json"});
    EXPECT_EQ(d.render.lightPick, LightPick::Power);
    EXPECT_EQ(d.render.lightSampling, LightSampling::Auto);
    EXPECT_EQ(d.render.solidAngleMinSize, kSolidAngleMinSize);
    EXPECT_EQ(parseArgs({"render", "s.json", "--light-pick", "uniform"}).render.lightPick, LightPick::Uniform);
    EXPECT_EQ(parseArgs({"render", "s.json", "--light-pick", "power"}).render.lightPick, LightPick::Power);
    EXPECT_EQ(parseArgs({"render", "s.json", "--light-sampling", "area"}).render.lightSampling, LightSampling::Area);
    EXPECT_EQ(parseArgs({"render", "s.json", "--light-sampling", "solid-angle"}).render.lightSampling, LightSampling::SolidAngle);
    EXPECT_NE(errorOf({"render", "s.json", "--light-pick", "random"}).find("--light-pick must be power or uniform, got 'random'"),
              std::string::npos);
    EXPECT_EQ(parseArgs({"render", "s.json", "--light-sampling", "auto"}).render.lightSampling, LightSampling::Auto);
    EXPECT_EQ(parseArgs({"render", "s.json", "--solid-angle-min", "0.05"}).render.solidAngleMinSize, 0.05f);
    EXPECT_EQ(parseArgs({"render", "s.json", "--light-sampling", "auto", "--solid-angle-min", "0"}).render.solidAngleMinSize, 0.0f);
    EXPECT_NE(errorOf({"render", "s.json", "--light-sampling", "cone"}).find("--light-sampling must be auto, solid-angle or area"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--light-sampling", "area", "--solid-angle-min", "0.1"})
                  .find("--solid-angle-min applies to --light-sampling auto only"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--solid-angle-min", "-1"}).find("--solid-angle-min"), std::string::npos);
    EXPECT_NE(errorOf({"info", "s.json", "--solid-angle-min", "0.1"}).find("only valid with 'vkpath render'"), std::string::npos);
}

TEST(CliArgs, WorkgroupAndTileOrder) {
    const CliArgs d = parseArgs({"render", "s.json"});
    EXPECT_EQ(d.render.workgroupX, 0u);  // auto: the renderer asks the device (render/workgroup.h)
    EXPECT_EQ(d.render.workgroupY, 0u);
    EXPECT_FALSE(d.render.linearTiles);
    const CliArgs a = parseArgs({"render", "s.json", "--workgroup", "16x4", "--tile-order", "linear"});
    EXPECT_EQ(a.render.workgroupX, 16u);
    EXPECT_EQ(a.render.workgroupY, 4u);
    EXPECT_TRUE(a.render.linearTiles);
    const CliArgs back = parseArgs({"render", "s.json", "--workgroup", "16x4", "--workgroup", "auto"});
    EXPECT_EQ(back.render.workgroupX, 0u);
    EXPECT_EQ(back.render.workgroupY, 0u);
    EXPECT_NE(errorOf({"render", "s.json", "--workgroup", "16"}).find("--workgroup wants WxH"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--workgroup", "0x8"}).find("--workgroup"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--workgroup", "64x32"}).find("at most 1024"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--tile-order", "hilbert"}).find("--tile-order must be scrambled or linear"),
              std::string::npos);
}

TEST(CliArgs, UsageErrors) {
    EXPECT_NE(errorOf({"paint"}).find("unknown command 'paint'"), std::string::npos);
    EXPECT_NE(errorOf({"render"}).find("needs a scene file"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--spp"}).find("--spp needs a value"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--spp", "0"}).find("--spp wants a whole number"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--spp", "12x"}).find("got '12x'"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--time", "nan"}).find("--time"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--sampler", "mis2"}).find("--sampler must be"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--sequence", "halton"}).find("--sequence must be random or sobol"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--bogus"}).find("unknown option '--bogus'"), std::string::npos);
    EXPECT_NE(errorOf({"render", "a.json", "b.json"}).find("unexpected argument 'b.json'"), std::string::npos);
    EXPECT_NE(errorOf({"info", "a.json", "--spp", "3"}).find("only valid with 'vkpath render'"), std::string::npos);
    EXPECT_EQ(errorOf({"render", "s.json", "--spp", "1"}), "");
}

// Feature images and the denoiser: which AOVs, what the kernel gathers, the denoiser's files.
TEST(CliArgs, FeatureImagesAndDenoising) {
    CliArgs a = parse({"render", "s.json", "--aov", "spp,variance"});
    EXPECT_EQ(a.session.aovs, (std::vector<Aov>{Aov::Variance, Aov::Spp}));
    EXPECT_FALSE(a.render.aov);  // from the accumulation sums: the kernel needs nothing more
    a = parse({"render", "s.json", "--aov", "depth"});
    EXPECT_TRUE(a.render.aov);
    a = parse({"render", "s.json", "--denoise", "--denoise-output", "d.exr", "--dump-every", "4", "--denoise-dumps"});
    EXPECT_TRUE(a.denoise);
    EXPECT_TRUE(a.render.aov);  // the denoiser's guides
    EXPECT_TRUE(a.session.aovs.empty());
    EXPECT_EQ(a.session.denoiseOutput, "d.exr");
    EXPECT_TRUE(a.session.denoiseDumps);
    EXPECT_NE(errorOf({"render", "s.json", "--aov", "albedo,shadow"}).find("--aov: unknown AOV 'shadow' (known: albedo, normal"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--denoise-output", "d.png"}).find("need --denoise"), std::string::npos);
    EXPECT_FALSE(a.denoiseFilter);  // the Denoiser's default
    a = parse({"render", "s.json", "--denoise", "--denoise-filter", "atrous"});
    EXPECT_EQ(a.denoiseFilter, DenoiseFilter::ATrous);
    a = parse({"render", "s.json", "--denoise", "--denoise-filter", "nlm"});
    EXPECT_EQ(a.denoiseFilter, DenoiseFilter::NonLocalMeans);
    EXPECT_NE(errorOf({"render", "s.json", "--denoise", "--denoise-filter", "svgf"}).find("--denoise-filter must be nlm or atrous, got 'svgf'"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--denoise-filter", "nlm"}).find("need --denoise"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--denoise", "--denoise-dumps"}).find("--denoise-dumps needs --dump-every"), std::string::npos);
    a = parse({"merge", "a.exr", "-o", "x.png", "--aov", "albedo,spp"});  // merge writes the parts' feature images
    ASSERT_EQ(a.session.aovs.size(), 2u);
    EXPECT_NE(errorOf({"merge", "a.exr", "-o", "x.png", "--denoise"}).find("vkpath merge takes"), std::string::npos);
}

// Light for scenes that bring none (render and info: it changes the variant).
TEST(CliArgs, BackgroundAndEnvironment) {
    CliArgs a = parse({"render", "s.gltf", "--background", "0.25,0.5,1"});
    ASSERT_TRUE(a.background);
    EXPECT_EQ(*a.background, glm::vec3(0.25f, 0.5f, 1.0f));
    EXPECT_EQ(*parse({"info", "s.gltf", "--background", "2"}).background, glm::vec3(2.0f));
    a = parse({"render", "s.gltf", "--environment", "sky.hdr", "--environment-strength", "3", "--environment-rotate", "-90"});
    EXPECT_EQ(a.environment, "sky.hdr");
    EXPECT_EQ(a.environmentStrength, 3.0f);
    EXPECT_EQ(a.environmentRotate, -90.0f);
    for (const char* bad : {"1,2", "1,2,3,4", "-1", "1,,2", "nan", "1,2,x", ""})
        EXPECT_NE(errorOf({"render", "s.gltf", "--background", bad}).find("--background wants R,G,B"), std::string::npos) << bad;
    EXPECT_NE(errorOf({"render", "s.gltf", "--background", "1", "--environment", "a.hdr"}).find("exclude each other"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.gltf", "--background", "1", "--environment-strength", "2"}).find("not to --background"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.gltf", "--environment-strength", "-1"}).find("--environment-strength"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.gltf", "--environment"}).find("--environment"), std::string::npos);
}

// The image size decides whether a render fits the device, which `vkpath info` checks.
TEST(CliArgs, InfoTakesTheImageSize) {
    const CliArgs a = parse({"info", "s.json", "--width", "4096", "--height", "300"});
    EXPECT_EQ(a.width, 4096u);
    EXPECT_EQ(a.height, 300u);
    EXPECT_NE(errorOf({"info", "s.json", "--width", "16385"}).find("--width"), std::string::npos);
}

TEST(CliArgs, SpatialSplitsOffByDefaultForRenderAndInfoNotMerge) {
    EXPECT_FALSE(parse({"render", "s.json"}).spatialSplits);
    EXPECT_TRUE(parse({"render", "s.json", "--spatial-splits"}).spatialSplits);
    EXPECT_TRUE(parse({"info", "s.glb", "--spatial-splits"}).spatialSplits);
    EXPECT_NE(errorOf({"merge", "a.exr", "-o", "x.png", "--spatial-splits"}).find("vkpath merge takes"), std::string::npos);
}

TEST(CliArgs, CacheDirIsARenderOptionNoneTurnsTheCacheOff) {
    EXPECT_FALSE(parse({"render", "s.json"}).cacheDir);  // the default folder (core/disk_cache.h)
    EXPECT_EQ(parse({"render", "s.json", "--cache-dir", "/tmp/k"}).cacheDir, std::filesystem::path("/tmp/k"));
    EXPECT_EQ(parse({"render", "s.json", "--cache-dir", "none"}).cacheDir, std::filesystem::path());
    EXPECT_EQ(parse({"render", "s.json", "--cache-dir", "./none"}).cacheDir, std::filesystem::path("./none"));
    EXPECT_EQ(errorOf({"render", "s.json", "--cache-dir", ""}), "usage: --cache-dir needs a file name (see 'vkpath --help')");
    EXPECT_NE(errorOf({"info", "s.json", "--cache-dir", "k"}).find("only valid with 'vkpath render'"), std::string::npos);
    EXPECT_NE(errorOf({"merge", "a.exr", "-o", "x.png", "--cache-dir", "k"}).find("vkpath merge takes"), std::string::npos);
}

TEST(CliArgs, InstancingAutoByDefaultFlattenOnRequestAlsoForInfo) {
    EXPECT_TRUE(parse({"render", "s.glb"}).instancing);
    EXPECT_FALSE(parse({"render", "s.glb", "--instancing", "flatten"}).instancing);
    EXPECT_TRUE(parse({"render", "s.glb", "--instancing", "auto"}).instancing);
    EXPECT_FALSE(parse({"info", "s.glb", "--instancing", "flatten"}).instancing);
    EXPECT_EQ(errorOf({"render", "s.glb", "--instancing", "never"}),
              "usage: --instancing must be auto or flatten, got 'never' (see 'vkpath --help')");
}

}  // namespace
}  // namespace vkp
