// The vkpath binary on bad input: one error line naming the file and place, exit code 1, and no
// output file written or clobbered. None of these cases reaches the device.
#include <gtest/gtest.h>

#include <cstdlib>
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

// The light options of the command line: a map that cannot be used, a strength or rotation without
// a map, are one line naming the option, exit 1, no output. A scene without light is one warning
// line that says what to add (`info` loads the scene as `render` does).
TEST_F(CliErrors, LightOptionsAndTheBlackSceneWarning) {
    const std::string scene = (scenesDir() / "gltf" / "no-camera.gltf").string();
    std::filesystem::remove(dir / "out.png");
    write("display.png", "not even a png");
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"--environment", "no-such-map.hdr"}, {"--environment", "display.png"},
          {"--environment-strength", "2"}, {"--environment-rotate", "30"}}) {
        std::vector<std::string> args = {"render", scene, "-o", "out.png"};
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = run(args);
        EXPECT_EQ(r.exitCode, 1) << extra[0] << ": " << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(extra[0]), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
    }
    ProcessResult r = run({"info", scene});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("warning: " + scene + " has no light"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("add --background R,G,B or --environment FILE"), std::string::npos) << r.err;
    r = run({"info", scene, "--background", "0.5"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("has no light"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("env:constant"), std::string::npos) << r.out;
    r = run({"info", scene, "--environment", (scenesDir() / "env" / "sky.hdr").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("has no light"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("env:map"), std::string::npos) << r.out;
    // A JSON scene of nothing but a glTF file: no camera, no materials (the framing camera). The
    // file is in another folder: --allow-path names it.
    write("wrap.json", R"({"objects": [{"type": "gltf", "file": ")" + scene + R"("}]})");
    r = run({"info", "wrap.json", "--background", "1"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("wrap.json: /objects/0/file: resolves to "), std::string::npos) << r.err;
    r = run({"info", "wrap.json", "--background", "1", "--allow-path", (scenesDir() / "gltf").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("image        512x512"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("12 (0 spheres, 0 quads, 12 triangles)"), std::string::npos) << r.out;
    // A scene with its own light has no warning.
    r = run({"info", (scenesDir() / "cornell-book3.json").string()});
    EXPECT_EQ(r.err.find("has no light"), std::string::npos) << r.err;
}

TEST_F(CliErrors, NoVulkanDriverIsExitCode2WithAFix) {
    // The loader finds no driver when pointed at a manifest that does not exist.
    const ProcessResult r = run({"devices"}, "VK_ICD_FILENAMES=/nonexistent/icd.json VK_DRIVER_FILES=/nonexistent/icd.json");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("apt-get install mesa-vulkan-drivers"), std::string::npos) << r.err;
    // `info` still describes the scene, and says there is no device to check the render against.
    const ProcessResult i = run({"info", (scenesDir() / "cornell-book3.json").string()},
                                "VK_ICD_FILENAMES=/nonexistent/icd.json VK_DRIVER_FILES=/nonexistent/icd.json");
    EXPECT_EQ(i.exitCode, 0) << i.err;
    EXPECT_NE(i.out.find("variant      "), std::string::npos) << i.out;
    EXPECT_NE(i.out.find("device       none"), std::string::npos) << i.out;
}

// A device, a link to one or a FIFO as the scene: one line naming it, exit 1. Under a memory limit
// and a time limit, so that a regression fails here (exit 124 or a bad_alloc) instead of reading
// /dev/zero into all the memory there is.
TEST_F(CliErrors, DevicesFifosAndLinksToThemAreRefused) {
    std::filesystem::remove(dir / "zero.json");
    std::filesystem::create_symlink("/dev/zero", dir / "zero.json");
    std::filesystem::remove(dir / "fifo.json");
    ASSERT_EQ(std::system(("mkfifo '" + (dir / "fifo.json").string() + "'").c_str()), 0);
    for (const std::string scene : {"/dev/zero", "/dev/urandom", "zero.json", "fifo.json"}) {
        const ProcessResult r = run({"info", scene}, "ulimit -v 2000000 && timeout 60");
        EXPECT_EQ(r.exitCode, 1) << scene << ": " << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(scene + ": cannot read: not a regular file"), std::string::npos) << r.err;
    }
}

// A "loader" without symbols (an empty libvulkan.so.1 on LD_LIBRARY_PATH): one line, exit 2, for
// every command that opens Vulkan, and no output file.
TEST_F(CliErrors, AStubVulkanLoaderIsExitCode2) {
    const std::string env = std::string("LD_LIBRARY_PATH='") + VKPATH_STUB_VULKAN_DIR + "'";
    ASSERT_TRUE(std::filesystem::exists(std::filesystem::path(VKPATH_STUB_VULKAN_DIR) / "libvulkan.so.1"));
    std::filesystem::remove(dir / "out.png");
    const std::string scene = (scenesDir() / "cornell-book3.json").string();
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"devices"}, {"render", scene, "--spp", "1", "-o", "out.png"}}) {
        const ProcessResult r = run(args, env);
        EXPECT_EQ(r.exitCode, 2) << args[0] << ": " << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("no usable Vulkan loader"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("libvulkan.so"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
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
