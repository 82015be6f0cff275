// A JSON scene that includes a glTF file several times, rendered with instances (`--instancing
// auto`: the file read once, its non-emissive meshes stored once, instances per node and include)
// against the same scene flattened (`--instancing flatten`). scenes/gltf/instances.gltf is included
// three times: as it is (with its panel and lamps, which stay world-space lights), turned, scaled
// down and lifted, and mirrored with every material replaced by a JSON lambertian (so its lamps,
// no longer emitting, are instanced too). The two renders use different seeds (independent noise),
// so their difference is a zero-mean estimate: z-tests on the whole image and on 16 blocks of 8 x 8
// pixels, each channel (51 tests), Sidak-corrected over the budget below (family-wise false-failure
// probability 0.01, test_gpu_analytic_common.h). 1024 spp per pixel and 64 pixels per block keep
// the block means near normal, as in test_gpu_instancing.cpp.
#include <gtest/gtest.h>

#include "gpu_env.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(60, 0.01));

Scene includesScene(bool instancing, std::uint32_t seed) {
    const std::string f = (scenesDir() / "gltf" / "instances.gltf").string();
    const std::string text =
        R"({"camera":{"lookfrom":[0,3,6.6],"lookat":[0,-0.08,0],"vup":[0,1,0],"vfov":43,"width":32,"height":32},)"
        R"("materials":{"grey":{"type":"lambertian","albedo":[0.55,0.6,0.5]}},)"
        R"("objects":[{"type":"gltf","file":")" + f + R"("},)"
        R"({"type":"gltf","file":")" + f + R"(","transform":[{"scale":0.4},{"rotate_y":40},{"translate":[0.3,1.4,-1.5]}]},)"
        R"({"type":"gltf","file":")" + f + R"(","material":"grey","transform":[{"scale":[-0.45,0.45,0.45]},{"translate":[-1.2,0.05,1.6]}]}]})";
    SceneJsonOptions o;
    o.instancing = instancing;
    o.allowPaths = {scenesDir()};  // the scene is in the scratch folder, instances.gltf in scenes/gltf
    Scene s = parseSceneJson(text, scratchDir("gpu_json_instancing") / "scene.json", o);
    s.render.seed = seed;
    return s;
}

TEST(GpuJsonInstancing, InstancedRenderAgreesWithTheFlattenedOne) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 1024;
    const Scene instanced = includesScene(true, 701);
    // blob, tetrahedron, floor (x2 includes) and blob, tetrahedron, lamp (grey): 25 instances.
    ASSERT_EQ(instanced.meshes.size(), 6u);
    ASSERT_EQ(instanced.instances.size(), 25u);
    const Scene flattened = includesScene(false, 702);
    ASSERT_TRUE(flattened.instances.empty());
    ASSERT_EQ(flattened.lights.size(), instanced.lights.size());
    const PixelStats a(renderSums(dev, instanced, Sampler::Mis, spp, "instances.gltf x 3 in JSON, instanced"));
    const PixelStats b(renderSums(dev, flattened, Sampler::Mis, spp, "instances.gltf x 3 in JSON, flattened"));
    const glm::dvec3 lit = expectRendersAgree(a, "instanced", b, "flattened", 32, 8);
    for (int c = 0; c < 3; ++c) EXPECT_GT(lit[c], 0.01) << "the scene is lit";
}

}  // namespace
}  // namespace vkp::test
