// JPEG textures (issue 6: "PNG and JPEG decoded with stb_image"): scenes/gltf/materials.gltf with
// its external checker.png swapped for a JPEG written here with stb_image_write, loaded through
// the glTF loader. A JPEG is lossy, so the image is made of flat 8 x 8 blocks (the codec's own
// blocks), which quality 100 reproduces within a few levels.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb/stb_image_write.h>

#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace {

using namespace vkp;
namespace fs = std::filesystem;

TEST(GltfJpeg, ExternalJpegTextureIsDecoded) {
    const fs::path dir = test::scratchDir("gltf_jpeg");
    const fs::path src = test::scenesDir() / "gltf";
    fs::copy_file(src / "materials.bin", dir / "materials.bin", fs::copy_options::overwrite_existing);
    // 16 x 8: two flat 8 x 8 blocks of known colours.
    const int w = 16, h = 8;
    const std::uint8_t left[3] = {200, 40, 20}, right[3] = {30, 90, 220};
    std::vector<std::uint8_t> rgb(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) rgb[3 * (std::size_t(y) * w + x) + c] = x < 8 ? left[c] : right[c];
    ASSERT_NE(stbi_write_jpg((dir / "checker.jpg").string().c_str(), w, h, 3, rgb.data(), 100), 0);
    nlohmann::json g;
    std::ifstream(src / "materials.gltf") >> g;
    bool swapped = false;
    for (auto& img : g["images"])
        if (img.value("uri", "") == "textures/checker.png") {
            img["uri"] = "checker.jpg";
            swapped = true;
        }
    ASSERT_TRUE(swapped);
    std::ofstream(dir / "materials.gltf") << g.dump();

    const Scene s = loadSceneGltf(dir / "materials.gltf");
    const TextureImage* jpeg = nullptr;
    for (const TextureImage& img : s.images)
        if (img.width == std::uint32_t(w) && img.height == std::uint32_t(h)) jpeg = &img;
    ASSERT_NE(jpeg, nullptr) << "no 16 x 8 image decoded";
    int worst = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = 4 * (std::size_t(y) * w + x);
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(jpeg->rgba8[i + c]) - int(x < 8 ? left[c] : right[c])));
            EXPECT_EQ(jpeg->rgba8[i + 3], 255);
        }
    std::printf("JPEG (quality 100, flat 8x8 blocks): largest difference %d of 255\n", worst);
    EXPECT_LE(worst, 4);
}

}  // namespace
