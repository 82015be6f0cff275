// Renders that survive interruption (issue 15): SIGINT/SIGTERM write every output with the samples
// reached and exit 130/143; a checkpoint continued with --resume gives the uninterrupted render's
// file bit for bit (with and without adaptive sampling, interrupted by a real signal); sample
// ranges merge to the single render within float rounding; bad combinations are refused up front.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <regex>

#include "core/image_io.h"
#include "gpu_env.h"
#include "image_checks.h"
#include "run_process.h"
#include "test_paths.h"

namespace vkp::test {
namespace {
namespace fs = std::filesystem;

/// Files in `dir` left by an atomic write: ".<name>.tmp-*".
int temporaryFiles(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp-") != std::string::npos;
    return n;
}

struct CliInterrupt : ::testing::Test {
    fs::path dir;
    void SetUp() override {
        dir = scratchDir("cli_interrupt") / ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ProcessResult run(std::vector<std::string> args) {
        return runProcess(vkpathBinary(), args, dir);
    }
    /// The render every test uses: a small Cornell box with glass (book 3), validation on.
    std::vector<std::string> render(std::vector<std::string> more) const {
        std::vector<std::string> a = {"render", (scenesDir() / "cornell-book3.json").string(), "--validate", "--width", "40", "--height", "32"};
        a.insert(a.end(), more.begin(), more.end());
        return a;
    }
    /// Starts a long render with a checkpoint after every batch, waits for the first checkpoint (so
    /// that samples were taken) and sends `signo`. `twice`: stops the process (SIGSTOP), sends
    /// SIGINT and SIGTERM, and continues it, so that both arrive before it can finish a batch (two
    /// signals of one kind would merge into one while pending). Returns the process's result.
    ProcessResult interrupted(std::vector<std::string> more, int signo, bool twice = false) {
        more.insert(more.end(), {"--spp", "1000000", "--checkpoint", "ck.exr", "--checkpoint-every", "0.001"});
        BackgroundProcess p(vkpathBinary(), render(more), dir);
        EXPECT_TRUE(p.waitFor([&] { return fs::exists(dir / "ck.exr"); }, 120.0)) << p.errSoFar();
        const auto t0 = std::chrono::steady_clock::now();
        if (twice) {
            p.signal(SIGSTOP);
            p.signal(SIGINT);
            p.signal(SIGTERM);
            p.signal(SIGCONT);
        } else {
            p.signal(signo);
        }
        ProcessResult r = p.wait();
        std::printf("signal %d to exit: %.3f s\n", signo, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        return r;
    }
};

/// K of "stopped at sample K of N" in vkpath's stderr, or 0.
std::uint32_t stoppedAt(const std::string& err) {
    std::smatch m;
    return std::regex_search(err, m, std::regex("stopped at sample ([0-9]+) of")) ? std::uint32_t(std::stoul(m[1])) : 0u;
}

class CliResume : public CliInterrupt, public ::testing::WithParamInterface<bool> {};

// Interrupted by a real SIGINT at sample K, continued to K + 13 with --resume: the output file is
// byte for byte the one an uninterrupted render of K + 13 samples writes. The interrupted render's
// own output holds exactly the K samples (equal pixels to a K-sample render) and says so.
TEST_P(CliResume, SigintThenResumeIsBitIdentical) {
    VKP_REQUIRE_DEVICE(dev);
    const bool adaptive = GetParam();
    // Adaptive: a threshold no pixel reaches, so the active list and decision sums matter to the end.
    const std::vector<std::string> mode = adaptive ? std::vector<std::string>{"--adaptive", "0.0001", "--adaptive-min-spp", "8"}
                                                   : std::vector<std::string>{};
    std::vector<std::string> args = mode;
    args.insert(args.end(), {"-o", "stopped.exr", "-o", "stopped.png"});
    const ProcessResult r = interrupted(args, SIGINT);
    ASSERT_EQ(r.exitCode, 130) << r.err;
    const std::uint32_t k = stoppedAt(r.err);
    ASSERT_GT(k, 0u) << r.err;
    std::printf("interrupted at sample %u\n", k);
    EXPECT_EQ(temporaryFiles(dir), 0);
    const std::string stopped = fileBytes(dir / "stopped.exr");
    EXPECT_NE(stopped.find("vkpath.interrupted"), std::string::npos);
    EXPECT_NE(stopped.find("0:" + std::to_string(k)), std::string::npos) << "the samples reached are in the file's metadata";
    EXPECT_NE(fileBytes(dir / "stopped.png").find("tEXtvkpath.spp"), std::string::npos);

    auto with = [&](std::vector<std::string> more) {
        std::vector<std::string> a = mode;
        a.insert(a.end(), more.begin(), more.end());
        a.push_back("--quiet");
        return render(a);
    };
    const std::string total = std::to_string(k + 13);
    ProcessResult res = run(with({"--resume", "ck.exr", "--spp", total, "-o", "resumed.exr"}));
    ASSERT_EQ(res.exitCode, 0) << res.err;
    res = run(with({"--spp", total, "-o", "straight.exr"}));
    ASSERT_EQ(res.exitCode, 0) << res.err;
    const std::string resumed = fileBytes(dir / "resumed.exr"), straight = fileBytes(dir / "straight.exr");
    ASSERT_FALSE(straight.empty());
    EXPECT_TRUE(resumed == straight) << "resumed.exr and straight.exr differ";
    EXPECT_TRUE(litAndNotConstant(readImage(dir / "straight.exr"), "straight.exr"));
    res = run(with({"--spp", std::to_string(k), "-o", "k.exr"}));
    ASSERT_EQ(res.exitCode, 0) << res.err;
    EXPECT_EQ(readImage(dir / "k.exr").rgb, readImage(dir / "stopped.exr").rgb);
}

INSTANTIATE_TEST_SUITE_P(Modes, CliResume, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "adaptive" : "plain"; });

// Two signals: the second stops at once (128 + its number) and writes nothing: no output, no
// temporary file; the checkpoint written before stays whole and can be continued.
TEST_F(CliInterrupt, SecondSignalStopsAtOnceAndWritesNothing) {
    VKP_REQUIRE_DEVICE(dev);
    const ProcessResult r = interrupted({"-o", "never.exr"}, SIGTERM, true);
    EXPECT_TRUE(r.exitCode == 130 || r.exitCode == 143) << r.exitCode << "\n" << r.err;
    EXPECT_NE(r.err.find("stopped at once"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "never.exr"));
    EXPECT_EQ(temporaryFiles(dir), 0);
    const ProcessResult res = run(render({"--resume", "ck.exr", "--spp", "300", "-o", "later.exr", "--quiet"}));
    EXPECT_EQ(res.exitCode, 0) << res.err;
}

// A checkpoint continues only the render it came from: the first difference is named, in one line.
TEST_F(CliInterrupt, ResumeRefusesAnotherRender) {
    VKP_REQUIRE_DEVICE(dev);
    ASSERT_EQ(run(render({"--spp", "3", "--checkpoint", "ck.exr", "--quiet", "-o", "a.exr"})).exitCode, 0);
    ProcessResult r = run(render({"--spp", "6", "--resume", "ck.exr", "--seed", "5", "-o", "b.exr"}));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("ck.exr: cannot resume: seed is 0 in it, 5 here"), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    r = run(render({"--spp", "6", "--resume", "ck.exr", "--sampler", "bsdf", "-o", "b.exr"}));
    EXPECT_NE(r.err.find("sampler is mis in it, bsdf here"), std::string::npos) << r.err;
    r = run(render({"--spp", "2", "--resume", "ck.exr", "-o", "b.exr"}));
    EXPECT_NE(r.err.find("already holds samples up to 3"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "b.exr"));
}

// Three sample ranges, merged in a shuffled order, against one render of all their samples: equal
// within float rounding (the largest relative difference is printed), and the merge does not
// depend on the order of its inputs.
TEST_F(CliInterrupt, SampleRangesMergeToTheSingleRender) {
    VKP_REQUIRE_DEVICE(dev);
    const char* ranges[] = {"0:5", "5:17", "17:24"};
    for (int i = 0; i < 3; ++i) {
        const ProcessResult r = run(render({"--sample-range", ranges[i], "--partial", "p" + std::to_string(i) + ".exr", "--quiet"}));
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "cornell-book3.png")) << "a range with --partial and no -o writes no default image";
    ASSERT_EQ(run(render({"--spp", "24", "-o", "single.exr", "--quiet"})).exitCode, 0);
    ProcessResult r = run({"merge", "p2.exr", "p0.exr", "p1.exr", "-o", "merged.exr", "-o", "merged.png"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_EQ(run({"merge", "p1.exr", "p2.exr", "p0.exr", "-o", "again.exr", "--quiet"}).exitCode, 0);
    EXPECT_EQ(fileBytes(dir / "merged.exr"), fileBytes(dir / "again.exr"));
    const Image merged = readImage(dir / "merged.exr"), single = readImage(dir / "single.exr");
    ASSERT_TRUE(litAndNotConstant(single, "single.exr"));
    double worst = 0.0;
    for (std::size_t i = 0; i < single.rgb.size(); ++i) {
        const double a = merged.rgb[i], b = single.rgb[i];
        worst = std::max(worst, std::abs(a - b) / std::max(std::abs(b), 1e-6));
    }
    std::printf("merged vs single render: largest relative difference %.3g\n", worst);
    // One sample more or less would change a pixel by about 1/24; float rounding by < 1e-6.
    EXPECT_LE(worst, 1e-6);
    // A gap and an overlap are refused with one line.
    r = run({"merge", "p0.exr", "p2.exr", "-o", "gap.exr"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("samples [5:17) are in no part"), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 1);
    r = run({"merge", "p0.exr", "p0.exr", "-o", "overlap.exr"});
    EXPECT_NE(r.err.find("overlap"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "gap.exr") || fs::exists(dir / "overlap.exr"));
}

// `vkpath merge --aov`: the feature images of the merged parts are those of the single render
// (count-weighted means of running means: equal within float rounding), the positions in the
// scene's coordinates from the frame the parts carry (vkpath.aovFrame).
TEST_F(CliInterrupt, SampleRangesMergeTheirFeatureImages) {
    VKP_REQUIRE_DEVICE(dev);
    for (const char* range : {"0:7", "7:16"}) {
        const ProcessResult r = run(render({"--sample-range", range, "--aov", "albedo,normal", "--partial",
                                            std::string("p") + range[0] + ".exr", "--quiet"}));
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    ASSERT_EQ(run(render({"--spp", "16", "--aov", "all", "-o", "single.exr", "--quiet"})).exitCode, 0);
    ProcessResult r = run({"merge", "p0.exr", "p7.exr", "--aov", "all", "-o", "merged.exr", "-o", "merged.png", "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* layer : {"albedo", "normal", "depth", "position", "emission", "variance", "spp"}) {
        const Image m = readImageLayer(dir / "merged.exr", layer), s = readImageLayer(dir / "single.exr", layer);
        ASSERT_EQ(m.rgb.size(), s.rgb.size());
        double worst = 0.0, largest = 0.0;
        for (std::size_t i = 0; i < s.rgb.size(); ++i) {
            if (std::isinf(s.rgb[i]) || std::isinf(m.rgb[i])) {  // depth where nothing was hit: both
                EXPECT_EQ(s.rgb[i], m.rgb[i]) << layer << " value " << i;
                continue;
            }
            worst = std::max(worst, std::abs(double(m.rgb[i]) - s.rgb[i]));
            largest = std::max(largest, std::abs(double(s.rgb[i])));
        }
        std::printf("merged %s: largest difference %.3g (largest value %.3g)\n", layer, worst, largest);
        EXPECT_GT(largest, 0.0) << layer;
        EXPECT_LE(worst, 2e-6 * std::max(largest, 1.0)) << layer;  // a few float roundings of a mean
    }
    EXPECT_TRUE(fs::exists(dir / "merged.albedo.pfm"));  // a PNG gets its layers beside it
    // Without the parts' feature sums only variance and spp can be written.
    ASSERT_EQ(run(render({"--sample-range", "0:4", "--partial", "plain.exr", "--quiet"})).exitCode, 0);
    r = run({"merge", "plain.exr", "--aov", "variance,spp", "-o", "plain-merged.exr", "--quiet"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    r = run({"merge", "plain.exr", "--aov", "albedo", "-o", "refused.exr"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--aov albedo needs parts rendered with --aov"), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 1);
    EXPECT_FALSE(fs::exists(dir / "refused.exr"));
}

// Several devices in one process (`--device N,N` opens the default device twice: lavapipe here):
// the samples are split in rounds and merged; the image equals one device's render within float
// rounding (printed).
TEST_F(CliInterrupt, TwoDevicesEqualOneDevice) {
    VKP_REQUIRE_DEVICE(dev);
    const std::string twice = std::to_string(dev.info().index) + "," + std::to_string(dev.info().index);
    ProcessResult r = run(render({"--spp", "30", "--device", twice, "-o", "two.exr", "--partial", "two-part.exr"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("on 2 devices"), std::string::npos) << r.err;
    ASSERT_EQ(run(render({"--spp", "30", "-o", "one.exr", "--quiet"})).exitCode, 0);
    const Image two = readImage(dir / "two.exr"), one = readImage(dir / "one.exr");
    ASSERT_TRUE(litAndNotConstant(one, "one.exr"));
    double worst = 0.0;
    for (std::size_t i = 0; i < one.rgb.size(); ++i)
        worst = std::max(worst, std::abs(double(two.rgb[i]) - one.rgb[i]) / std::max(std::abs(double(one.rgb[i])), 1e-6));
    std::printf("two devices vs one: largest relative difference %.3g\n", worst);
    EXPECT_LE(worst, 1e-6);
    // Its partial is that of samples [0:30), and merges with a later range of one device.
    ASSERT_EQ(run(render({"--sample-range", "30:40", "--partial", "later.exr", "--quiet"})).exitCode, 0);
    ASSERT_EQ(run({"merge", "two-part.exr", "later.exr", "-o", "forty.exr", "--quiet"}).exitCode, 0);
    // Options that need one device are refused up front.
    r = run(render({"--spp", "4", "--device", "0,0", "--adaptive", "0.1", "-o", "no.exr"}));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--adaptive works on one device"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "no.exr"));
}

// A lost device (injected at the second submission, VKPATH_INJECT_DEVICE_LOST; the first is one sample) ends the render with
// one line and exit 3, writes no output, and keeps the last checkpoint, which continues to the
// image of an uninterrupted render.
TEST_F(CliInterrupt, DeviceLostKeepsTheLastCheckpoint) {
    VKP_REQUIRE_DEVICE(dev);
    ProcessResult r = runProcess(vkpathBinary(), render({"--spp", "40", "--checkpoint", "ck.exr", "--checkpoint-every", "0.001", "-o",
                                                         "lost.exr", "--quiet"}),
                                 dir, "VKPATH_INJECT_DEVICE_LOST=2");
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("ErrorDeviceLost"), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "lost.exr"));
    EXPECT_EQ(temporaryFiles(dir), 0);
    ASSERT_TRUE(fs::exists(dir / "ck.exr"));
    ASSERT_EQ(run(render({"--spp", "40", "--resume", "ck.exr", "-o", "resumed.exr", "--quiet"})).exitCode, 0);
    ASSERT_EQ(run(render({"--spp", "40", "-o", "straight.exr", "--quiet"})).exitCode, 0);
    EXPECT_TRUE(fileBytes(dir / "resumed.exr") == fileBytes(dir / "straight.exr"));
}

// Checked before rendering (defect 7 of issue 15): a --dump-dir that is a file, exit 1 at once.
TEST_F(CliInterrupt, DumpDirThatIsAFileIsRefusedUpFront) {
    VKP_REQUIRE_DEVICE(dev);
    std::ofstream(dir / "afile") << "x";
    const ProcessResult r = run(render({"--spp", "2", "--dump-every", "1", "--dump-dir", "afile", "-o", "x.exr"}));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("afile: --dump-dir is not a folder"), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

}  // namespace
}  // namespace vkp::test
