// CPU traversal of the flattened BVH (tests/support/binary_bvh/traverse_binary_cpu.h) against brute force over every
// primitive: closest t and primitive, any-hit agreement, on random triangles, spheres, quads, a
// mix, a dense mesh, axis-parallel rays on box planes, tiny scenes; the pass guard and the
// documented stack-overflow behaviour.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "bvh/flatten.h"
#include "traverse_binary_cpu.h"
#include "bvh_test_scenes.h"

namespace {

using namespace vkp;
using test::Ray;

struct Summary {
    std::size_t hits = 0;
    std::uint32_t maxPasses = 0;
};

/// Traces every ray with both CPU traversals and brute force; they must agree exactly on t.
Summary compare(const FlatBvh& bvh, const std::vector<Ray>& rays) {
    Summary sum;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Ray& r = rays[i];
        const test::BruteHit ref = test::bruteForce(bvh.prims, r);
        const TraceResult c = traceClosestCpu(bvh, r.o, r.d, r.tmin, r.tmax);
        EXPECT_FALSE(c.cutShort()) << "ray " << i;
        EXPECT_EQ(c.hit, ref.hit) << "ray " << i;
        if (c.hit && ref.hit) {
            EXPECT_EQ(c.t, ref.t) << "ray " << i;
            glm::vec2 ab;
            const float own = gpu::intersectPrim(bvh.prims.at(c.prim), r.o, r.d, r.tmin,
                                                 std::min(r.tmax, gpu::VKP_FAR), ab);
            EXPECT_EQ(own, c.t) << "ray " << i << ": reported primitive does not give t";  // ties allowed
            EXPECT_EQ(ab, c.ab) << "ray " << i;
            ++sum.hits;
        }
        if (!c.hit) {
            EXPECT_EQ(c.t, gpu::VKP_FAR);
            EXPECT_EQ(c.prim, gpu::GPU_NODE_EMPTY);
        }
        const TraceResult a = traceAnyCpu(bvh, r.o, r.d, r.tmin, r.tmax);
        EXPECT_FALSE(a.cutShort()) << "ray " << i;
        EXPECT_EQ(a.hit, ref.hit) << "any-hit, ray " << i;
        if (a.hit) {
            EXPECT_GT(a.t, r.tmin);
            EXPECT_LT(a.t, r.tmax);
            EXPECT_LE(a.passes, c.passes + 2u * 32u) << "any-hit should not do more work";
        }
        sum.maxPasses = std::max({sum.maxPasses, c.passes, a.passes});
        if (::testing::Test::HasFailure()) break;  // one ray's report is enough
    }
    return sum;
}

FlatBvh build(const std::vector<Shape>& shapes, Scene& keep) {
    keep = test::makeScene(shapes);
    return buildFlatBvh(keep);
}

TEST(BvhTraverse, RandomTriangles) {
    Scene s;
    FlatBvh bvh = build(test::randomTriangles(2000, 1), s);
    Summary sum = compare(bvh, test::randomRays(s.shapes, 2000, 2));
    EXPECT_GT(sum.hits, 600u);
}

TEST(BvhTraverse, RandomSpheres) {
    Scene s;
    FlatBvh bvh = build(test::randomSpheres(2000, 3), s);
    Summary sum = compare(bvh, test::randomRays(s.shapes, 2000, 4));
    EXPECT_GT(sum.hits, 600u);
}

TEST(BvhTraverse, RandomQuads) {
    Scene s;
    FlatBvh bvh = build(test::randomQuads(2000, 5), s);
    Summary sum = compare(bvh, test::randomRays(s.shapes, 2000, 6));
    EXPECT_GT(sum.hits, 600u);
}

TEST(BvhTraverse, Mix) {
    std::vector<Shape> shapes = test::randomTriangles(1000, 7);
    for (const Shape& x : test::randomSpheres(500, 8)) shapes.push_back(x);
    for (const Shape& x : test::randomQuads(500, 9)) shapes.push_back(x);
    // Spheres inside spheres and a negative radius (the book's hollow glass).
    shapes.push_back(test::sphere(glm::vec3(0), 3.0f));
    shapes.push_back(test::sphere(glm::vec3(0), -2.5f));
    Scene s;
    FlatBvh bvh = build(shapes, s);
    Summary sum = compare(bvh, test::randomRays(s.shapes, 2500, 10));
    EXPECT_GT(sum.hits, 800u);
}

// A dense mesh: a tessellated sphere of 100,352 triangles, rays from outside aimed at it and from
// points inside it (every one of those must hit). Also bounds the passes a dense-mesh ray costs.
TEST(BvhTraverse, DenseMesh100k) {
    Scene s;
    FlatBvh bvh = build(test::sphereMesh(224, 224, 5.0f), s);
    ASSERT_GE(bvh.prims.size(), 100000u);
    std::vector<Ray> rays = test::randomRays(s.shapes, 90, 11, 6.0f);  // brute force is 100k tests a ray
    test::Rng rng(12);
    for (int i = 0; i < 30; ++i)
        rays.push_back({rng.inBox(glm::vec3(-2.0f), glm::vec3(2.0f)), rng.direction(), 0.0f, gpu::VKP_FAR});
    Summary sum = compare(bvh, rays);
    EXPECT_GT(sum.hits, 60u);
    EXPECT_LT(sum.maxPasses, 2000u);
    std::printf("dense mesh: %zu triangles, %zu nodes, depth %u, max passes of a ray %u\n",
                bvh.prims.size(), bvh.nodes.size(), bvh.stats.maxDepth, sum.maxPasses);
}

// Axis-aligned quads (flat boxes) on an integer grid, like the book's Cornell box walls, and
// axis-parallel rays exactly along grid lines and inside the quads' planes: infinite inverse
// directions, 0 * inf at slab planes, rays starting on faces.
TEST(BvhTraverse, AxisParallelRaysOnPlanes) {
    std::vector<Shape> shapes;
    for (int i = 0; i <= 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            for (int k = 0; k < 4; ++k) {
                const float a = float(i), b = float(j), c = float(k);
                if ((i + j + k) % 2 == 0) shapes.push_back(test::quad(glm::vec3(a, b, c), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)));
                if ((i + j + k) % 3 == 0) shapes.push_back(test::quad(glm::vec3(b, a, c), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)));
                if ((i + j + k) % 2 == 1) shapes.push_back(test::quad(glm::vec3(b, c, a), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)));
            }
        }
    }
    shapes.push_back(test::sphere(glm::vec3(2.0f, 2.0f, 2.0f), 0.5f));
    Scene s;
    FlatBvh bvh = build(shapes, s);
    std::vector<Ray> rays;
    const float coords[] = {-1.0f, 0.0f, 0.5f, 1.0f, 1.25f, 2.0f, 3.0f, 4.0f, 5.0f};
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            for (float u : coords) {
                for (float v : coords) {
                    for (float start : {-2.0f, 0.0f, 2.0f, 2.5f, 6.0f}) {
                        glm::vec3 o, d(0.0f);
                        o[axis] = start;
                        o[(axis + 1) % 3] = u;
                        o[(axis + 2) % 3] = v;
                        d[axis] = sign;
                        if (sign < 0.0f) d[(axis + 1) % 3] = -0.0f;  // negative zeros too
                        rays.push_back({o, d, 0.0f, gpu::VKP_FAR});
                        rays.push_back({o, d, 1e-3f, 3.0f});
                    }
                }
            }
        }
    }
    Summary sum = compare(bvh, rays);
    EXPECT_GT(sum.hits, rays.size() / 4);
}

TEST(BvhTraverse, ZeroOneTwoPrimitives) {
    Scene s0;
    FlatBvh b0 = build({}, s0);
    test::Rng rng(13);
    for (int i = 0; i < 100; ++i) {
        TraceResult r = traceClosestCpu(b0, rng.inBox(glm::vec3(-5), glm::vec3(5)), rng.direction(), 0.0f, gpu::VKP_FAR);
        EXPECT_FALSE(r.hit);
        EXPECT_EQ(r.passes, 2u);
        EXPECT_FALSE(traceAnyCpu(b0, glm::vec3(0), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR).hit);
    }
    EXPECT_FALSE(traceClosestCpu(b0, glm::vec3(0), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR).hit);

    Scene s1;
    FlatBvh b1 = build({test::quad(glm::vec3(-1, -1, -3), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0))}, s1);
    TraceResult h = traceClosestCpu(b1, glm::vec3(0), glm::vec3(0, 0, -1), 0.0f, gpu::VKP_FAR);
    EXPECT_TRUE(h.hit);
    EXPECT_FLOAT_EQ(h.t, 3.0f);
    EXPECT_EQ(h.prim, 0u);
    EXPECT_FLOAT_EQ(h.ab.x, 0.5f);
    EXPECT_FLOAT_EQ(h.ab.y, 0.5f);
    EXPECT_FALSE(traceClosestCpu(b1, glm::vec3(0), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR).hit);
    EXPECT_FALSE(traceClosestCpu(b1, glm::vec3(0), glm::vec3(0, 0, -1), 0.0f, 2.9f).hit);
    compare(b1, test::randomRays(s1.shapes, 500, 14, 3.0f));

    Scene s2;
    FlatBvh b2 = build({test::sphere(glm::vec3(0, 0, -3), 1.0f), test::sphere(glm::vec3(0, 0, -6), 1.0f)}, s2);
    TraceResult h2 = traceClosestCpu(b2, glm::vec3(0), glm::vec3(0, 0, -1), 0.0f, gpu::VKP_FAR);
    EXPECT_FLOAT_EQ(h2.t, 2.0f);
    EXPECT_EQ(b2.primToShape[h2.prim], 0u);
    TraceResult h3 = traceClosestCpu(b2, glm::vec3(0), glm::vec3(0, 0, -1), 4.5f, gpu::VKP_FAR);
    EXPECT_FLOAT_EQ(h3.t, 5.0f);
    EXPECT_EQ(b2.primToShape[h3.prim], 1u);
    compare(b2, test::randomRays(s2.shapes, 500, 15, 7.0f));
}

TEST(BvhTraverse, DegenerateRaysMissForFree) {
    Scene s;
    FlatBvh bvh = build(test::randomSpheres(100, 16), s);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const Ray& r : {Ray{glm::vec3(nan, 0, 0), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR},
                         Ray{glm::vec3(0), glm::vec3(0, nan, 0), 0.0f, gpu::VKP_FAR},
                         Ray{glm::vec3(0), glm::vec3(0, 0, 1), 1.0f, 1.0f},
                         Ray{glm::vec3(0), glm::vec3(0, 0, 1), nan, 5.0f},
                         Ray{glm::vec3(0), glm::vec3(0, 0, 1), 0.0f, nan}}) {
        TraceResult c = traceClosestCpu(bvh.nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax, 17u);
        EXPECT_FALSE(c.hit);
        EXPECT_EQ(c.passes, 17u);
        EXPECT_FALSE(traceAnyCpu(bvh.nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax).hit);
    }
    // tmax beyond VKP_FAR (infinity) is clamped, not a bogus hit.
    TraceResult far = traceClosestCpu(bvh, glm::vec3(100, 100, 100), glm::vec3(1, 0, 0), 0.0f,
                                      std::numeric_limits<float>::infinity());
    EXPECT_FALSE(far.hit);
}

TEST(BvhTraverse, DeepAdversarialTree) {
    std::vector<Shape> shapes;
    for (int i = 0; i < 250; ++i) {
        float x = std::ldexp(1.0f, i / 8 - 10) * (1.0f + 0.1f * float(i % 8));
        shapes.push_back(test::quad(glm::vec3(x, -1, -1), glm::vec3(0, 2, 0), glm::vec3(0, 0, 2)));
    }
    Scene s;
    FlatBvh bvh = build(shapes, s);
    EXPECT_GT(bvh.stats.maxDepth, 12u);
    EXPECT_LE(bvh.stats.maxDepth, 32u);
    std::vector<Ray> rays = test::randomRays(s.shapes, 1000, 17, 4.0f);
    for (int i = 0; i < 200; ++i) {  // along the row of quads, both ways
        float y = -1.0f + 0.01f * float(i);
        rays.push_back({glm::vec3(-1, y, 0.3f), glm::vec3(1, 0, 0), 0.0f, gpu::VKP_FAR});
        rays.push_back({glm::vec3(2e6f, y, -0.7f), glm::vec3(-1, 0, 0), 0.0f, gpu::VKP_FAR});
    }
    Summary sum = compare(bvh, rays);
    EXPECT_GT(sum.hits, 400u);
}

TEST(BvhTraverse, PassBudget) {
    Scene s;
    FlatBvh bvh = build(test::randomTriangles(5000, 18), s);
    const glm::vec3 o(-30, 0.1f, 0.2f), d(1, 0, 0);
    TraceResult full = traceClosestCpu(bvh, o, d, 0.0f, gpu::VKP_FAR);
    ASSERT_FALSE(full.cutShort());
    ASSERT_GT(full.passes, 10u);
    TraceResult cut = traceClosestCpu(bvh.nodes, bvh.prims, o, d, 0.0f, gpu::VKP_FAR, 0u, 10u);
    EXPECT_TRUE(cut.cutShort());
    EXPECT_GE(cut.passes, 10u);
    // A trace that starts with the budget spent ends at once, cut short.
    TraceResult spent = traceAnyCpu(bvh.nodes, bvh.prims, o, d, 0.0f, gpu::VKP_FAR, kTraceMaxPasses);
    EXPECT_FALSE(spent.hit);
    EXPECT_TRUE(spent.cutShort());
    EXPECT_EQ(spent.passes, kTraceMaxPasses);
    // Passes accumulate from the start value.
    TraceResult cont = traceClosestCpu(bvh.nodes, bvh.prims, o, d, 0.0f, gpu::VKP_FAR, 1000u);
    EXPECT_EQ(cont.passes, full.passes + 1000u);
}

/// A hand-made (foreign) tree: a chain of `chain` nodes, each with an inner right child holding two
/// one-sphere leaves; all boxes equal, so every level pushes one entry on the stack.
struct ChainTree {
    std::vector<gpu::GpuNode> nodes;
    std::vector<gpu::GpuPrim> prims;
};
ChainTree chainTree(std::uint32_t chain) {
    ChainTree t;
    auto slot = [](glm::vec4& lo, glm::vec4& hi, std::uint32_t index, std::uint32_t count) {
        lo = glm::vec4(-1, -1, -1, glm::uintBitsToFloat(index));
        hi = glm::vec4(1, 1, 1, glm::uintBitsToFloat(count));
    };
    t.nodes.resize(2 * chain);
    for (std::uint32_t k = 0; k < chain; ++k) {
        gpu::GpuNode& c = t.nodes[k];
        if (k + 1 < chain) slot(c.a, c.b, k + 1, 0);
        else slot(c.a, c.b, 2 * chain, 1);
        slot(c.c, c.d, chain + k, 0);
        gpu::GpuNode& h = t.nodes[chain + k];
        slot(h.a, h.b, 2 * k, 1);
        slot(h.c, h.d, 2 * k + 1, 1);
    }
    for (std::uint32_t i = 0; i <= 2 * chain; ++i) {
        Shape s = test::sphere(glm::vec3(0, 0, 0.9f - 0.02f * float(i)), 0.005f);
        t.prims.push_back(packShape(s, 0));
    }
    return t;
}

TEST(BvhTraverse, StackOverflowIsReportedAsCutShort) {
    // A chain of n nodes pushes n - 1 entries; the stack holds kTraceStackSize = 32.
    const glm::vec3 o(0, 0, -5), d(0, 0, 1);
    {
        ChainTree t = chainTree(33);  // 32 entries: exactly fits
        TraceResult r = traceClosestCpu(t.nodes, t.prims, o, d, 0.0f, gpu::VKP_FAR);
        EXPECT_FALSE(r.cutShort());
        EXPECT_TRUE(r.hit);
        EXPECT_EQ(r.prim, 2u * 33u);  // the sphere nearest to the origin
        EXPECT_FLOAT_EQ(r.t, 5.0f + 0.9f - 0.02f * 66.0f - 0.005f);
    }
    {
        ChainTree t = chainTree(34);  // 33 entries: overflow
        TraceResult r = traceClosestCpu(t.nodes, t.prims, o, d, 0.0f, gpu::VKP_FAR);
        EXPECT_TRUE(r.cutShort());
        EXPECT_GE(r.passes, kTraceMaxPasses);
    }
}

TEST(BvhTraverse, MalformedTreeThrows) {
    ChainTree t = chainTree(3);
    t.nodes[1].a.w = glm::uintBitsToFloat(99u);  // inner child out of range
    EXPECT_THROW(traceClosestCpu(t.nodes, t.prims, glm::vec3(0, 0, -5), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR),
                 std::out_of_range);
    ChainTree u = chainTree(3);
    u.nodes[4].b.w = glm::uintBitsToFloat(50u);  // leaf count past the primitives
    EXPECT_THROW(traceClosestCpu(u.nodes, u.prims, glm::vec3(0, 0, -5), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR),
                 std::out_of_range);
}

}  // namespace
