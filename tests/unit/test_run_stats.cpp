// The JSON of --stats-json (render/run_stats.h): valid JSON, the keys scripts rely on, derived
// numbers consistent with the inputs, string escaping, atomic write.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "render/run_stats.h"
#include "test_paths.h"

namespace vkp {
namespace {

RunStats example() {
    RunStats s;
    s.version = "0.1.0";
    s.scene = "scenes/a \"quoted\" name\\x.json";
    s.sampler = "mixture";
    s.variant = "prims:sphere";
    s.width = 40;
    s.height = 30;
    s.spp = 16;
    s.sppRequested = 16;
    s.rays = 50000;
    s.firstBatchRays = 2000;
    s.peakRssBytes = 123456789;
    s.sceneBufferBytes = 4096;
    s.secondsTotal = 3.0;
    s.secondsRender = 2.0;
    s.secondsFirstBatch = 0.5;
    s.secondsLongestDispatch = 0.125;
    s.deviceName = "llvmpipe\t(LLVM)";
    return s;
}

TEST(RunStats, RequiredKeysAndDerivedNumbers) {
    const nlohmann::json j = nlohmann::json::parse(runStatsJson(example()));
    for (const char* k : {"spp", "samples", "rays", "seconds_total", "seconds_render", "samples_per_second",
                          "rays_per_second", "nonfinite_samples", "device"})
        EXPECT_TRUE(j.contains(k)) << k;
    EXPECT_EQ(j["spp"], 16);
    EXPECT_EQ(j["pixels"], 1200);
    EXPECT_EQ(j["samples"], 16 * 1200);
    EXPECT_EQ(j["rays"], 50000);
    EXPECT_DOUBLE_EQ(j["samples_per_second"].get<double>(), 16 * 1200 / 2.0);
    EXPECT_DOUBLE_EQ(j["rays_per_second"].get<double>(), 50000 / 2.0);
    // Steady rates leave out the first batch: 1 spp and its rays, and its time.
    EXPECT_NEAR(j["samples_per_second_steady"].get<double>(), 15 * 1200 / 1.5, 1e-3);
    EXPECT_NEAR(j["rays_per_second_steady"].get<double>(), 48000 / 1.5, 1e-3);
    EXPECT_EQ(j["device"]["name"], "llvmpipe\t(LLVM)");
    EXPECT_EQ(j["scene"], "scenes/a \"quoted\" name\\x.json");
    EXPECT_TRUE(j["error"].is_null());
    EXPECT_EQ(j["peak_rss_bytes"], 123456789);
    EXPECT_EQ(j["scene_buffer_bytes"], 4096);
    EXPECT_EQ(j["seconds_longest_dispatch"], 0.125);
    EXPECT_EQ(j["pixels_per_invocation"], 1);
}

TEST(RunStats, NoRenderTimeGivesNullRatesAndErrorIsAnObject) {
    RunStats s = example();
    s.secondsRender = 0;
    s.secondsFirstBatch = 0;
    ErrorMetrics m;
    m.rmse = 0.5;
    m.relmse = 0.25;
    s.error = m;
    s.reference = "ref.exr";
    const nlohmann::json j = nlohmann::json::parse(runStatsJson(s));
    EXPECT_TRUE(j["samples_per_second"].is_null());
    EXPECT_TRUE(j["rays_per_second_steady"].is_null());
    EXPECT_EQ(j["error"]["rmse"], 0.5);
    EXPECT_EQ(j["error"]["relmse"], 0.25);
    EXPECT_EQ(j["error"]["reference"], "ref.exr");
}

TEST(RunStats, JsonStringEscapes) {
    EXPECT_EQ(jsonString("a\"b\\c\n\x01"), "\"a\\\"b\\\\c\\n\\u0001\"");
    EXPECT_EQ(nlohmann::json::parse(jsonString("x\x1fy")).get<std::string>(), "x\x1fy");
}

TEST(RunStats, WritesTheFile) {
    const auto path = test::scratchDir("run_stats") / "stats.json";
    std::filesystem::remove(path);
    writeRunStatsJson(example(), path);
    std::ifstream f(path);
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["vkpath_version"], "0.1.0");
}

}  // namespace
}  // namespace vkp
