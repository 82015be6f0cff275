// The measuring side of `vkpath render` end to end: --reference (size checks before rendering),
// --error-log (rows at powers of two or at dumps, kept by a killed run) and --stats-json (keys and
// consistency). Validation layer on (--validate) where the run is short.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/image_io.h"
#include "gpu_env.h"
#include "render/error_metrics.h"
#include "render/features.h"
#include "run_process.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

struct Row {
    std::uint32_t spp;
    double seconds, rmse, relmse, mean[3];
};

/// Parses an error log; fails the test on a malformed line.
std::vector<Row> readLog(const std::filesystem::path& p, std::string* header = nullptr) {
    std::ifstream f(p);
    std::string line;
    std::vector<Row> rows;
    if (!std::getline(f, line)) {
        ADD_FAILURE() << p << ": empty";
        return rows;
    }
    if (header) *header = line;
    while (std::getline(f, line)) {
        Row r{};
        char tail = 0;
        const int n = std::sscanf(line.c_str(), "%u,%lf,%lf,%lf,%lf,%lf,%lf%c", &r.spp, &r.seconds, &r.rmse, &r.relmse,
                                  &r.mean[0], &r.mean[1], &r.mean[2], &tail);
        EXPECT_EQ(n, 7) << "malformed row: '" << line << "'";
        rows.push_back(r);
    }
    return rows;
}

struct CliBench : ::testing::Test {
    std::filesystem::path dir = scratchDir("cli_bench");
    ProcessResult run(const std::vector<std::string>& args, const std::string& env = "") {
        return runProcess(vkpathBinary(), args, dir, env);
    }
    std::string scene(const char* name) { return (scenesDir() / name).string(); }
    void removeAll(std::initializer_list<const char*> files) {
        for (const char* f : files) std::filesystem::remove(dir / f);
    }
    /// A 16x16 reference of cornell-classic at 64 spp, rendered once per test.
    void makeReference() {
        const ProcessResult r = run({"render", scene("cornell-classic.json"), "--spp", "64", "--width", "16", "--height",
                                     "16", "--seed", "7", "-o", "ref.pfm", "--quiet"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
};

TEST_F(CliBench, ReferenceOfAnotherSizeFailsBeforeRendering) {
    VKP_REQUIRE_DEVICE(dev);
    removeAll({"wrong.pfm", "out.png", "log.csv", "st.json"});
    writeImage(Image(20, 10), dir / "wrong.pfm");
    ProcessResult r = run({"render", scene("cornell-classic.json"), "--width", "16", "--height", "16", "--reference",
                           "wrong.pfm", "--error-log", "log.csv", "--stats-json", "st.json", "-o", "out.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("wrong.pfm: reference is 20x10 but the render is 16x16"), std::string::npos) << r.err;
    for (const char* f : {"out.png", "log.csv", "st.json"}) EXPECT_FALSE(std::filesystem::exists(dir / f)) << f;

    // A missing reference, and a PNG (display-encoded, not a reference), are refused the same way.
    r = run({"render", scene("cornell-classic.json"), "--reference", "none.exr", "--error-log", "log.csv", "-o", "out.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("none.exr"), std::string::npos) << r.err;
    writeImage(Image(16, 16), dir / "ref.png");
    r = run({"render", scene("cornell-classic.json"), "--width", "16", "--height", "16", "--reference", "ref.png",
             "-o", "out.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    for (const char* f : {"out.png", "log.csv"}) EXPECT_FALSE(std::filesystem::exists(dir / f)) << f;
}

TEST_F(CliBench, ErrorLogAtPowersOfTwoAndAtTheEnd) {
    VKP_REQUIRE_DEVICE(dev);
    makeReference();
    removeAll({"log.csv", "out.pfm"});
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--validate", "--spp", "20", "--width", "16",
                                 "--height", "16", "--reference", "ref.pfm", "--error-log", "log.csv", "-o", "out.pfm"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string header;
    const std::vector<Row> rows = readLog(dir / "log.csv", &header);
    EXPECT_EQ(header, "spp,seconds,rmse,relmse,mean_r,mean_g,mean_b");
    ASSERT_EQ(rows.size(), 6u);
    const std::uint32_t spp[] = {1, 2, 4, 8, 16, 20};
    for (std::size_t i = 0; i < rows.size(); ++i) {
        EXPECT_EQ(rows[i].spp, spp[i]);
        EXPECT_TRUE(std::isfinite(rows[i].rmse) && std::isfinite(rows[i].relmse)) << i;
        if (i > 0) EXPECT_GE(rows[i].seconds, rows[i - 1].seconds) << i;
    }
    EXPECT_GT(rows[0].seconds, 0.0);
    // 20 spp against 1 spp: the relMSE falls ~20x in expectation; the chance that it does not fall
    // at all (over 256 pixels x 3 channels) is negligible.
    EXPECT_LT(rows.back().relmse, rows.front().relmse);
    // The last row is the final image's error.
    const Image out = readImage(dir / "out.pfm");
    const ErrorMetrics m = computeErrorMetrics(out, readImage(dir / "ref.pfm"));
    EXPECT_NEAR(rows.back().rmse, m.rmse, 1e-6 * m.rmse);
    EXPECT_NEAR(rows.back().relmse, m.relmse, 1e-6 * m.relmse);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rows.back().mean[c], m.mean[c], 1e-6 * m.mean[c]) << c;
    EXPECT_NE(r.err.find("error against ref.pfm: rmse"), std::string::npos) << r.err;
}

TEST_F(CliBench, ErrorLogAtDumpsOnly) {
    VKP_REQUIRE_DEVICE(dev);
    makeReference();
    removeAll({"log.csv"});
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--spp", "12", "--width", "16", "--height",
                                 "16", "--dump-every", "5", "--dump-dir", "frames", "--reference", "ref.pfm",
                                 "--error-log", "log.csv", "-o", "out.png", "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<Row> rows = readLog(dir / "log.csv");
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].spp, 5u);
    EXPECT_EQ(rows[1].spp, 10u);
    EXPECT_EQ(rows[2].spp, 12u);
}

TEST_F(CliBench, KilledRunKeepsItsRows) {
    VKP_REQUIRE_DEVICE(dev);
    makeReference();
    removeAll({"log.csv", "st.json", "never.png"});
    // Killed (SIGKILL) after 4 s, long before 16M spp (also on a fast GPU: at most 8 samples per
    // dispatch): the rows so far are complete and on disk.
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--spp", "16000000", "--width", "16", "--height",
                                 "16", "--reference", "ref.pfm", "--error-log", "log.csv", "--stats-json", "st.json",
                                 "-o", "never.png", "--quiet"},
                                "timeout -s KILL 4");
    EXPECT_EQ(r.exitCode, 137) << r.err;
    const std::vector<Row> rows = readLog(dir / "log.csv");
    EXPECT_GE(rows.size(), 3u);
    for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].spp, 1u << i);
    EXPECT_FALSE(std::filesystem::exists(dir / "st.json"));
    EXPECT_FALSE(std::filesystem::exists(dir / "never.png"));
}

TEST_F(CliBench, StatsJsonKeysAndConsistency) {
    VKP_REQUIRE_DEVICE(dev);
    makeReference();
    removeAll({"st.json"});
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--validate", "--spp", "9", "--width", "16",
                                 "--height", "16", "--sampler", "light", "--reference", "ref.pfm", "--stats-json",
                                 "st.json", "-o", "out.png", "--quiet"},
                                "LP_NUM_THREADS=2");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream f(dir / "st.json");
    const nlohmann::json j = nlohmann::json::parse(f);
    for (const char* k : {"spp", "samples", "rays", "seconds_total", "seconds_render", "samples_per_second",
                          "rays_per_second", "nonfinite_samples", "device", "seconds_scene_load", "seconds_bvh_build",
                          "seconds_setup", "seconds_first_batch", "vkpath_version", "variant", "sampler"})
        EXPECT_TRUE(j.contains(k)) << k;
    EXPECT_EQ(j["spp"], 9);
    EXPECT_EQ(j["pixels"], 256);
    EXPECT_EQ(j["samples"], 9 * 256);
    // Every sample traces at least its camera ray; the light sampler adds a shadow ray per bounce.
    EXPECT_GE(j["rays"].get<double>(), 9 * 256);
    EXPECT_EQ(j["nonfinite_samples"], 0);
    EXPECT_EQ(j["loop_guard_paths"], 0);
    EXPECT_EQ(j["sampler"], "light");
    EXPECT_NE(j["variant"].get<std::string>().find("sampler:light"), std::string::npos) << j["variant"];
    const double total = j["seconds_total"], render = j["seconds_render"], first = j["seconds_first_batch"];
    EXPECT_GT(first, 0.0);
    EXPECT_GE(render, first);
    EXPECT_GE(total, render + j["seconds_setup"].get<double>() + j["seconds_scene_load"].get<double>());
    EXPECT_GE(total, j["seconds_to_first_sample"].get<double>());
    EXPECT_NEAR(j["samples_per_second"].get<double>(), 9 * 256 / render, 1e-6 * 9 * 256 / render);
    EXPECT_NEAR(j["rays_per_second"].get<double>(), j["rays"].get<double>() / render, 1e-6 * j["rays_per_second"].get<double>());
    EXPECT_EQ(j["device"]["name"], dev.info().name);
    EXPECT_EQ(j["environment"]["LP_NUM_THREADS"], "2");
    EXPECT_TRUE(j["error"]["relmse"].is_number());
    EXPECT_EQ(j["light_pick"], "power");
    EXPECT_EQ(j["light_sampling"], "auto");
    EXPECT_NEAR(j["solid_angle_min_size"].get<double>(), double(kSolidAngleMinSize), 1e-7);
    // cornell-classic: 18 primitives of 48 bytes at least; a process with a Vulkan device uses megabytes.
    EXPECT_GE(j["scene_buffer_bytes"].get<double>(), 18 * 48);
    EXPECT_GT(j["peak_rss_bytes"].get<double>(), 1e6);
    EXPECT_TRUE(j["huge_pages"].is_boolean());
    EXPECT_EQ(j["spatial_splits"], false);
    EXPECT_EQ(j["bvh_primitives"], 18);  // cornell-classic's 18 quads, one reference each
    const ProcessResult v = run({"--version"});
    EXPECT_EQ(v.out, "vkpath " + j["vkpath_version"].get<std::string>() + "\n");
}

// vkpath re-executes itself with glibc.malloc.hugetlb=1 (core/huge_pages.h), adding it to
// tunables already set; a GLIBC_TUNABLES that names it already is left alone (the opt-out).
// Fails if the re-execution does not happen or ignores the user's value.
TEST_F(CliBench, HugePagesByDefault) {
    VKP_REQUIRE_DEVICE(dev);
    struct Case {
        const char* env;
        bool expected;
    };
    for (const Case c : {Case{"", true}, Case{"GLIBC_TUNABLES=glibc.malloc.arena_max=2", true},
                         Case{"GLIBC_TUNABLES=glibc.malloc.hugetlb=0", false}}) {
        removeAll({"hp.json"});
        const ProcessResult r = run({"render", scene("cornell-classic.json"), "--spp", "1", "--width", "8", "--height", "8",
                                     "--stats-json", "hp.json", "-o", "hp.pfm", "--quiet"},
                                    std::string("env -u GLIBC_TUNABLES ") + c.env);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        std::ifstream f(dir / "hp.json");
        const nlohmann::json j = nlohmann::json::parse(f);
        EXPECT_EQ(j["huge_pages"], c.expected) << c.env;
    }
}

TEST_F(CliBench, StatsJsonWithTimeLimit) {
    VKP_REQUIRE_DEVICE(dev);
    removeAll({"st.json"});
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--spp", "1000000", "--time", "2", "--width",
                                 "16", "--height", "16", "--stats-json", "st.json", "-o", "out.png", "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream f(dir / "st.json");
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_LT(j["spp"].get<double>(), 1000000);
    EXPECT_EQ(j["spp_requested"], 1000000);
    EXPECT_EQ(j["samples"].get<double>(), j["spp"].get<double>() * 256);
    EXPECT_TRUE(j["error"].is_null());
    // --time counts from process start; the stats are written after the last image.
    EXPECT_GE(j["seconds_total"].get<double>(), 1.0);
    EXPECT_LT(j["seconds_total"].get<double>(), 10.0);  // generous: the machine may be loaded
}

TEST_F(CliBench, StatsJsonNamesTheBvhBuild) {
    VKP_REQUIRE_DEVICE(dev);
    removeAll({"st.json"});
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--spp", "1", "--width", "16", "--height", "16",
                                 "--spatial-splits", "--stats-json", "st.json", "-o", "out.png", "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream f(dir / "st.json");
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["spatial_splits"], true);
    EXPECT_EQ(j["bvh_primitives"], 18);  // no cut pays among the box's 18 quads
}

// --adaptive: the render stops when every pixel has converged (a loose threshold on a tiny image),
// and the stats count the samples actually taken.
TEST_F(CliBench, AdaptiveStopsWhenEveryPixelConverged) {
    VKP_REQUIRE_DEVICE(dev);
    removeAll({"st.json"});
    const ProcessResult r = run({"render", scene("cornell-classic.json"), "--validate", "--spp", "100000", "--width", "16",
                                 "--height", "16", "--adaptive", "0.2", "--adaptive-min-spp", "32", "--stats-json",
                                 "st.json", "-o", "out.png", "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream f(dir / "st.json");
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["active_pixels"], 0);
    EXPECT_EQ(j["adaptive_threshold"], 0.2);
    EXPECT_LT(j["spp"].get<double>(), 100000);
    EXPECT_GE(j["mean_spp"].get<double>(), 32);
    EXPECT_LE(j["mean_spp"].get<double>(), j["spp"].get<double>());
    EXPECT_NEAR(j["samples"].get<double>(), j["mean_spp"].get<double>() * 256, 1e-3);
    const ProcessResult bad = run({"render", scene("cornell-classic.json"), "--adaptive", "-1", "-o", "x.png"});
    EXPECT_EQ(bad.exitCode, 1);
}

}  // namespace
}  // namespace vkp::test
