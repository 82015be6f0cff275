// The Khronos glTF sample models (tests/data/khronos-samples: glTF-Embedded variants, copied byte for
// byte; README.md there lists their sources) rendered by the vkpath binary as a user runs it
// (label gpu): each exits 0, prints exactly the warnings listed below for it (skins, morph targets,
// animations, points and lines: what vkpath does not render, said once each) and nothing from the
// validation layer, and its image is lit and not constant. `--background 1` lights them: none
// brings a light. The two texture tests are authored to be seen from -Z (a back plane covers them
// from +Z) and are rendered through small JSON scenes that place the camera there.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "image_checks.h"
#include "run_process.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

struct Sample {
    const char* file;
    std::vector<std::string> warnings;  ///< a fragment of each expected warning line, in order
};

const std::vector<Sample>& samples() {
    static const std::vector<Sample> list = {
        {"Triangle.gltf", {}},
        {"TriangleWithoutIndices.gltf", {}},
        {"SimpleMeshes.gltf", {}},
        {"SimpleSparseAccessor.gltf", {}},
        {"MultipleScenes.gltf", {}},
        {"Cameras.gltf", {}},
        {"Box.gltf", {}},
        {"BoxTextured.gltf", {}},
        {"BoxVertexColors.gltf", {}},
        {"SimpleMaterial.gltf", {}},
        {"SimpleTexture.gltf", {}},
        {"MultiUVTest.gltf", {}},
        {"OrientationTest.gltf", {}},
        {"Duck.gltf", {}},
        {"TextureCoordinateTest.from-back.json", {}},
        {"TextureSettingsTest.from-back.json", {}},
        {"MeshPrimitiveModes.gltf",
         {"mesh 0 (\"mesh with POINTS\") primitive 0: mode 0 (POINTS): points and lines are not rendered",
          "mesh 1 (\"mesh with LINES\") primitive 0: mode 1 (LINES)", "mesh 2 (\"mesh with LINE_LOOP\") primitive 0: mode 2 (LINE_LOOP)",
          "mesh 3 (\"mesh with LINE_STRIP\") primitive 0: mode 3 (LINE_STRIP)"}},
        {"AnimatedTriangle.gltf", {"animations: ignored: the scene is drawn at rest"}},
        {"BoxAnimated.gltf", {"animations: ignored: the scene is drawn at rest"}},
        {"SimpleMorph.gltf", {"mesh 0: morph targets ignored: the base shape is drawn", "animations: ignored"}},
        {"SimpleSkin.gltf", {"node 0: skin ignored: the mesh is drawn in its bind pose", "animations: ignored"}},
        {"RiggedSimple.gltf", {"node 1: skin ignored: the mesh is drawn in its bind pose", "animations: ignored"}},
        {"RiggedFigure.gltf", {"node 1 (\"Proxy\"): skin ignored: the mesh is drawn in its bind pose", "animations: ignored"}},
        {"CesiumMan.gltf", {"node 2 (\"Cesium_Man\"): skin ignored: the mesh is drawn in its bind pose", "animations: ignored"}},
        {"Monster.gltf", {"node 1: skin ignored: the mesh is drawn in its bind pose", "animations: ignored"}},
    };
    return list;
}

/// The lines of s that contain "warning:".
std::vector<std::string> warningLines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string line; std::getline(in, line);)
        if (line.find("warning:") != std::string::npos) out.push_back(line);
    return out;
}

class KhronosSample : public ::testing::TestWithParam<Sample> {};

TEST_P(KhronosSample, RendersWithItsWarningsOnly) {
    const Sample& s = GetParam();
    const std::filesystem::path dir = sourceDir() / "tests" / "data" / "khronos-samples";
    const std::filesystem::path scratch = scratchDir("khronos_samples");
    const std::filesystem::path out = scratch / (std::string(s.file) + ".pfm");
    std::filesystem::remove(out);
    const ProcessResult r = runProcess(vkpathBinary(), {"render", (dir / s.file).string(), "--validate", "--background", "1",
                                                        "--width", "48", "--height", "48", "--spp", "4", "--quiet", "-o",
                                                        out.string()},
                                       scratch);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("alidation"), std::string::npos) << r.err;
    const std::vector<std::string> got = warningLines(r.err);
    ASSERT_EQ(got.size(), s.warnings.size()) << r.err;
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NE(got[i].find(s.warnings[i]), std::string::npos) << got[i];
    const Image img = readImage(out);
    EXPECT_TRUE(litAndNotConstant(img, s.file));
}

std::string sampleName(const ::testing::TestParamInfo<Sample>& info) {
    std::string n = info.param.file;
    n = n.substr(0, n.find('.'));
    if (std::string(info.param.file).find(".json") != std::string::npos) n += "FromBack";
    return n;
}

INSTANTIATE_TEST_SUITE_P(Models, KhronosSample, ::testing::ValuesIn(samples()), sampleName);

}  // namespace
}  // namespace vkp::test
