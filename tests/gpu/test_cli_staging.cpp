// Buffers reached through staging copies, as on a discrete GPU (VKPATH_NO_BUFFER_MAPPING=1 forces
// that path on lavapipe, whose one memory type is otherwise mapped), give the mapped render's files
// bit for bit, with the validation layer on (synchronization validation included): every upload and
// read-back of the renderer, the feature images, the denoiser, adaptive sampling's active lists and a
// checkpoint's save and resume goes the way a discrete GPU's will (docs/design.md "Buffer memory").
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "gpu_env.h"
#include "image_checks.h"
#include "core/image_io.h"
#include "run_process.h"
#include "test_paths.h"

namespace vkp::test {
namespace {
namespace fs = std::filesystem;

struct CliStaging : ::testing::Test {
    fs::path dir;
    void SetUp() override {
        dir = scratchDir("cli_staging") / ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    /// cornell-book3 (glass, so every kind of path) at 24x16 with the validation layer, `more`
    /// appended; `staging`: through staging buffers. Returns the process's result.
    ProcessResult render(bool staging, std::vector<std::string> more) {
        std::vector<std::string> a = {"render", (scenesDir() / "cornell-book3.json").string(), "--validate", "--width", "24",
                                      "--height", "16", "--quiet"};
        a.insert(a.end(), more.begin(), more.end());
        const std::string env = std::string("VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT") +
                                (staging ? " VKPATH_NO_BUFFER_MAPPING=1" : "");
        return runProcess(vkpathBinary(), a, dir, env);
    }
    std::uint64_t stagingCopies(const char* statsJson) {
        std::ifstream in(dir / statsJson);
        return nlohmann::json::parse(in).at("staging_copies").get<std::uint64_t>();
    }
    /// The two files exist, are not empty and are equal byte for byte.
    void expectSameFile(const std::string& a, const std::string& b) {
        const std::string x = fileBytes(dir / a), y = fileBytes(dir / b);
        ASSERT_FALSE(x.empty()) << a;
        EXPECT_TRUE(x == y) << a << " and " << b << " differ";
    }
};

TEST_F(CliStaging, FeatureImagesAndTheDenoiserGiveTheMappedFiles) {
    VKP_REQUIRE_DEVICE(dev);
    for (bool staging : {false, true}) {
        const std::string tag = staging ? "s" : "m";
        const ProcessResult r = render(staging, {"--spp", "8", "--aov", "all", "--denoise", "-o", tag + ".exr", "-o", tag + ".pfm",
                                                 "--stats-json", tag + ".json"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    // The staging run really copied (renderer, feature images and denoiser: dozens of transfers);
    // the other one did only where the device has no memory to map (a discrete GPU: both runs copy).
    EXPECT_GE(stagingCopies("s.json"), 10u);
    if (dev.info().mappedBuffers) EXPECT_EQ(stagingCopies("m.json"), 0u);
    else EXPECT_EQ(stagingCopies("m.json"), stagingCopies("s.json"));
    expectSameFile("m.exr", "s.exr");
    expectSameFile("m.pfm", "s.pfm");
    expectSameFile("m.denoised.pfm", "s.denoised.pfm");
    expectSameFile("m.albedo.pfm", "s.albedo.pfm");
    expectSameFile("m.variance.pfm", "s.variance.pfm");
    EXPECT_TRUE(litAndNotConstant(readImage(dir / "s.pfm"), "s.pfm"));
}

TEST_F(CliStaging, AdaptiveSamplingGivesTheMappedFile) {
    VKP_REQUIRE_DEVICE(dev);
    for (bool staging : {false, true}) {
        const std::string tag = staging ? "s" : "m";
        const ProcessResult r =
            render(staging, {"--spp", "48", "--adaptive", "0.1", "--adaptive-min-spp", "8", "--aov", "spp", "-o", tag + ".exr"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    expectSameFile("m.exr", "s.exr");
    // Pixels stopped at different counts, so the active lists were uploaded more than once.
    const Image spp = readImageLayer(dir / "s.exr", "spp");
    float lo = spp.rgb[0], hi = spp.rgb[0];
    for (float v : spp.rgb) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_LT(lo, hi) << "every pixel took the same samples: the active lists were never used";
}

TEST_F(CliStaging, ACheckpointSavedAndResumedThroughStagingGivesTheStraightRender) {
    VKP_REQUIRE_DEVICE(dev);
    ProcessResult r = render(true, {"--spp", "4", "--checkpoint", "ck.exr", "-o", "first.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = render(true, {"--spp", "12", "--resume", "ck.exr", "-o", "resumed.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = render(false, {"--spp", "12", "-o", "straight.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    expectSameFile("straight.exr", "resumed.exr");
}

}  // namespace
}  // namespace vkp::test
