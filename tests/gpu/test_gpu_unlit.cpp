// KHR_materials_unlit on the device (label gpu): scenes/gltf/unlit.gltf, a quad of unlit base colour
// (0.2, 0.4, 0.6) facing the camera and one turned away, under a grey sky (background 0.5) and in
// the dark. An unlit surface shows exactly its base colour whatever light falls on it (vkpath
// renders it as an emitter that reflects nothing, docs/gltf.md), and a single-sided one shows
// nothing from behind. Every sample of those pixels is the same value: exact comparisons.
#include <gtest/gtest.h>

#include <string>

#include "gpu_env.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

TEST(GpuUnlit, ShowsItsBaseColourWhateverTheLight) {
    VKP_REQUIRE_DEVICE(dev);
    const std::string file = (scenesDir() / "gltf" / "unlit.gltf").generic_string();
    // 100 above (2.5, 1): x in [-0.25, 5.25], y in [-0.25, 2.25], 44 x 20 pixels of 0.125.
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [2.5, 1, 100], "lookat": [2.5, 1, 0], "vup": [0, 1, 0], "vfov": 1.4323, "width": 44, "height": 20},
      "render": {"max_depth": 4, "background": [0.5, 0.5, 0.5]},
      "objects": [{"type": "gltf", "file": ")" + file + R"("}]})",
                                 scenesDir() / "gltf" / "unlit-test.json");
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_TRUE(scene.materials[0].pbr.unlit);
    EXPECT_EQ(scene.lights.size(), 4u);  // both quads emit (from their fronts): two triangles each
    const glm::vec3 base(0.2f, 0.4f, 0.6f);
    for (const glm::vec3 sky : {glm::vec3(0.5f), glm::vec3(0.0f)}) {
        scene.render.background = sky;
        for (Sampler s : samplersUnderTest()) {
            const PixelStats st(renderSums(dev, scene, s, 16, std::string("unlit ") + samplerName(s)));
            for (std::uint32_t j = 4; j < 16; ++j) {  // y in [0.25, 1.75]
                for (std::uint32_t i = 4; i < 16; ++i)  // x in [0.25, 1.75]: the front quad
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(st.mean.at(i, j, c), base[c], 1e-6f) << samplerName(s) << " pixel " << i << "," << j;
                for (std::uint32_t i = 28; i < 40; ++i)  // x in [3.25, 4.75]: the back of the other
                    for (int c = 0; c < 3; ++c) ASSERT_EQ(st.mean.at(i, j, c), 0.0f) << samplerName(s) << " pixel " << i << "," << j;
            }
        }
    }
}

}  // namespace
}  // namespace vkp::test
