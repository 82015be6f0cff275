// Watertight triangle intersection (label stress): rays shot from inside a closed triangle mesh
// never escape through an edge or a vertex. Escape = the ray hits no triangle at all.
//  - The routine itself (shared/intersect.h intersectTriangleWatertight, Woop et al. 2013) on a
//    closed icosphere with bit-identical shared vertices: 0 escapes in 1M rays, a third of them
//    aimed at vertices and a third at points on edges (the rays that find cracks). Teeth: the same
//    rays through Moller-Trumbore (intersectParallelogram) do escape.
//  - The traversal (host/bvh CPU twin, through the packed GpuPrim and the BVH) on the 100k-triangle
//    sphere mesh of the BVH tests, 1M rays; and the same on the device (shaders/tests/bvh_trace.comp,
//    lavapipe), spot-checked bit for bit against the CPU: 0 escapes (GpuPrim keeps triangle
//    vertices, so shared vertices stay bit-identical through the packing). The same for the
//    4-wide layout (shared/wide_bvh.h), on the CPU and on the device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "bvh/flatten.h"
#include "traverse_binary_cpu.h"
#include "bvh/traverse_wide_cpu.h"
#include "bvh/wide_pack.h"
#include "bvh_test_scenes.h"
#include "bvh_trace.spv.h"
#include "bvh_trace_compare.h"
#include "bvh_trace_wide.spv.h"
#include "gpu_env.h"
#include "shared/intersect.h"

namespace vkp::test {
namespace {

using glm::vec3;

struct Mesh {
    std::vector<vec3> v;
    std::vector<glm::uvec3> tri;
};

/// Icosahedron subdivided `levels` times, vertices on the sphere of radius r (each vertex stored
/// once, so shared edges are bit-identical in every triangle that uses them).
Mesh icosphere(int levels, float r) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    Mesh m;
    for (vec3 p : {vec3(-1, t, 0), vec3(1, t, 0), vec3(-1, -t, 0), vec3(1, -t, 0), vec3(0, -1, t), vec3(0, 1, t),
                   vec3(0, -1, -t), vec3(0, 1, -t), vec3(t, 0, -1), vec3(t, 0, 1), vec3(-t, 0, -1), vec3(-t, 0, 1)})
        m.v.push_back(r * glm::normalize(p));
    m.tri = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int l = 0; l < levels; ++l) {
        std::vector<glm::uvec3> next;
        std::vector<std::pair<std::pair<unsigned, unsigned>, unsigned>> mids;
        auto mid = [&](unsigned a, unsigned b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            for (const auto& [k, i] : mids)
                if (k == key) return i;
            m.v.push_back(r * glm::normalize(m.v[a] + m.v[b]));
            mids.push_back({key, unsigned(m.v.size() - 1)});
            return unsigned(m.v.size() - 1);
        };
        for (const glm::uvec3& f : m.tri) {
            const unsigned a = mid(f.x, f.y), b = mid(f.y, f.z), c = mid(f.z, f.x);
            next.insert(next.end(), {{f.x, a, c}, {f.y, b, a}, {f.z, c, b}, {a, b, c}});
        }
        m.tri = next;
    }
    return m;
}

/// 1M rays from inside a closed mesh of "radius" ~r: origins uniform in the ball of radius 0.5 r;
/// directions, in turn: uniform, towards a random vertex, towards a random point of a random edge.
std::vector<Ray> insideRays(const std::vector<vec3>& verts, const std::vector<std::pair<vec3, vec3>>& edges, float r,
                            std::size_t n, std::uint32_t seed) {
    Rng rng(seed);
    std::vector<Ray> rays;
    rays.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        vec3 o;
        do o = rng.inBox(vec3(-0.5f * r), vec3(0.5f * r));
        while (glm::length(o) > 0.5f * r);
        vec3 d = rng.direction();
        if (i % 3 == 1) d = glm::normalize(verts[rng.below(std::uint32_t(verts.size()))] - o);
        if (i % 3 == 2) {
            const auto& [a, b] = edges[rng.below(std::uint32_t(edges.size()))];
            d = glm::normalize(a + rng.uniform() * (b - a) - o);
        }
        rays.push_back({o, d, 0.0f, gpu::VKP_FAR});
    }
    return rays;
}

std::vector<std::pair<vec3, vec3>> edgesOf(const Mesh& m) {
    std::vector<std::pair<vec3, vec3>> e;
    for (const glm::uvec3& f : m.tri) e.insert(e.end(), {{m.v[f.x], m.v[f.y]}, {m.v[f.y], m.v[f.z]}, {m.v[f.z], m.v[f.x]}});
    return e;
}

TEST(StressWatertight, WoopNeverLetsARayOutOfAClosedMesh) {
    const Mesh m = icosphere(1, 1.0f);  // 80 triangles, 42 vertices
    ASSERT_EQ(m.tri.size(), 80u);
    const std::vector<Ray> rays = insideRays(m.v, edgesOf(m), 1.0f, 1000000, 5);
    long woopEscapes = 0, mtEscapes = 0;
    for (const Ray& r : rays) {
        bool woop = false, mt = false;
        for (const glm::uvec3& f : m.tri) {
            glm::vec2 ab;
            const vec3 a = m.v[f.x], b = m.v[f.y], c = m.v[f.z];
            woop = woop || gpu::intersectTriangleWatertight(a, b, c, r.o, r.d, 0.0f, gpu::VKP_FAR, ab) < gpu::VKP_FAR;
            mt = mt || gpu::intersectParallelogram(a, b - a, c - a, true, r.o, r.d, 0.0f, gpu::VKP_FAR, ab) < gpu::VKP_FAR;
        }
        woopEscapes += !woop;
        mtEscapes += !mt;
    }
    std::printf("escapes in %zu rays: watertight %ld, Moller-Trumbore %ld\n", rays.size(), woopEscapes, mtEscapes);
    EXPECT_EQ(woopEscapes, 0);
    EXPECT_GT(mtEscapes, 0) << "teeth: the rays should find Moller-Trumbore's cracks";
}

// Woop's t and (a, b) against a double-precision reference, as accurate as Moller-Trumbore's
// (the parametrisation the rest of the renderer uses): errors in units of float epsilon times the
// scale of the coordinates over |cos| (the conditioning of a ray/plane intersection).
TEST(StressWatertight, WoopIsAsAccurateAsMollerTrumbore) {
    Rng rng(9);
    int compared = 0;
    double worstWoop = 0, worstMt = 0;
    for (int i = 0; i < 100000; ++i) {
        const vec3 a = rng.inBox(vec3(-2), vec3(2)), b = rng.inBox(vec3(-2), vec3(2)), c = rng.inBox(vec3(-2), vec3(2));
        const vec3 o = rng.inBox(vec3(-5), vec3(5));
        const float u = rng.uniform(0.05f, 0.9f), v = rng.uniform(0.05f, 0.9f);
        if (u + v > 0.95f) continue;
        const vec3 d = glm::normalize(a + u * (b - a) + v * (c - a) - o);
        // Double-precision reference (Cramer's rule on o + t d = a + s (b - a) + r (c - a)).
        const glm::dvec3 da(a), e1 = glm::dvec3(b) - da, e2 = glm::dvec3(c) - da, dd(d), f = glm::dvec3(o) - da;
        const glm::dvec3 n = glm::cross(e1, e2);
        const double cosine = std::abs(glm::dot(glm::normalize(n), dd));
        if (cosine < 1e-3) continue;
        const double det = -glm::dot(dd, n);
        const double tRef = glm::dot(f, n) / det;
        const double sRef = -glm::dot(dd, glm::cross(f, e2)) / det, rRef = -glm::dot(dd, glm::cross(e1, f)) / det;
        glm::vec2 ab1, ab2;
        const float t1 = gpu::intersectTriangleWatertight(a, b, c, o, d, 0.0f, gpu::VKP_FAR, ab1);
        const float t2 = gpu::intersectParallelogram(a, b - a, c - a, true, o, d, 0.0f, gpu::VKP_FAR, ab2);
        ASSERT_NE(t1, gpu::VKP_FAR) << i;
        ++compared;
        const double unit = 1.19e-7 * (glm::length(o) + glm::length(a) + glm::length(b) + glm::length(c)) / cosine;
        const double eWoop = std::max(std::abs(t1 - tRef), glm::length(glm::dvec3(b - a) * (ab1.x - sRef) + glm::dvec3(c - a) * (ab1.y - rRef))) / unit;
        worstWoop = std::max(worstWoop, eWoop);
        if (t2 < gpu::VKP_FAR)
            worstMt = std::max(worstMt, std::max(std::abs(t2 - tRef), glm::length(glm::dvec3(b - a) * (ab2.x - sRef) + glm::dvec3(c - a) * (ab2.y - rRef))) / unit);
    }
    std::printf("largest error of t and of the hit point (units of eps |coordinates| / |cos|): watertight %.2f, Moller-Trumbore %.2f\n",
                worstWoop, worstMt);
    EXPECT_GT(compared, 50000);
    EXPECT_LT(worstWoop, 16.0);
}

/// Rays (1M) from inside the 100k-triangle sphere mesh of the BVH tests (shared vertices are
/// computed by the same function, so bit-identical), and the escapes of the CPU traversal.
struct MeshRays {
    Scene scene;
    FlatBvh bvh;
    std::vector<Ray> rays;
};
const MeshRays& meshRays() {
    static const MeshRays mr = [] {
        MeshRays r;
        r.scene = makeScene(sphereMesh(224, 224, 5.0f));
        r.bvh = buildFlatBvh(r.scene);
        std::vector<vec3> verts;
        std::vector<std::pair<vec3, vec3>> edges;
        for (const Shape& s : r.scene.shapes) {
            verts.push_back(s.p0);
            edges.push_back({s.p0, s.p1});
            edges.push_back({s.p1, s.p2});
        }
        r.rays = insideRays(verts, edges, 5.0f, 1000000, 17);
        return r;
    }();
    return mr;
}

/// packShape keeps a triangle's vertices (p1 = v1, p2 = v2), not edges: v0 + (v1 - v0) is v1 only
/// when the subtraction was exact, and neighbours that disagree on a shared vertex by an ulp leave a
/// crack however watertight the test itself is (141 escapes in 1M rays here when edges were stored).
TEST(WatertightTraversal, PackedTrianglesKeepVertices) {
    Shape s = triangle(vec3(0.1f, 0.2f, 0.3f), vec3(5.3f, -0.7f, 1.1f), vec3(-2.9f, 3.3f, 0.05f));
    const gpu::GpuPrim p = packShape(s, 0);
    EXPECT_EQ(glm::vec3(p.p1), s.p1);
    EXPECT_EQ(glm::vec3(p.p2), s.p2);
}

/// Checks the escapes of a traversal: none at all.
void checkEscapes(const MeshRays& mr, const std::vector<std::size_t>& escaped, const char* who) {
    std::printf("%s: %zu escapes in %zu rays\n", who, escaped.size(), mr.rays.size());
    EXPECT_EQ(escaped.size(), 0u) << who;
}

TEST(StressWatertight, CpuTraversalNeverLetsARayOutOfTheSphereMesh) {
    const MeshRays& mr = meshRays();
    std::vector<std::size_t> escaped;
    long cut = 0;
    for (std::size_t i = 0; i < mr.rays.size(); ++i) {
        const TraceResult h = traceClosestCpu(mr.bvh, mr.rays[i].o, mr.rays[i].d, mr.rays[i].tmin, mr.rays[i].tmax);
        if (!h.hit) escaped.push_back(i);
        cut += h.cutShort();
    }
    checkEscapes(mr, escaped, "CPU traversal");
    EXPECT_EQ(cut, 0);
}

/// Runs the rays through bvh_trace.comp (or a variant of it: spirv) on the device with node data
/// `nodes` (nodeBytes bytes), counts escapes, spot-checks every 97th ray against `cpu` (t, prim).
template <class CpuTrace>
void checkDeviceEscapes(VulkanDevice& dev, std::span<const std::uint32_t> spirv, const void* nodes, std::size_t nodeBytes,
                        CpuTrace cpu, const char* who) {
    const MeshRays& mr = meshRays();
    const std::vector<glm::uvec4> out = runTraversalKernel(dev, spirv, nodes, nodeBytes, mr.bvh.prims, mr.rays, who);
    std::vector<std::size_t> escaped;
    // On a device that rounds as the host, the same bits; else t up to rounding, and at a shared edge
    // (where these rays aim) either of its triangles (bvh_trace_compare.h, device_rounding.h).
    const bool exact = roundsLikeTheHost(dev);
    long mismatches = 0, checked = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (out[i].y == gpu::GPU_NODE_EMPTY) escaped.push_back(i);
        if (i % 97 == 0) {  // spot-check against the CPU twin
            const TraceResult h = cpu(mr.rays[i]);
            float t;
            std::memcpy(&t, &out[i].x, sizeof t);
            mismatches += exact ? (std::memcmp(&t, &h.t, sizeof t) != 0 || out[i].y != h.prim)
                                : !sameDistanceUpToRounding(t, h.t, mr.rays[i]);
            ++checked;
        }
    }
    checkEscapes(mr, escaped, who);
    EXPECT_LE(mismatches, exact ? 0 : std::max(1L, checked / 1000)) << who << ": " << probeRounding(dev).describe();
}

TEST(StressWatertight, DeviceTraversalNeverLetsARayOutOfTheSphereMesh) {
    VKP_REQUIRE_DEVICE(dev);
    const MeshRays& mr = meshRays();
    checkDeviceEscapes(
        dev, std::span<const std::uint32_t>(kBvhTraceSpv, std::size(kBvhTraceSpv)), mr.bvh.nodes.data(),
        mr.bvh.nodes.size() * sizeof(gpu::GpuNode),
        [&](const Ray& r) { return traceClosestCpu(mr.bvh, r.o, r.d, 0.0f, gpu::VKP_FAR); }, "device traversal");
}

/// The 4-wide layout (shared/wide_bvh.h) on the same mesh and rays: CPU twin and device.
TEST(StressWatertight, WideCpuTraversalNeverLetsARayOutOfTheSphereMesh) {
    const MeshRays& mr = meshRays();
    const std::vector<gpu::GpuWideNode> wide = buildWideNodes(mr.bvh);
    std::vector<std::size_t> escaped;
    long cut = 0;
    for (std::size_t i = 0; i < mr.rays.size(); ++i) {
        const Ray& r = mr.rays[i];
        const TraceResult h = traceClosestWideCpu(wide, mr.bvh.prims, r.o, r.d, r.tmin, r.tmax);
        if (!h.hit) escaped.push_back(i);
        cut += h.cutShort();
    }
    checkEscapes(mr, escaped, "wide CPU traversal");
    EXPECT_EQ(cut, 0);
}

TEST(StressWatertight, WideDeviceTraversalNeverLetsARayOutOfTheSphereMesh) {
    VKP_REQUIRE_DEVICE(dev);
    const MeshRays& mr = meshRays();
    const std::vector<gpu::GpuWideNode> wide = buildWideNodes(mr.bvh);
    checkDeviceEscapes(
        dev, std::span<const std::uint32_t>(kBvhTraceWideSpv, std::size(kBvhTraceWideSpv)), wide.data(),
        wide.size() * sizeof(gpu::GpuWideNode),
        [&](const Ray& r) { return traceClosestWideCpu(wide, mr.bvh.prims, r.o, r.d, 0.0f, gpu::VKP_FAR); },
        "wide device traversal");
}

}  // namespace
}  // namespace vkp::test
