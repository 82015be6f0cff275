// The two-level BVH (instancing) on the host: the top level's build input and tree (tlas.h), the
// joined layout (two_level.h), the CPU traversal of instances (traverse_wide_cpu.h) against the
// same scene flattened, and the world-space shading geometry of an instance's hit
// (shared/instance.h): hit points, normals under mirrors, ray origins that do not hit their own
// triangle again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "bvh/tlas.h"
#include "bvh/traverse_wide_cpu.h"
#include "traverse_binary_cpu.h"
#include "bvh/two_level.h"
#include "instance_test_scenes.h"
#include "shared/instance.h"
#include "shared/intersect.h"

namespace vkp {
namespace {

using test::instancedScene;

Aabb meshBox(const InstancedMesh& m) {
    Aabb b;
    for (const Shape& s : m.shapes) b.grow(shapeBounds(s));
    return b;
}

TEST(TwoLevelBvh, TransformedBoundsHoldEveryPlacedVertex) {
    const Scene scene = instancedScene();
    for (const MeshInstance& inst : scene.instances) {
        const Aabb box = transformedBounds(meshBox(scene.meshes[inst.mesh]), inst.objectToWorld);
        ASSERT_FALSE(box.empty());
        for (const Shape& t : scene.meshes[inst.mesh].shapes) {
            const Shape w = test::placeTriangle(t, inst.objectToWorld);
            Aabb tb = shapeBounds(w);
            EXPECT_TRUE(box.contains(tb));
        }
    }
    EXPECT_TRUE(transformedBounds(Aabb{}, glm::dmat4(2.0)).empty());
}

TEST(TwoLevelBvh, TopLevelTreeCoversShapesAndInstancesOnce) {
    const Scene scene = instancedScene();
    std::vector<Aabb> boxes;
    for (const InstancedMesh& m : scene.meshes) boxes.push_back(meshBox(m));
    const TopLevelItems items = topLevelItems(scene, boxes);
    ASSERT_EQ(items.boxes.size(), scene.shapes.size() + scene.instances.size());
    EXPECT_EQ(items.shapeCount, scene.shapes.size());
    const BvhBuildTree tree = buildTopLevel(items);
    std::vector<int> seen(items.boxes.size(), 0);
    for (std::uint32_t i : tree.primIndices) ++seen.at(i);
    for (int n : seen) EXPECT_EQ(n, 1);
    // Every leaf's box holds its items' boxes; every inner node's box holds its children's.
    for (const BvhBuildNode& n : tree.nodes) {
        if (n.isLeaf()) {
            for (std::uint32_t k = n.index; k < n.index + n.count; ++k) EXPECT_TRUE(n.box.contains(items.boxes[tree.primIndices[k]]));
        } else {
            EXPECT_TRUE(n.box.contains(tree.nodes[n.index].box));
            EXPECT_TRUE(n.box.contains(tree.nodes[n.index + 1].box));
        }
    }
    std::vector<Aabb> tooFew;
    EXPECT_THROW(topLevelItems(scene, tooFew), std::invalid_argument);
}

TEST(TwoLevelBvh, JoinedLayoutIndexesEveryLevelInRange) {
    const Scene scene = instancedScene();
    const FlatBvh bvh = buildTwoLevelBvh(scene);
    std::size_t meshTriangles = 0;
    for (const InstancedMesh& m : scene.meshes) meshTriangles += m.shapes.size();
    const std::size_t top = scene.shapes.size() + scene.instances.size();
    ASSERT_EQ(bvh.prims.size(), top + meshTriangles);
    EXPECT_EQ(bvh.stats.topPrimCount, top);
    EXPECT_EQ(bvh.stats.instanceCount, scene.instances.size());
    EXPECT_EQ(bvh.stats.meshCount, scene.meshes.size());
    ASSERT_EQ(bvh.instances.size(), scene.instances.size());
    ASSERT_EQ(bvh.primMesh.size(), bvh.prims.size());
    std::size_t instancePrims = 0;
    for (std::size_t i = 0; i < bvh.prims.size(); ++i) {
        const bool isInstance = gpu::primKind(bvh.prims[i]) == gpu::PRIM_INSTANCE;
        instancePrims += isInstance;
        EXPECT_EQ(bvh.primMesh[i] == 0, i < top) << i;
        if (isInstance) {
            EXPECT_LT(i, top);
            EXPECT_EQ(primShape(scene, bvh, i), nullptr);
            EXPECT_LT(gpu::primMaterial(bvh.prims[i]), scene.instances.size());
        } else {
            EXPECT_NE(primShape(scene, bvh, i), nullptr);
        }
    }
    EXPECT_EQ(instancePrims, scene.instances.size());
    // Each instance's root is a wide node whose subtree reaches only its own mesh's triangles.
    for (std::size_t k = 0; k < bvh.instances.size(); ++k) {
        const gpu::GpuInstance& g = bvh.instances[k];
        EXPECT_EQ(g.info.w, scene.instances[k].mesh);
        std::vector<std::uint32_t> stack{g.info.x};
        std::size_t leaves = 0;
        while (!stack.empty()) {
            const gpu::GpuWideNode& n = bvh.wideNodes.at(stack.back());
            stack.pop_back();
            for (int c = 0; c < 4; ++c) {
                if (n.count[c] > 0) {
                    for (std::uint32_t p = n.index[c]; p < n.index[c] + n.count[c]; ++p) {
                        ASSERT_LT(p, bvh.prims.size());
                        EXPECT_EQ(bvh.primMesh[p], scene.instances[k].mesh + 1);
                        ++leaves;
                    }
                } else if (n.index[c] != gpu::GPU_NODE_EMPTY) {
                    stack.push_back(n.index[c]);
                }
            }
        }
        EXPECT_EQ(leaves, scene.meshes[scene.instances[k].mesh].shapes.size());
        // The two maps are inverses of each other (each rounded once to float).
        const glm::vec3 p(0.3f, -1.7f, 2.2f);
        const glm::vec3 back = gpu::affinePoint(g.w2o0, g.w2o1, g.w2o2, gpu::affinePoint(g.o2w0, g.o2w1, g.o2w2, p));
        EXPECT_LT(glm::length(back - p), 1e-4f * (1.0f + glm::length(glm::vec3(g.o2w0.w, g.o2w1.w, g.o2w2.w)) * 100.0f));
        EXPECT_EQ((g.info.z & gpu::INSTANCE_MIRROR) != 0, glm::determinant(glm::dmat3(scene.instances[k].objectToWorld)) < 0.0);
    }
    EXPECT_THROW(packInstance(MeshInstance{0, glm::dmat4(0.0)}, 0, 0), std::invalid_argument);
}

/// Index of the flattened shape that a two-level hit is (flattenedScene's order).
std::uint32_t flatIndex(const Scene& scene, const FlatBvh& bvh, const TraceResult& h) {
    if (h.instance == gpu::GPU_NO_INSTANCE) return bvh.primToShape[h.prim];
    std::uint32_t base = std::uint32_t(scene.shapes.size());
    for (std::uint32_t k = 0; k < h.instance; ++k) base += std::uint32_t(scene.meshes[scene.instances[k].mesh].shapes.size());
    return base + bvh.primToShape[h.prim];
}

/// The instance a flattened shape came from (flattenedScene's order), or GPU_NO_INSTANCE.
std::uint32_t flatInstance(const Scene& scene, std::uint32_t shape) {
    if (shape < scene.shapes.size()) return gpu::GPU_NO_INSTANCE;
    std::size_t base = scene.shapes.size();
    for (std::uint32_t k = 0; k < scene.instances.size(); ++k) {
        base += scene.meshes[scene.instances[k].mesh].shapes.size();
        if (shape < base) return k;
    }
    return gpu::GPU_NO_INSTANCE;
}

TEST(TwoLevelBvh, CpuTraversalAgreesWithTheFlattenedScene) {
    const Scene scene = instancedScene();
    const Scene flat = test::flattenedScene(scene);
    const FlatBvh two = buildTwoLevelBvh(scene);
    const FlatBvh one = buildFlatBvh(flat);
    // The small mesh placed 1e4 from the origin is compared apart: flattened, its float vertices
    // are rounded to ulps of 1e4 (~1e-3) on triangles ~0.02 across, so the two scenes differ there
    // by the flattening's rounding, not the traversal's.
    auto far = [&](std::uint32_t inst) {
        return inst != gpu::GPU_NO_INSTANCE && std::abs(scene.instances[inst].objectToWorld[3].x) > 1000.0;
    };
    const std::vector<test::Ray> rays = test::randomRays(flat.shapes, 40000, 41, 25.0f);
    int hits = 0, instanceHits = 0, hitMismatch = 0, shapeMismatch = 0, anyMismatch = 0, mirroredHits = 0, farRays = 0;
    double worstT = 0.0, worstTie = 0.0;
    for (const test::Ray& r : rays) {
        const TraceResult a = traceClosestWideCpu(two.wideNodes, two.prims, two.instances, r.o, r.d, r.tmin, r.tmax);
        const TraceResult b = traceClosestWideCpu(one.wideNodes, one.prims, r.o, r.d, r.tmin, r.tmax);
        const TraceResult any = traceAnyWideCpu(two.wideNodes, two.prims, two.instances, r.o, r.d, r.tmin, r.tmax);
        EXPECT_FALSE(a.cutShort());
        if ((a.hit && far(a.instance)) || (b.hit && far(flatInstance(scene, one.primToShape[b.prim])))) {
            ++farRays;
            continue;
        }
        hitMismatch += a.hit != b.hit;
        anyMismatch += any.hit != b.hit;
        if (!a.hit || !b.hit) continue;
        ++hits;
        if (a.instance != gpu::GPU_NO_INSTANCE) {
            ++instanceHits;
            mirroredHits += (two.instances[a.instance].info.z & gpu::INSTANCE_MIRROR) != 0;
        }
        const bool same = flatIndex(scene, two, a) == one.primToShape[b.prim];
        shapeMismatch += !same;
        const double dt = std::abs(double(a.t) - double(b.t)) / std::max(1.0, double(b.t));
        if (!same) worstTie = std::max(worstTie, dt);
        if (same) {
            // How far apart the two hit points are along the triangle's normal (t itself is
            // ill-conditioned at grazing incidence: it moves by that distance / |cos|).
            const Shape& sh = flat.shapes[one.primToShape[b.prim]];
            const glm::vec3 n = glm::normalize(glm::cross(sh.p1 - sh.p0, sh.p2 - sh.p0));
            worstT = std::max(worstT, dt * std::abs(double(glm::dot(n, r.d))));
        }
    }
    std::printf("two-level vs flattened: %d hits (%d on instances, %d mirrored), hit/miss differ %d, any-hit differ %d, "
                "another triangle %d (worst relative t difference there %.3g), same triangle: worst relative distance "
                "along its normal %.3g; %d rays reach the far mesh\n",
                hits, instanceHits, mirroredHits, hitMismatch, anyMismatch, shapeMismatch, worstTie, worstT, farRays);
    EXPECT_GT(instanceHits, 5000);
    EXPECT_GT(mirroredHits, 500);
    EXPECT_GT(farRays, 100);
    // The instance's ray is the world ray mapped in float and the flattened triangles are placed in
    // double and rounded, so a ray within rounding of an edge may find the neighbour (the other
    // triangle at the same t), and one within rounding of a silhouette may miss in one of them.
    EXPECT_LE(hitMismatch, 4);
    EXPECT_LE(anyMismatch, 4);
    EXPECT_LE(shapeMismatch, hits / 200);
    EXPECT_LT(worstTie, 1e-4);  // another triangle only in a tie: the same point within rounding
    EXPECT_LT(worstT, 1e-5);
}

/// With spatial splits (host/bvh/sbvh.h) each mesh's bottom level may name a triangle from several
/// leaves; the hits must be those of the tree without them, bit for bit.
TEST(TwoLevelBvh, SpatialSplitsFindTheSameHits) {
    const Scene scene = instancedScene();
    BvhBuildOptions spatial;
    spatial.spatialSplits = 1.0f;
    const FlatBvh plain = buildTwoLevelBvh(scene), split = buildTwoLevelBvh(scene, spatial);
    std::printf("two-level: %zu primitives, %zu with spatial splits\n", plain.prims.size(), split.prims.size());
    EXPECT_GT(split.prims.size(), plain.prims.size()) << "no triangle was split";
    const std::vector<test::Ray> rays = test::randomRays(test::flattenedScene(scene).shapes, 20000, 43, 25.0f);
    int hits = 0;
    for (const test::Ray& r : rays) {
        const TraceResult a = traceClosestWideCpu(plain.wideNodes, plain.prims, plain.instances, r.o, r.d, r.tmin, r.tmax);
        const TraceResult b = traceClosestWideCpu(split.wideNodes, split.prims, split.instances, r.o, r.d, r.tmin, r.tmax);
        ASSERT_EQ(a.hit, b.hit);
        ASSERT_EQ(traceAnyWideCpu(split.wideNodes, split.prims, split.instances, r.o, r.d, r.tmin, r.tmax).hit, a.hit);
        if (!a.hit) continue;
        ++hits;
        ASSERT_EQ(a.t, b.t);
        ASSERT_EQ(a.instance, b.instance);
    }
    EXPECT_GT(hits, 5000);
}

TEST(TwoLevelBvh, WorldHitGeometryMatchesTheFlattenedTriangleAndRaysLeaveIt) {
    const Scene scene = instancedScene();
    const FlatBvh two = buildTwoLevelBvh(scene);
    test::Rng rng(51);
    int selfHits = 0, aimed = 0;
    double worstPoint = 0.0;
    for (std::size_t k = 0; k < scene.instances.size(); ++k) {
        const MeshInstance& inst = scene.instances[k];
        const InstancedMesh& mesh = scene.meshes[inst.mesh];
        for (int trial = 0; trial < 300; ++trial) {
            // A ray aimed at a random point of a random triangle of this instance.
            const Shape& t = mesh.shapes[rng.below(std::uint32_t(mesh.shapes.size()))];
            const Shape w = test::placeTriangle(t, inst.objectToWorld);
            float a = rng.uniform(), b = rng.uniform();
            if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
            const glm::vec3 target = w.p0 + a * (w.p1 - w.p0) + b * (w.p2 - w.p0);
            const glm::vec3 dir = rng.direction();
            const float dist = 0.5f + 30.0f * rng.uniform();
            const glm::vec3 o = target - dist * dir;
            const TraceResult h = traceClosestWideCpu(two.wideNodes, two.prims, two.instances, o, dir, 0.0f, gpu::VKP_FAR);
            if (!h.hit || h.instance == gpu::GPU_NO_INSTANCE) continue;
            ++aimed;
            const gpu::GpuInstance& g = two.instances[h.instance];
            const gpu::GpuPrim pObj = two.prims[h.prim];
            const gpu::GpuPrim p = gpu::instanceWorldPrim(g, pObj);
            const glm::vec2 ab = gpu::instanceWorldAb(g, h.ab);
            const glm::vec3 x = gpu::primHitPoint(p, o, dir, h.t, ab);
            const glm::vec3 ray = o + h.t * dir;
            worstPoint = std::max(worstPoint, double(glm::length(x - ray)) / (1.0 + glm::length(ray)));
            // The geometric normal is the flattened triangle's (mirrors swap two corners in both).
            const Shape& hitShape = scene.meshes[scene.instances[h.instance].mesh].shapes[two.primToShape[h.prim]];
            const Shape hw = test::placeTriangle(hitShape, scene.instances[h.instance].objectToWorld);
            const glm::vec3 nFlat = glm::normalize(glm::cross(hw.p1 - hw.p0, hw.p2 - hw.p0));
            const glm::vec3 n = gpu::primNormal(p, x);
            EXPECT_GT(glm::dot(n, nFlat), 0.999f);
            // Rays leaving the hit point to either side never hit that triangle again.
            for (int side = 0; side < 2; ++side) {
                const glm::vec3 ns = side == 0 ? n : -n;
                const float extra = gpu::instanceOffsetDistance(g, pObj, h.ab, x, n);
                const glm::vec3 xo = gpu::spawnRayOriginExtra(p, ab, x, ns, extra, 1.0f);
                for (int j = 0; j < 4; ++j) {
                    glm::vec3 d = rng.direction();
                    if (glm::dot(d, ns) < 0.0f) d = -d;
                    const TraceResult again = traceClosestWideCpu(two.wideNodes, two.prims, two.instances, xo, d, 0.0f, gpu::VKP_FAR);
                    selfHits += again.hit && again.prim == h.prim && again.instance == h.instance;
                }
            }
        }
    }
    std::printf("aimed hits %d, worst hit point vs o + t d %.3g (relative), self-hits %d\n", aimed, worstPoint, selfHits);
    EXPECT_GT(aimed, 2000);
    EXPECT_LT(worstPoint, 1e-4);
    EXPECT_EQ(selfHits, 0);
}

TEST(TwoLevelBvh, BinaryTraversalFindsTheWideOnesHits) {
    // The binary nodes of the same two-level BVH (each level flattened, the mesh roots in
    // GpuInstance::info.y): the same closest t bit for bit, the same instance, any-hit answer.
    const Scene scene = instancedScene();
    const FlatBvh two = buildTwoLevelBvh(scene);
    int hits = 0, instanceHits = 0, differ = 0, tieOther = 0;
    for (const test::Ray& r : test::randomRays(test::flattenedScene(scene).shapes, 20000, 61, 25.0f)) {
        const TraceResult b = traceClosestCpu(two.nodes, two.prims, two.instances, r.o, r.d, r.tmin, r.tmax);
        const TraceResult w = traceClosestWideCpu(two.wideNodes, two.prims, two.instances, r.o, r.d, r.tmin, r.tmax);
        const bool anyB = traceAnyCpu(two.nodes, two.prims, two.instances, r.o, r.d, r.tmin, r.tmax).hit;
        EXPECT_FALSE(b.cutShort());
        hits += b.hit;
        instanceHits += b.hit && b.instance != gpu::GPU_NO_INSTANCE;
        differ += b.hit != w.hit || anyB != w.hit || std::memcmp(&b.t, &w.t, sizeof(float)) != 0 || b.instance != w.instance;
        tieOther += b.hit && w.hit && b.prim != w.prim;  // only in an exact tie (same t): two triangles at an edge
    }
    std::printf("binary vs 4-wide, two-level: %d hits (%d on instances), %d differ, %d on another triangle at the same t\n",
                hits, instanceHits, differ, tieOther);
    EXPECT_EQ(differ, 0);
    EXPECT_GT(instanceHits, 4000);
    EXPECT_LE(tieOther, hits / 1000);
}

}  // namespace
}  // namespace vkp
