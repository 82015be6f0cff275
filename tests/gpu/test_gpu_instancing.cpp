// A render with instances (two-level BVH, `--instancing auto`) against the same scene flattened
// (`--instancing flatten`): scenes/gltf/instances.gltf, whose shared meshes are placed by
// translations, a rotation, a non-uniform scale and three mirrors (one of them a glass
// tetrahedron, whose refraction depends on which side is the front), with interpolated NORMALs
// under the glTF BRDF. The two renders use different seeds (independent noise), so their
// difference is a zero-mean estimate: z-tests on the whole image and on 16 blocks of 8 x 8 pixels,
// each channel (51 tests), Sidak-corrected over the budget below (family-wise false-failure
// probability 0.01, test_gpu_analytic_common.h). Every sample is a path of bounded radiance except
// through the glass, where a light seen through it is found by BSDF sampling only; 1024 spp per
// pixel and 64 pixels per block keep the block means near normal.
#include <gtest/gtest.h>

#include "gpu_env.h"
#include "scene/gltf.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(60, 0.01));

const char* const kChannel[3] = {"R", "G", "B"};

Scene instancesScene(bool instancing, std::uint32_t seed) {
    GltfOptions o;
    o.instancing = instancing;
    o.width = 32;
    o.height = 32;
    Scene s = loadSceneGltf(scenesDir() / "gltf" / "instances.gltf", o);
    s.render.seed = seed;
    return s;
}

TEST(GpuInstancing, InstancedRenderAgreesWithTheFlattenedOne) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t spp = 1024;
    const Scene instanced = instancesScene(true, 601);
    ASSERT_EQ(instanced.instances.size(), 7u);
    ASSERT_EQ(instanced.meshes.size(), 2u);
    const PixelStats a(renderSums(dev, instanced, Sampler::Mis, spp, "instances.gltf, instanced"));
    const PixelStats b(renderSums(dev, instancesScene(false, 602), Sampler::Mis, spp, "instances.gltf, flattened"));
    expectRendersAgree(a, b, 32, 8, "instanced - flattened");
}

}  // namespace
}  // namespace vkp::test
