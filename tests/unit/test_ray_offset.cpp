// The ray offset's scale (shaders/shared/ray_offset.h rayOffsetScale, host/render/gpu_arrays.h
// sceneExtent): Wachter and Binder's absolute floor near the origin is a length sized for a scene
// about a unit across; a smaller scene scales it, and a scene scaled by a power of two is then
// offset exactly as the original, scaled. Scenes of a unit and more keep the paper's constants
// (their images are unchanged).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "bvh/flatten.h"
#include "render/gpu_arrays.h"
#include "scene/scene.h"
#include "shared/ray_offset.h"
#include "bvh_test_scenes.h"
#include "test_paths.h"

namespace {

using glm::vec3;
using vkp::gpu::offsetRayOrigin;
using vkp::gpu::rayOffsetScale;

TEST(RayOffset, ScaleIsOneFromAUnitOnAndThePowerOfTwoAtOrAboveTheExtentBelow) {
    for (float e : {1.0f, 1.5f, 555.0f, 1e30f, std::numeric_limits<float>::infinity(), 0.0f, -1.0f,
                    std::numeric_limits<float>::quiet_NaN()})
        EXPECT_EQ(rayOffsetScale(e), 1.0f) << e;
    EXPECT_EQ(rayOffsetScale(0.5f), 0.5f);
    EXPECT_EQ(rayOffsetScale(0.500001f), 1.0f);
    EXPECT_EQ(rayOffsetScale(0.3f), 0.5f);
    EXPECT_EQ(rayOffsetScale(0.25f), 0.25f);
    EXPECT_EQ(rayOffsetScale(1.4e-3f), std::ldexp(1.0f, -9));  // cornell-classic scaled by 1e-6
    for (int k = 1; k < 100; ++k) {
        const float e = std::ldexp(1.0f, -k) * 0.75f;
        EXPECT_EQ(rayOffsetScale(e), std::ldexp(1.0f, -k)) << k;
    }
}

TEST(RayOffset, ScaleOneIsThePapersOffset) {
    // Near the origin: 2^-16 along the normal; elsewhere 256 ulps.
    EXPECT_EQ(offsetRayOrigin(vec3(0.01f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), 1.0f).y, 1.0f / 65536.0f);
    const vec3 far = offsetRayOrigin(vec3(1.0f, 1.0f, 1.0f), vec3(0.0f, 1.0f, 0.0f), 1.0f);
    EXPECT_EQ(far.y, std::nextafter(1.0f, 2.0f) + 255.0f * std::ldexp(1.0f, -23));
    EXPECT_EQ(far.x, 1.0f);
}

// A point set and its copy scaled by 2^-k (k up to 60: coordinates and offsets stay normal
// floats) are offset identically up to that factor, bit for bit: with the scene's scale the
// offset does not depend on the scene's units.
TEST(RayOffset, ScaledSceneIsOffsetAsTheOriginalScaled) {
    vkp::test::Rng rng(5);
    for (int k : {1, 6, 20, 40, 60}) {
        const float f = std::ldexp(1.0f, -k);
        int differ = 0;
        for (int i = 0; i < 20000; ++i) {
            const vec3 p = rng.inBox(vec3(-1.0f), vec3(1.0f)) * (i % 3 == 0 ? 0.01f : 1.0f);
            const vec3 n = rng.direction();
            const vec3 a = offsetRayOrigin(p, n, 1.0f) * f;
            const vec3 b = offsetRayOrigin(p * f, n, f);
            differ += a != b;
        }
        EXPECT_EQ(differ, 0) << "scaled by 2^-" << k;
    }
}

TEST(RayOffset, SceneExtentIsTheLargestCoordinateOfTheBoundsRelativeToTheCamera) {
    const vkp::Scene unit = vkp::loadSceneJson(vkp::test::scenesDir() / "cornell-classic.json");
    const float e1 = vkp::sceneExtent(vkp::buildFlatBvh(unit));
    // Camera at (278, 278, -800): the far corners lie 555 - 278 = 277 across and 555 + 800 deep.
    EXPECT_NEAR(e1, 1355.0f, 1e-3f);
    EXPECT_EQ(rayOffsetScale(e1), 1.0f);
    const vkp::Scene tiny = vkp::loadSceneJson(vkp::test::scenesDir() / "stress" / "cornell-scale-1e-6.json");
    const float e6 = vkp::sceneExtent(vkp::buildFlatBvh(tiny));
    EXPECT_NEAR(e6, 1355e-6f, 1e-9f);
    EXPECT_EQ(rayOffsetScale(e6), std::ldexp(1.0f, -9));
    EXPECT_EQ(vkp::sceneExtent(vkp::FlatBvh{}), 0.0f);
}

}  // namespace
