// The command line with glTF scenes: --gltf-scene and --camera, warnings on stderr, one error
// line and exit code 1 for a broken file. `vkpath info` never opens a device.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "cli/args.h"
#include "core/errors.h"
#include "run_process.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

TEST(GltfCliArgs, SceneAndCameraFlags) {
    const CliArgs a = parseArgs({"render", "x.glb", "--gltf-scene", "2", "--camera", "1", "--width", "300"});
    EXPECT_EQ(a.command, Command::Render);
    EXPECT_EQ(a.gltfScene, 2u);
    EXPECT_EQ(a.camera, 1u);
    EXPECT_EQ(a.width, 300u);
    EXPECT_FALSE(a.height);
    const CliArgs i = parseArgs({"info", "x.gltf", "--camera", "0"});  // not a render-only option
    EXPECT_EQ(i.command, Command::Info);
    EXPECT_EQ(i.camera, 0u);
    EXPECT_FALSE(i.gltfScene);
    EXPECT_THROW(parseArgs({"render", "x.gltf", "--camera", "-1"}), InputError);
    EXPECT_THROW(parseArgs({"render", "x.gltf", "--gltf-scene"}), InputError);
}

struct GltfCli : ::testing::Test {
    std::filesystem::path dir = scratchDir("gltf_cli");
    ProcessResult run(const std::vector<std::string>& args) { return runProcess(vkpathBinary(), args, dir); }
};

TEST_F(GltfCli, InfoPrintsTheWarningsOfAGltfFile) {
    // The file's one warning, then (it has no light) the black-scene one.
    const ProcessResult r = run({"info", (scenesDir() / "gltf" / "extensions.gltf").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(lineCount(r.err), 2) << r.err;
    EXPECT_NE(r.err.find("has no light"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.rfind("vkpath: warning: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("extensions.gltf: extensionsUsed: extension KHR_materials_variants is not supported"), std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find("1 triangles"), std::string::npos) << r.out;
}

TEST_F(GltfCli, InfoOfAGlbAndItsOtherScene) {
    const ProcessResult r = run({"info", (scenesDir() / "gltf" / "hierarchy.gltf").string(), "--gltf-scene", "0",
                                 "--background", "1"});  // it has no light of its own
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("1 triangles"), std::string::npos) << r.out;
    const ProcessResult g = run({"info", (scenesDir() / "gltf" / "emissive.glb").string()});
    EXPECT_EQ(g.exitCode, 0) << g.err;
    EXPECT_NE(g.out.find("image        512x341"), std::string::npos) << g.out;
    EXPECT_NE(g.out.find("3 sampled objects (3 emitting)"), std::string::npos) << g.out;
}

TEST_F(GltfCli, InfoWithSpatialSplitsCountsTheReferences) {
    const std::string scene = (scenesDir() / "gltf" / "include-instances.json").string();
    const ProcessResult plain = run({"info", scene});
    const ProcessResult r = run({"info", scene, "--spatial-splits"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(plain.out.find("spatial      splits on"), std::string::npos) << plain.out;
    const std::size_t at = r.out.find("spatial      splits on: ");
    ASSERT_NE(at, std::string::npos) << r.out;
    std::size_t refs = 0, prims = 0;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "spatial      splits on: %zu primitive references on the device for %zu", &refs, &prims), 2)
        << r.out;
    EXPECT_GE(refs, prims);
    EXPECT_GT(prims, 0u);
}

TEST_F(GltfCli, InfoOfAJsonSceneIncludingAFileSeveralTimes) {
    const std::string scene = (scenesDir() / "gltf" / "include-instances.json").string();
    const ProcessResult a = run({"info", scene});  // --instancing auto is the default
    EXPECT_EQ(a.exitCode, 0) << a.err;
    EXPECT_TRUE(a.err.empty()) << a.err;
    EXPECT_NE(a.out.find("instancing   25 instances of 6 shared meshes"), std::string::npos) << a.out;
    EXPECT_NE(a.out.find("MB two-level (auto); flattened (--instancing flatten) about "), std::string::npos) << a.out;
    EXPECT_NE(a.out.find("lights       12 sampled objects (12 emitting)"), std::string::npos) << a.out;
    const ProcessResult f = run({"info", scene, "--instancing", "flatten"});
    EXPECT_EQ(f.exitCode, 0) << f.err;
    EXPECT_NE(f.out.find("instancing   none (--instancing flatten): geometry on the device"), std::string::npos) << f.out;
    EXPECT_NE(f.out.find("lights       12 sampled objects (12 emitting)"), std::string::npos) << f.out;
    EXPECT_NE(f.out.find("materials    6"), std::string::npos) << f.out;  // sage + the file's 5, once
}

TEST_F(GltfCli, ErrorsAreOneLineWithExitCode1) {
    std::ofstream(dir / "broken.glb", std::ios::binary) << "glTF\x02";
    std::filesystem::remove(dir / "out.png");
    const ProcessResult r = run({"render", "broken.glb", "-o", "out.png"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("vkpath: error: broken.glb: GLB header: truncated", 0), 0u) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));

    const ProcessResult s = run({"info", (scenesDir() / "gltf" / "modes.gltf").string(), "--gltf-scene", "3"});
    EXPECT_EQ(s.exitCode, 1) << s.err;
    EXPECT_NE(s.err.find("--gltf-scene 3: scene 3 does not exist (the file has 1 scene)"), std::string::npos) << s.err;

    const ProcessResult j = run({"info", (scenesDir() / "cornell-classic.json").string(), "--camera", "0"});
    EXPECT_EQ(j.exitCode, 1) << j.err;
    EXPECT_NE(j.err.find("--gltf-scene and --camera are for .gltf and .glb scenes"), std::string::npos) << j.err;
}

}  // namespace
}  // namespace vkp::test
