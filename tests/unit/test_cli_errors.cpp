// The vkpath binary on bad input: one error line naming the file and place, exit code 1, and no
// output file written or clobbered. None of these cases reaches the device.
#include <gtest/gtest.h>

#include <fstream>

#include "run_process.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

struct CliErrors : ::testing::Test {
    std::filesystem::path dir = scratchDir("cli_errors");
    std::filesystem::path write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return dir / name;
    }
    ProcessResult run(const std::vector<std::string>& args, const std::string& env = "") {
        return runProcess(vkpathBinary(), args, dir, env);
    }
};

TEST_F(CliErrors, BadSceneValueNamesFileAndPointerAndWritesNothing) {
    write("bad.json", R"({"camera": {"lookfrom": [0,0,1], "lookat": [0,0,0], "vup": [0,1,0], "vfov": 40, "width": 8, "height": 8},
      "materials": {"m": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "sphere", "center": [0,0,0], "radius": -1, "material": "m"}]})");
    std::filesystem::remove(dir / "out.png");
    const ProcessResult r = run({"render", "bad.json", "-o", "out.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/objects/0/radius"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

TEST_F(CliErrors, ExistingOutputIsNotClobberedByAFailedRun) {
    write("keep.png", "precious");
    write("broken.json", "{ \"camera\": ");
    const ProcessResult r = run({"render", "broken.json", "-o", "keep.png"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    std::ifstream f(dir / "keep.png");
    std::string s((std::istreambuf_iterator<char>(f)), {});
    EXPECT_EQ(s, "precious");
}

TEST_F(CliErrors, MissingSceneFileUsageAndOutputErrors) {
    ProcessResult r = run({"render", "no-such-scene.json"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("no-such-scene.json"), std::string::npos) << r.err;
    r = run({"render", "x.json", "--spp", "-3"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    r = run({"frobnicate"});
    EXPECT_EQ(r.exitCode, 1);
    // A bad output path fails before any rendering (and before a device is needed).
    write("ok.json", R"({"camera": {"lookfrom": [0,0,1], "lookat": [0,0,0], "vup": [0,1,0], "vfov": 40, "width": 8, "height": 8},
      "materials": {}, "objects": []})");
    r = run({"render", "ok.json", "-o", "image.jpg"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("image.jpg"), std::string::npos) << r.err;
    r = run({"render", "ok.json", "-o", "no/such/dir/x.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
}

TEST_F(CliErrors, NoVulkanDriverIsExitCode2WithAFix) {
    // The loader finds no driver when pointed at a manifest that does not exist.
    const ProcessResult r = run({"devices"}, "VK_ICD_FILENAMES=/nonexistent/icd.json VK_DRIVER_FILES=/nonexistent/icd.json");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("apt-get install mesa-vulkan-drivers"), std::string::npos) << r.err;
}

TEST_F(CliErrors, HelpAndVersion) {
    ProcessResult r = run({"--help"});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("exit codes"), std::string::npos);
    r = run({"--version"});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("vkpath "), std::string::npos);
}

}  // namespace
}  // namespace vkp::test
