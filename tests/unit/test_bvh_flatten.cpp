// Flattening into the GPU layout (host/bvh/flatten.h): node order and references, leaf ranges,
// tight child boxes, primitive packing (header, light index), the < 2 primitive roots, stats.
#include <algorithm>
#include <cstring>
#include <functional>
#include <string>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "bvh/flatten.h"
#include "core/errors.h"
#include "bvh_test_scenes.h"

namespace {

using namespace vkp;
using gpu::GpuNode;
using gpu::GpuPrim;

std::uint32_t bits(float f) { return glm::floatBitsToUint(f); }

Aabb childBox(const glm::vec4& lo, const glm::vec4& hi) {
    return Aabb{glm::vec3(lo), glm::vec3(hi)};
}

bool isEmptyChild(const glm::vec4& lo, const glm::vec4& hi) {
    const float big = std::numeric_limits<float>::max();
    return bits(lo.w) == gpu::GPU_NODE_EMPTY && bits(hi.w) == 0u && lo.x == big && lo.y == big && lo.z == big &&
           hi.x == -big && hi.y == -big && hi.z == -big;
}

struct Walk {
    std::size_t leaves = 0;
    std::uint32_t maxDepth = 0;
    double sah = 0.0;
};

/// Walks the flat tree from the root, checking references and tight boxes; returns the union of
/// the primitives' boxes below (node, slot) through `out`.
void checkFlat(const FlatBvh& bvh, const Scene& scene, Walk& w) {
    const std::size_t n = scene.shapes.size();
    ASSERT_FALSE(bvh.nodes.empty());
    ASSERT_EQ(bvh.prims.size(), n);
    ASSERT_EQ(bvh.primToShape.size(), n);
    std::vector<int> seenShape(n, 0);
    for (std::uint32_t s : bvh.primToShape) {
        ASSERT_LT(s, n);
        ++seenShape[s];
    }
    for (int c : seenShape) ASSERT_EQ(c, 1);

    std::vector<int> nodeRefs(bvh.nodes.size(), 0);
    std::vector<int> primRefs(n, 0);
    nodeRefs[0] = 1;
    const Aabb rootBox = [&] {
        Aabb b = childBox(bvh.nodes[0].a, bvh.nodes[0].b);
        b.grow(childBox(bvh.nodes[0].c, bvh.nodes[0].d));
        return b;
    }();
    const double rootArea = rootBox.halfArea();
    auto ratio = [&](const Aabb& b) { return rootArea > 0.0 ? b.halfArea() / rootArea : 1.0; };

    // Post-order by explicit recursion (depth <= 32): the box of everything below a child slot.
    std::function<Aabb(std::uint32_t, std::uint32_t)> visit = [&](std::uint32_t node, std::uint32_t depth) {
        const GpuNode& f = bvh.nodes[node];
        Aabb nodeBox;
        const glm::vec4* slots[2][2] = {{&f.a, &f.b}, {&f.c, &f.d}};
        for (int s = 0; s < 2; ++s) {
            const glm::vec4& lo = *slots[s][0];
            const glm::vec4& hi = *slots[s][1];
            const std::uint32_t index = bits(lo.w), count = bits(hi.w);
            const Aabb box = childBox(lo, hi);
            Aabb below;
            if (isEmptyChild(lo, hi)) {
                EXPECT_LT(n, 2u) << "empty child in a scene with >= 2 primitives";
                continue;
            }
            if (count > 0) {
                EXPECT_LE(std::size_t(index) + count, n);
                for (std::uint32_t i = index; i < index + count && i < n; ++i) {
                    ++primRefs[i];
                    below.grow(shapeBounds(scene.shapes[bvh.primToShape[i]]));
                }
                ++w.leaves;
                w.maxDepth = std::max(w.maxDepth, depth + 1);
                w.sah += ratio(box) * count;
            } else {
                EXPECT_LT(index, bvh.nodes.size());
                EXPECT_GT(index, node) << "children come after their parent";
                if (s == 0) EXPECT_EQ(index, node + 1) << "left inner child is next";
                if (index >= bvh.nodes.size() || index <= node) continue;
                EXPECT_EQ(nodeRefs[index]++, 0) << "node " << index << " referenced twice";
                below = visit(index, depth + 1);
            }
            EXPECT_EQ(box.lo, below.lo) << "child box not tight at node " << node;
            EXPECT_EQ(box.hi, below.hi) << "child box not tight at node " << node;
            nodeBox.grow(box);
        }
        w.sah += ratio(nodeBox);
        return nodeBox;
    };
    visit(0, 0);
    for (std::size_t i = 0; i < bvh.nodes.size(); ++i) EXPECT_EQ(nodeRefs[i], 1) << "node " << i;
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(primRefs[i], 1) << "primitive " << i;
}

Scene mixedScene(std::uint32_t seed) {
    std::vector<Shape> shapes = test::randomTriangles(700, seed);
    for (Shape& s : test::randomSpheres(300, seed + 1)) shapes.push_back(s);
    for (Shape& s : test::randomQuads(300, seed + 2)) shapes.push_back(s);
    Scene scene = test::makeScene(shapes);
    scene.materials.resize(5);
    for (std::size_t i = 0; i < scene.shapes.size(); ++i) scene.shapes[i].material = std::uint32_t(i % 5);
    for (std::uint32_t i = 3; i < scene.shapes.size(); i += 97) scene.lights.push_back(i);
    return scene;
}

TEST(BvhFlatten, InvariantsOnMixedScene) {
    Scene scene = mixedScene(1);
    FlatBvh bvh = buildFlatBvh(scene);
    Walk w;
    checkFlat(bvh, scene, w);
    EXPECT_EQ(bvh.stats.primCount, scene.shapes.size());
    EXPECT_EQ(bvh.stats.nodeCount, bvh.nodes.size());
    EXPECT_EQ(bvh.stats.leafCount, w.leaves);
    EXPECT_EQ(bvh.stats.leafCount, bvh.nodes.size() + 1);  // a full binary tree
    EXPECT_EQ(bvh.stats.maxDepth, w.maxDepth);
    EXPECT_LE(bvh.stats.maxDepth, 32u);
    EXPECT_NEAR(bvh.stats.sahCost, w.sah, 1e-6 * w.sah);
    EXPECT_GE(bvh.stats.buildMs, 0.0);
    EXPECT_GE(bvh.stats.flattenMs, 0.0);
}

TEST(BvhFlatten, PacksShapes) {
    Scene scene = mixedScene(2);
    FlatBvh bvh = buildFlatBvh(scene);
    std::vector<std::uint32_t> lightOf(scene.shapes.size(), 0);
    for (std::size_t l = 0; l < scene.lights.size(); ++l) lightOf[scene.lights[l]] = std::uint32_t(l + 1);
    for (std::size_t i = 0; i < bvh.prims.size(); ++i) {
        const std::uint32_t si = bvh.primToShape[i];
        const Shape& s = scene.shapes[si];
        const GpuPrim& p = bvh.prims[i];
        ASSERT_EQ(gpu::primKind(p), static_cast<std::uint32_t>(s.type));
        ASSERT_EQ(gpu::primMaterial(p), s.material);
        ASSERT_EQ(gpu::primLight(p), int(lightOf[si]) - 1);
        ASSERT_EQ(glm::vec3(p.p0), s.p0);
        if (s.type == ShapeType::Sphere) {
            ASSERT_EQ(p.p1.w, s.radius);
        } else if (s.type == ShapeType::Quad) {
            ASSERT_EQ(glm::vec3(p.p1), s.p1);
            ASSERT_EQ(glm::vec3(p.p2), s.p2);
        } else {
            ASSERT_EQ(glm::vec3(p.p1), s.p1);
            ASSERT_EQ(glm::vec3(p.p2), s.p2);
        }
    }
    // Header of a known shape.
    Shape q = test::quad(glm::vec3(1), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), 12345);
    GpuPrim p = packShape(q, 7);
    EXPECT_EQ(bits(p.p0.w), 1u | (12345u << 2));
    EXPECT_EQ(bits(p.p2.w), 7u);
    EXPECT_EQ(gpu::primLight(p), 6);
}

TEST(BvhFlatten, FewPrimitiveRoots) {
    Scene empty = test::makeScene({});
    FlatBvh b0 = buildFlatBvh(empty);
    ASSERT_EQ(b0.nodes.size(), 1u);
    EXPECT_TRUE(isEmptyChild(b0.nodes[0].a, b0.nodes[0].b));
    EXPECT_TRUE(isEmptyChild(b0.nodes[0].c, b0.nodes[0].d));
    EXPECT_TRUE(b0.prims.empty());
    EXPECT_EQ(b0.stats.leafCount, 0u);
    EXPECT_EQ(b0.stats.sahCost, 0.0);

    Scene one = test::makeScene({test::sphere(glm::vec3(0, 0, -1), 0.5f)});
    one.lights = {0};
    FlatBvh b1 = buildFlatBvh(one);
    ASSERT_EQ(b1.nodes.size(), 1u);
    EXPECT_EQ(bits(b1.nodes[0].a.w), 0u);
    EXPECT_EQ(bits(b1.nodes[0].b.w), 1u);
    EXPECT_EQ(glm::vec3(b1.nodes[0].a), glm::vec3(-0.5f, -0.5f, -1.5f));
    EXPECT_TRUE(isEmptyChild(b1.nodes[0].c, b1.nodes[0].d));
    EXPECT_EQ(gpu::primLight(b1.prims[0]), 0);
    EXPECT_EQ(b1.stats.leafCount, 1u);
    EXPECT_EQ(b1.stats.maxDepth, 1u);
    EXPECT_EQ(b1.stats.sahCost, 2.0);  // root node + one primitive, same box
    Walk w1;
    checkFlat(b1, one, w1);

    for (std::size_t n = 2; n <= 9; ++n) {
        Scene s = test::makeScene(test::randomTriangles(n, 50 + std::uint32_t(n)));
        FlatBvh b = buildFlatBvh(s);
        Walk w;
        checkFlat(b, s, w);
        EXPECT_EQ(b.stats.leafCount, b.nodes.size() + 1);
    }
}

TEST(BvhFlatten, BadInputIsInputError) {
    Scene nanScene = test::makeScene({test::sphere(glm::vec3(0), 1.0f), test::sphere(glm::vec3(0, std::nanf(""), 0), 1.0f)});
    try {
        buildFlatBvh(nanScene);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("shape 1"), std::string::npos) << e.what();
    }
    Scene inf = test::makeScene({test::quad(glm::vec3(3e38f), glm::vec3(3e38f, 0, 0), glm::vec3(0, 1, 0))});
    EXPECT_THROW(buildFlatBvh(inf), InputError);
    Scene badRadius = test::makeScene({test::sphere(glm::vec3(0), std::numeric_limits<float>::infinity())});
    EXPECT_THROW(buildFlatBvh(badRadius), InputError);
    Scene badLight = test::makeScene({test::sphere(glm::vec3(0), 1.0f)});
    badLight.lights = {1};
    EXPECT_THROW(buildFlatBvh(badLight), InputError);
    Scene badMaterial = test::makeScene({test::sphere(glm::vec3(0), 1.0f, 1u << 30)});
    EXPECT_THROW(buildFlatBvh(badMaterial), InputError);
}

TEST(BvhFlatten, MismatchedTreeIsRejected) {
    Scene a = test::makeScene(test::randomTriangles(10, 1));
    Scene b = test::makeScene(test::randomTriangles(11, 1));
    BvhBuildTree tree = buildBvh(std::span<const Shape>(a.shapes));
    EXPECT_THROW(flattenBvh(tree, b), std::invalid_argument);
}

}  // namespace
