// A render with instances (two-level BVH, `--instancing auto`) against the same scene flattened
// (`--instancing flatten`): scenes/gltf/instances.gltf, whose shared meshes are placed by
// translations, a rotation, a non-uniform scale and three mirrors (one of them a glass
// tetrahedron, whose refraction depends on which side is the front), with interpolated NORMALs
// under the glTF BRDF. The two renders use different seeds (independent noise), so their
// difference is a zero-mean estimate: z-tests on the whole image and on 16 blocks of 8 x 8 pixels,
// each channel (51 tests), Sidak-corrected over the budget below (family-wise false-failure
// probability 0.01, test_gpu_analytic_common.h). Every sample is a path of bounded radiance except
// through the glass, where a light seen through it is found by BSDF sampling only; 1024 spp per
// pixel and 64 pixels per block keep the block means near normal. The instances must show: the
// image with them differs from the same scene without them (its shared meshes removed) by more
// than the critical z of the budget in each channel (3 tests more), so two renders that both lost
// the instanced meshes cannot pass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gpu_env.h"
#include "scene/gltf.h"
#include "test_gpu_analytic_common.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

[[maybe_unused]] ::testing::Environment* const kBudget =
    ::testing::AddGlobalTestEnvironment(new ZBudgetEnvironment(60, 0.01));

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
    const glm::dvec3 lit = expectRendersAgree(a, "instanced", b, "flattened", 32, 8);
    Scene bare = instancesScene(true, 603);
    bare.meshes.clear();
    bare.instances.clear();
    const PixelStats c(renderSums(dev, bare, Sampler::Mis, spp, "instances.gltf without its shared meshes"));
    const std::vector<Pixel> all = rect(0, 0, 32, 32);
    for (int ch = 0; ch < 3; ++ch) {
        const Estimate d = difference(a, c, all, ch);
        EXPECT_DOUBLE_EQ(average(a, all, ch).mean, lit[ch]);
        const double z = zBudget().take();
        EXPECT_GT(std::abs(d.mean), z * std::sqrt(d.var))
            << "the instanced meshes change the image mean " << lit[ch] << " by " << d.mean << " (channel " << kChannel[ch]
            << "): they must be seen";
        std::printf("  instanced meshes change the image mean (%s) by %+.4g = %+.1f se\n", kChannel[ch], d.mean,
                    d.mean / std::sqrt(d.var));
    }
}

}  // namespace
}  // namespace vkp::test
