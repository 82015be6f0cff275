// The 4-wide BVH (and the benchmark's 8-wide collapse): collapse (host/bvh/wide_collapse.h), packing (wide_pack.h) and its CPU traversal
// (traverse_wide_cpu.h). Collapse: every primitive reachable exactly once, each inner child's box
// contains its node's child boxes, leaf boxes contain their primitives, nodes are fewer. Traversal:
// the same closest t (bit-exact), the same reported primitive's t and the same any-hit answer as
// brute force, on triangles, spheres, quads, a dense mesh and axis-parallel rays.
#include <algorithm>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "bvh/flatten.h"
#include "bvh/traverse_wide_cpu.h"
#include "bvh/wide_pack.h"
#include "bvh_test_scenes.h"

namespace {

using namespace vkp;
using test::Ray;

/// Walks the packed nodes from the root, checking structure; returns how often each prim is reached.
/// halves: GpuWideNodes per tree node (1: 4-wide; 2: 8-wide, packWide8).
std::vector<int> reachCounts(const Scene& scene, const FlatBvh& bvh, const std::vector<gpu::GpuWideNode>& nodes,
                             std::uint32_t halves = 1) {
    std::vector<int> seen(bvh.prims.size(), 0);
    std::vector<int> nodeSeen(nodes.size() / halves, 0);
    std::vector<std::pair<std::uint32_t, Aabb>> todo{{0u, Aabb{}}};
    bool root = true;
    while (!todo.empty()) {
        const auto [i, parentBox] = todo.back();
        todo.pop_back();
        EXPECT_LT(i, nodeSeen.size());
        if (i >= nodeSeen.size()) break;
        ++nodeSeen[i];
        for (std::uint32_t slot = 0; slot < 4 * halves; ++slot) {
            const gpu::GpuWideNode& n = nodes[halves * i + slot / 4];
            const int k = int(slot % 4);
            Aabb box;
            box.lo = glm::vec3(n.loX[k], n.loY[k], n.loZ[k]);
            box.hi = glm::vec3(n.hiX[k], n.hiY[k], n.hiZ[k]);
            if (n.count[k] == 0 && n.index[k] == gpu::GPU_NODE_EMPTY) {
                EXPECT_TRUE(box.empty()) << "empty slot with a box";
                continue;
            }
            if (!root) EXPECT_TRUE(parentBox.contains(box)) << "node " << i << " child " << k;
            if (n.count[k] == 0) {
                todo.push_back({n.index[k], box});
                continue;
            }
            for (std::uint32_t p = n.index[k]; p < n.index[k] + n.count[k]; ++p) {
                EXPECT_LT(p, seen.size());
                if (p >= seen.size()) break;
                ++seen[p];
                EXPECT_TRUE(box.contains(shapeBounds(scene.shapes[bvh.primToShape[p]]))) << "prim " << p;
            }
        }
        root = false;
    }
    for (std::size_t i = 0; i < nodeSeen.size(); ++i) EXPECT_EQ(nodeSeen[i], 1) << "node " << i;
    return seen;
}

void checkCollapse(const std::vector<vkp::Shape>& shapes) {
    const Scene scene = test::makeScene(shapes);
    const FlatBvh bvh = buildFlatBvh(scene);
    const WideTree tree = collapseToWide(bvh);
    const std::vector<gpu::GpuWideNode> nodes = packWide(tree);
    ASSERT_EQ(nodes.size(), tree.nodes.size());
    const std::vector<int> seen = reachCounts(scene, bvh, nodes);
    for (std::size_t p = 0; p < seen.size(); ++p) ASSERT_EQ(seen[p], 1) << "prim " << p << " reached " << seen[p] << " times";
    if (bvh.nodes.size() > 3) EXPECT_LT(nodes.size(), bvh.nodes.size());
    EXPECT_LE(tree.maxDepth, bvh.stats.maxDepth);

    // The layout benchmark's 8-wide tree (two GpuWideNodes per node): the same guarantees, and no
    // more nodes than the 4-wide tree.
    const WideTreeOf<8> tree8 = collapseToWideOf<8>(bvh);
    const std::vector<gpu::GpuWideNode> nodes8 = packWide8(tree8);
    ASSERT_EQ(nodes8.size(), 2 * tree8.nodes.size());
    const std::vector<int> seen8 = reachCounts(scene, bvh, nodes8, 2);
    for (std::size_t p = 0; p < seen8.size(); ++p) ASSERT_EQ(seen8[p], 1) << "8-wide: prim " << p;
    EXPECT_LE(tree8.nodes.size(), tree.nodes.size());
    EXPECT_LE(tree8.maxDepth, tree.maxDepth);
}

TEST(BvhWide, CollapseReachesEveryPrimitiveOnceInsideItsBoxes) {
    checkCollapse(test::randomTriangles(3000, 1));
    checkCollapse(test::randomSpheres(500, 2));
    checkCollapse(test::randomQuads(500, 3));
    checkCollapse(test::sphereMesh(64, 64));
    checkCollapse({});
    checkCollapse({test::sphere(glm::vec3(0), 1.0f)});
    checkCollapse({test::sphere(glm::vec3(0), 1.0f), test::sphere(glm::vec3(3), 1.0f)});
}

TEST(BvhWide, CollapseFillsNodes) {
    const FlatBvh bvh = buildFlatBvh(test::makeScene(test::randomTriangles(20000, 4)));
    const WideTree tree = collapseToWide(bvh);
    std::size_t used = 0;
    for (const auto& n : tree.nodes)
        for (const WideChild& c : n) used += !c.empty();
    // A binary tree of N nodes has 2N child slots; the wide tree must hold them in about N/1.5 nodes.
    EXPECT_GT(double(used) / double(tree.nodes.size()), 3.0);
    std::printf("binary nodes %zu, wide nodes %zu, slots used per wide node %.2f, depth %u -> %u\n", bvh.nodes.size(),
                tree.nodes.size(), double(used) / double(tree.nodes.size()), bvh.stats.maxDepth, tree.maxDepth);
}

TEST(BvhWide, BuildFlatBvhFillsTheWideNodes) {
    const FlatBvh bvh = buildFlatBvh(test::makeScene(test::randomTriangles(500, 6)));
    const std::vector<gpu::GpuWideNode> again = buildWideNodes(bvh);
    ASSERT_EQ(bvh.wideNodes.size(), again.size());
    EXPECT_EQ(bvh.stats.wideNodeCount, again.size());
    EXPECT_EQ(std::memcmp(bvh.wideNodes.data(), again.data(), again.size() * sizeof(gpu::GpuWideNode)), 0);
}

TEST(BvhWide, MalformedFlatBvhIsRejected) {
    FlatBvh bvh = buildFlatBvh(test::makeScene(test::randomTriangles(100, 5)));
    bvh.nodes[0].a.w = gpu::uintBitsToFloat(999999u);
    bvh.nodes[0].b.w = gpu::uintBitsToFloat(0u);
    EXPECT_THROW(collapseToWide(bvh), std::invalid_argument);
}

/// Wide CPU traversal against brute force (t bit-exact) and against the binary traversal's any-hit.
void checkTraversal(const std::vector<vkp::Shape>& shapes, const std::vector<Ray>& rays) {
    const FlatBvh bvh = buildFlatBvh(test::makeScene(shapes));
    const std::vector<gpu::GpuWideNode> nodes = buildWideNodes(bvh);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Ray& r = rays[i];
        const test::BruteHit ref = test::bruteForce(bvh.prims, r);
        const TraceResult c = traceClosestWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax);
        ASSERT_FALSE(c.cutShort()) << "ray " << i;
        ASSERT_EQ(c.hit, ref.hit) << "ray " << i;
        if (c.hit) {
            ASSERT_EQ(c.t, ref.t) << "ray " << i;
            glm::vec2 ab;
            const float own = gpu::intersectPrim(bvh.prims.at(c.prim), r.o, r.d, r.tmin, std::min(r.tmax, gpu::VKP_FAR), ab);
            ASSERT_EQ(own, c.t) << "ray " << i << ": reported primitive does not give t";
            ++hits;
        } else {
            ASSERT_EQ(c.prim, gpu::GPU_NODE_EMPTY);
        }
        const TraceResult a = traceAnyWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax);
        ASSERT_FALSE(a.cutShort());
        ASSERT_EQ(a.hit, ref.hit) << "any-hit, ray " << i;
    }
    EXPECT_GT(hits, rays.size() / 10);
}

TEST(BvhWide, TraversalMatchesBruteForce) {
    std::vector<vkp::Shape> mix = test::randomTriangles(1500, 7);
    for (const vkp::Shape& s : test::randomSpheres(500, 8)) mix.push_back(s);
    for (const vkp::Shape& s : test::randomQuads(500, 9)) mix.push_back(s);
    checkTraversal(mix, test::randomRays(mix, 3000, 10));
    const std::vector<vkp::Shape> mesh = test::sphereMesh(100, 100, 5.0f);
    checkTraversal(mesh, test::randomRays(mesh, 1000, 11, 6.0f));
}

TEST(BvhWide, EmptySceneMisses) {
    const FlatBvh bvh = buildFlatBvh(test::makeScene({}));
    const std::vector<gpu::GpuWideNode> nodes = buildWideNodes(bvh);
    const TraceResult c = traceClosestWideCpu(nodes, bvh.prims, glm::vec3(0), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR);
    EXPECT_FALSE(c.hit);
    EXPECT_FALSE(c.cutShort());
}

TEST(BvhWide, PassGuardCutsShort) {
    const std::vector<vkp::Shape> mesh = test::sphereMesh(64, 64, 5.0f);
    const FlatBvh bvh = buildFlatBvh(test::makeScene(mesh));
    const std::vector<gpu::GpuWideNode> nodes = buildWideNodes(bvh);
    const TraceResult full = traceClosestWideCpu(nodes, bvh.prims, glm::vec3(0, 0, -20), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR);
    ASSERT_TRUE(full.hit);
    ASSERT_GT(full.passes, 4u);
    const TraceResult cut = traceClosestWideCpu(nodes, bvh.prims, glm::vec3(0, 0, -20), glm::vec3(0, 0, 1), 0.0f,
                                                gpu::VKP_FAR, 0, 4);
    EXPECT_TRUE(cut.cutShort());
}

}  // namespace
