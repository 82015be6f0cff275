// Motion blur on the host ("Ray Tracing: The Next Week", sec. 2; docs/design.md "Motion blur"):
//  - the BVH bounds what moves over the whole shutter interval: shapeBounds holds a moving shape
//    at every time in [0, 1], and the kernel's traversal (its CPU twin, over the primitives moved
//    as the kernel moves them) finds every hit that brute force finds, at several times;
//  - the per-primitive motion the kernel reads follows the BVH's order, the variant compiles motion
//    in only for scenes with it, and the ray offset's scale covers where things end up;
//  - the JSON loader: a sphere's "center1" (through its transform), "motion" on every shape kind
//    and on a glTF include (then placed in the world, not instanced), and a moving include's
//    punctual lights refused. The loader's one-line errors: tests/unit/test_scene_errors.cpp.
// Everything here is deterministic (fixed seeds): no false failures.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bvh/build.h"
#include "bvh/flatten.h"
#include "bvh/traverse_wide_cpu.h"
#include "bvh/two_level.h"
#include "bvh_test_scenes.h"
#include "core/errors.h"
#include "render/features.h"
#include "render/gpu_arrays.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "shared/intersect.h"
#include "shared/ray_offset.h"
#include "test_paths.h"

namespace {

using namespace vkp;

/// Times the tests look at: both ends, the float just below 1, and some between.
const float kTimes[] = {0.0f, 1e-7f, 0.25f, 0.5f, 0.75f, std::nextafter(1.0f, 0.0f), 1.0f};

/// The shape without its motion (its box is where it is now).
Shape still(Shape s) {
    s.velocity = glm::vec3(0.0f);
    return s;
}

Shape moving(Shape s, glm::vec3 velocity) {
    s.velocity = velocity;
    return s;
}

TEST(MotionBounds, HoldAMovingShapeAtEveryTime) {
    const std::vector<Shape> shapes = {
        moving(test::sphere({1.0f, 2.0f, 3.0f}, 0.5f), {0.0f, 0.37f, -4.0f}),
        moving(test::quad({-1.0f, 0.1f, 2.0f}, {2.0f, 0.0f, 0.3f}, {0.0f, 1.5f, 0.0f}), {-3.3f, 0.0f, 1e-3f}),
        moving(test::triangle({0.0f, 0.0f, 1.0f}, {-1.0f, 2.0f, 0.0f}, {3.0f, 1.0f, 0.0f}), {1e5f, -2.0f, 7.0f}),
        moving(test::sphere({1e6f, -3e5f, 0.1f}, 2.0f), {-0.1f, 0.2f, 1e6f}),
    };
    for (const Shape& s : shapes) {
        const Aabb box = shapeBounds(s);
        for (float t : kTimes) EXPECT_TRUE(box.contains(shapeBounds(still(shapeAt(s, t))))) << "time " << t;
        // Exactly the union of both ends: no looser.
        Aabb ends = shapeBounds(still(s));
        ends.grow(shapeBounds(still(shapeAt(s, 1.0f))));
        EXPECT_EQ(box.lo, ends.lo);
        EXPECT_EQ(box.hi, ends.hi);
    }
    // A still shape's box is what it always was.
    const Shape q = test::quad({0.0f, 1.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -3.0f});
    EXPECT_EQ(shapeBounds(q).lo, glm::vec3(0.0f, 1.0f, -3.0f));
    EXPECT_EQ(shapeBounds(q).hi, glm::vec3(2.0f, 1.0f, 0.0f));
}

/// 300 still spheres and 60 moving spheres, quads and triangles that cross the scene.
Scene movingScene() {
    std::vector<Shape> shapes = test::randomSpheres(300, 11);
    test::Rng rng(12);
    const std::vector<Shape> tris = test::randomTriangles(20, 13), quads = test::randomQuads(20, 14), balls = test::randomSpheres(20, 15);
    for (const std::vector<Shape>* kind : {&tris, &quads, &balls})
        for (const Shape& s : *kind) shapes.push_back(moving(s, 8.0f * rng.direction()));
    return test::makeScene(std::move(shapes));
}

TEST(MotionBounds, TheTraversalFindsMovingPrimitivesAtEveryTime) {
    const Scene scene = movingScene();
    const FlatBvh bvh = buildSceneBvh(scene);
    const std::vector<gpu::GpuMotion> motion = packMotion(scene, bvh);
    ASSERT_EQ(motion.size(), bvh.prims.size());
    std::size_t hits = 0, checked = 0;
    for (float t : kTimes) {
        // The primitives where the kernel sees them at time t (lib/bindings.glsl fetchPrim).
        std::vector<gpu::GpuPrim> moved(bvh.prims.size());
        std::vector<Shape> movedShapes;
        for (std::size_t i = 0; i < moved.size(); ++i) {
            moved[i] = gpu::primMoved(bvh.prims[i], t * glm::vec3(motion[i].v));
            const Shape& s = *primShape(scene, bvh, i);
            if (s.moves()) movedShapes.push_back(shapeAt(s, t));
        }
        // Rays aimed at the moving shapes (randomRays: one in three aims at a shape), and others.
        for (const test::Ray& r : test::randomRays(movedShapes, 3000, 17 + std::uint32_t(1e6f * t))) {
            const test::BruteHit want = test::bruteForce(moved, r);
            const TraceResult got = traceClosestWideCpu(bvh.wideNodes, moved, r.o, r.d, r.tmin, r.tmax);
            ++checked;
            hits += want.hit;
            ASSERT_EQ(got.hit, want.hit) << "time " << t;
            if (want.hit) EXPECT_EQ(got.t, want.t) << "time " << t;
        }
    }
    std::printf("  %zu rays at %zu times, %zu hits: the BVH found every one\n", checked, std::size(kTimes), hits);
    EXPECT_GT(hits, checked / 5);
}

TEST(MotionPack, TheKernelReadsEachPrimitivesMotionInTheBvhsOrder) {
    const Scene scene = movingScene();
    const FlatBvh bvh = buildSceneBvh(scene);
    const GpuArrays a = packGpuArrays(scene, bvh, RenderOptions{});
    EXPECT_TRUE(a.features.motion);
    EXPECT_NE(a.features.name().find("motion"), std::string::npos) << a.features.name();
    ASSERT_EQ(a.motion.size(), a.prims.size());
    std::size_t movingPrims = 0;
    for (std::size_t i = 0; i < a.prims.size(); ++i) {
        const Shape& s = *primShape(scene, bvh, i);
        EXPECT_EQ(glm::vec3(a.motion[i].v), s.velocity) << i;
        EXPECT_EQ(a.motion[i].v.w, 0.0f);
        movingPrims += s.moves();
    }
    EXPECT_EQ(movingPrims, 60u);
    EXPECT_EQ(a.hostData(VKP_BINDING_MOTION).size(), a.prims.size() * sizeof(gpu::GpuMotion));
    // The ray offset's scale covers where the primitives end up.
    float extent = 0.0f;
    for (const Shape& s : scene.shapes) {
        const Aabb b = shapeBounds(s);
        for (int k = 0; k < 3; ++k) extent = std::max({extent, std::abs(b.lo[k]), std::abs(b.hi[k])});
    }
    EXPECT_EQ(a.frame.origin.w, gpu::rayOffsetScale(extent));

    // Without motion: HAS_MOTION off, one token texel; --variant full reads every primitive's (0).
    Scene still = scene;
    for (Shape& s : still.shapes) s.velocity = glm::vec3(0.0f);
    const FlatBvh stillBvh = buildSceneBvh(still);
    const GpuArrays b = packGpuArrays(still, stillBvh, RenderOptions{});
    EXPECT_FALSE(b.features.motion);
    EXPECT_EQ(b.features.name().find("motion"), std::string::npos) << b.features.name();
    EXPECT_EQ(b.motion.size(), 1u);
    EXPECT_EQ(b.features.specConstants().at(VKP_SPEC_HAS_MOTION), 0u);
    RenderOptions full;
    full.fullVariant = true;
    const GpuArrays c = packGpuArrays(still, stillBvh, full);
    EXPECT_TRUE(c.features.motion);
    ASSERT_EQ(c.motion.size(), c.prims.size());
    for (const gpu::GpuMotion& m : c.motion) EXPECT_EQ(m.v, glm::vec4(0.0f));
}

const char* kCamera = R"("camera":{"lookfrom":[0,0,10],"lookat":[0,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8})";

TEST(MotionJson, Center1AndMotionGiveEachShapeItsVelocity) {
    const Scene s = parseSceneJson(std::string("{") + kCamera + R"(,
      "materials": {"m": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [
        {"type": "sphere", "center": [1, 0, 0], "center1": [1, 2, 0], "radius": 1, "material": "m",
         "transform": [{"scale": 2}, {"rotate_z": 90}, {"translate": [0, 0, -5]}]},
        {"type": "sphere", "center": [1, 0, 0], "center1": [1, 2, 0], "radius": 1, "material": "m",
         "motion": {"translate": [0, 0, 1]}},
        {"type": "sphere", "center": [1, 0, 0], "center1": [1, 0, 0], "radius": 1, "material": "m"},
        {"type": "quad", "Q": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0], "material": "m", "motion": {"translate": [0.5, 0, 0]}},
        {"type": "triangle", "v0": [0, 0, 0], "v1": [1, 0, 0], "v2": [0, 1, 0], "material": "m",
         "transform": [{"rotate_y": 90}], "motion": {"translate": [0, -0.25, 3]}},
        {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "m", "motion": {"translate": [1, 2, 3]}},
        {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}
      ]})",
                                   "motion.json");
    ASSERT_EQ(s.shapes.size(), 12u);
    // center1 - center = (0, 2, 0), scaled by 2 and turned by 90 degrees about z: (-4, 0, 0).
    EXPECT_NEAR(s.shapes[0].velocity.x, -4.0f, 1e-6f);
    EXPECT_NEAR(s.shapes[0].velocity.y, 0.0f, 1e-6f);
    EXPECT_EQ(s.shapes[0].velocity.z, 0.0f);
    EXPECT_EQ(s.shapes[1].velocity, glm::vec3(0.0f, 2.0f, 1.0f));  // both: they add up
    EXPECT_FALSE(s.shapes[2].moves());                               // center1 = center: still
    EXPECT_EQ(s.shapes[3].velocity, glm::vec3(0.5f, 0.0f, 0.0f));
    EXPECT_EQ(s.shapes[4].velocity, glm::vec3(0.0f, -0.25f, 3.0f));  // world units: not turned by the transform
    for (int i = 5; i < 11; ++i) EXPECT_EQ(s.shapes[i].velocity, glm::vec3(1.0f, 2.0f, 3.0f)) << "box face " << i - 5;
    EXPECT_FALSE(s.shapes[11].moves());
    EXPECT_TRUE(sceneFeatures(s).motion);
    // Where it starts is where a still copy is (the shape at time 0 is the file's).
    EXPECT_EQ(s.shapes[3].p0, glm::vec3(0.0f, 0.0f, -10.0f));
}

TEST(MotionJson, AMovingGltfIncludeIsPlacedInTheWorldNotInstanced) {
    const std::string file = (test::scenesDir() / "gltf" / "instances.gltf").string();
    SceneJsonOptions o;
    o.instancing = true;
    o.allowPaths = {test::scenesDir()};
    const Scene s = parseSceneJson(std::string("{") + kCamera + R"(,
      "objects": [
        {"type": "gltf", "file": ")" + file + R"("},
        {"type": "gltf", "file": ")" + file + R"(", "motion": {"translate": [0, 1, 0]}, "transform": [{"translate": [5, 0, 0]}]}
      ]})",
                                   test::scratchDir("motion_json") / "include.json", o);
    const Scene flat = loadSceneGltf(test::scenesDir() / "gltf" / "instances.gltf");
    // The still include keeps its instances; the moving one is every triangle of the file, placed.
    EXPECT_FALSE(s.instances.empty());
    std::size_t movingShapes = 0;
    for (const Shape& sh : s.shapes)
        if (sh.moves()) {
            EXPECT_EQ(sh.velocity, glm::vec3(0.0f, 1.0f, 0.0f));
            ++movingShapes;
        }
    EXPECT_EQ(movingShapes, flat.shapes.size());
    for (const InstancedMesh& m : s.meshes)
        for (const Shape& sh : m.shapes) EXPECT_FALSE(sh.moves());
    // The moving include's emitters are lights, moving with it.
    std::size_t movingLights = 0;
    for (std::uint32_t l : s.lights) movingLights += s.shapes[l].moves();
    EXPECT_EQ(movingLights, flat.lights.size());
    EXPECT_GT(movingLights, 0u);
}

TEST(MotionJson, AMovingIncludeWithPunctualLightsIsRefused) {
    const std::string file = (test::scenesDir() / "gltf" / "point-lamp.gltf").string();
    SceneJsonOptions o;
    o.allowPaths = {test::scenesDir()};
    const std::string text = std::string("{") + kCamera + R"(,"objects": [{"type": "gltf", "file": ")" + file +
                             R"(", "motion": {"translate": [0, 1, 0]}}]})";
    try {
        (void)parseSceneJson(text, "lamp.json", o);
        FAIL() << "accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("lamp.json: /objects/0/motion: the glTF file has punctual lights", 0), 0u) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos);
    }
    // Still, the same include is fine.
    EXPECT_NO_THROW((void)parseSceneJson(std::string("{") + kCamera + R"(,"objects": [{"type": "gltf", "file": ")" + file + R"("}]})",
                                         "lamp.json", o));
}

}  // namespace
