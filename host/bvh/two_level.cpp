// Two-level BVH assembly (see two_level.h).
#include "bvh/two_level.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bvh/tlas.h"
#include "bvh/wide_pack.h"
#include "core/errors.h"

namespace vkp {
namespace {

constexpr std::uint32_t kMaxHeaderIndex = 1u << 30;  // material or instance index in the header word

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

float bitsToFloat(std::uint32_t u) { return glm::uintBitsToFloat(u); }
std::uint32_t floatBits(float f) { return glm::floatBitsToUint(f); }

/// Offsets the index of one binary child slot (index in lo.w, count in hi.w).
void offsetSlot(glm::vec4& lo, const glm::vec4& hi, std::uint32_t nodeOffset, std::uint32_t primOffset) {
    const std::uint32_t index = floatBits(lo.w), count = floatBits(hi.w);
    if (count > 0) lo.w = bitsToFloat(index + primOffset);
    else if (index != gpu::GPU_NODE_EMPTY) lo.w = bitsToFloat(index + nodeOffset);
}

/// The PRIM_INSTANCE primitive of instance i: header only, NaN coordinates (shared/instance.h).
gpu::GpuPrim instancePrim(std::uint32_t i) {
    const float nan = bitsToFloat(0x7fc00000u);
    gpu::GpuPrim p;
    p.p0 = glm::vec4(nan, nan, nan, bitsToFloat(gpu::PRIM_INSTANCE | (i << 2)));
    p.p1 = glm::vec4(nan, nan, nan, 0.0f);
    p.p2 = glm::vec4(nan, nan, nan, 0.0f);
    return p;
}

glm::vec4 row(const glm::dmat4& m, int r) { return glm::vec4(float(m[0][r]), float(m[1][r]), float(m[2][r]), float(m[3][r])); }

}  // namespace

gpu::GpuInstance packInstance(const MeshInstance& inst, std::uint32_t wideRoot, std::uint32_t binaryRoot) {
    const glm::dmat4& m = inst.objectToWorld;
    const double det = glm::determinant(glm::dmat3(m));
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
        throw std::invalid_argument("packInstance: the instance's map is singular or not finite");
    const glm::dmat4 w = glm::inverse(m);
    gpu::GpuInstance g;
    g.info = glm::uvec4(wideRoot, binaryRoot, det < 0.0 ? gpu::INSTANCE_MIRROR : 0u, inst.mesh);
    g.w2o0 = row(w, 0);
    g.w2o1 = row(w, 1);
    g.w2o2 = row(w, 2);
    g.o2w0 = row(m, 0);
    g.o2w1 = row(m, 1);
    g.o2w2 = row(m, 2);
    return g;
}

AppendedLevel appendBvh(FlatBvh& dst, const FlatBvh& src, std::uint32_t mesh) {
    if (src.wideNodes.empty() || src.nodes.empty()) throw std::invalid_argument("appendBvh: the level has no nodes");
    AppendedLevel at;
    at.node = std::uint32_t(dst.nodes.size());
    at.wideNode = std::uint32_t(dst.wideNodes.size());
    at.firstPrim = std::uint32_t(dst.prims.size());
    for (gpu::GpuNode n : src.nodes) {
        offsetSlot(n.a, n.b, at.node, at.firstPrim);
        offsetSlot(n.c, n.d, at.node, at.firstPrim);
        dst.nodes.push_back(n);
    }
    for (gpu::GpuWideNode n : src.wideNodes) {
        for (int k = 0; k < 4; ++k) {
            if (n.count[k] > 0) n.index[k] += at.firstPrim;
            else if (n.index[k] != gpu::GPU_NODE_EMPTY) n.index[k] += at.wideNode;
        }
        dst.wideNodes.push_back(n);
    }
    dst.prims.insert(dst.prims.end(), src.prims.begin(), src.prims.end());
    dst.primToShape.insert(dst.primToShape.end(), src.primToShape.begin(), src.primToShape.end());
    dst.primMesh.resize(dst.prims.size(), mesh);
    return at;
}

FlatBvh buildMeshBvh(const Scene& scene, const InstancedMesh& mesh, const BvhBuildOptions& options) {
    checkShapesFinite(scene, mesh.shapes, mesh.name + " triangle ");
    const auto t0 = std::chrono::steady_clock::now();
    const BvhBuildTree tree = buildBvh(mesh.shapes, options);
    const double buildMs = msSince(t0);
    const auto t1 = std::chrono::steady_clock::now();
    FlatBvh out;
    out.prims.reserve(mesh.shapes.size());
    for (std::uint32_t s : tree.primIndices) {
        if (mesh.shapes[s].material >= kMaxHeaderIndex)
            throw InputError(scene.path.string() + ": " + mesh.name + ": material index too large");
        out.prims.push_back(packShape(mesh.shapes[s], 0u));
    }
    out.primToShape = tree.primIndices;
    flattenNodes(tree, tree.primIndices.size(), out);  // spatial splits: a triangle may have several
    out.stats.buildMs = buildMs;
    out.stats.flattenMs = msSince(t1);
    const auto t2 = std::chrono::steady_clock::now();
    out.wideNodes = buildWideNodes(out);
    out.stats.wideMs = msSince(t2);
    out.stats.wideNodeCount = out.wideNodes.size();
    return out;
}

FlatBvh buildTwoLevelBvh(const Scene& scene, const BvhBuildOptions& options) {
    checkShapesFinite(scene, scene.shapes, "shape ");
    if (scene.instances.size() >= kMaxHeaderIndex)
        throw InputError(scene.path.string() + ": " + std::to_string(scene.instances.size()) + " instances: too many");
    // Bottom levels first (their boxes place the instances).
    std::vector<FlatBvh> meshes;
    std::vector<Aabb> meshBounds;
    meshes.reserve(scene.meshes.size());
    for (const InstancedMesh& m : scene.meshes) {
        meshes.push_back(buildMeshBvh(scene, m, options));
        Aabb box;
        for (const Shape& s : m.shapes) box.grow(shapeBounds(s));
        meshBounds.push_back(box);
    }
    // Top level: the shapes (lights keep their light index) and one primitive per instance.
    const auto t0 = std::chrono::steady_clock::now();
    const TopLevelItems items = topLevelItems(scene, meshBounds);
    const BvhBuildTree tree = buildTopLevel(items, options);
    const double buildMs = msSince(t0);
    const auto t1 = std::chrono::steady_clock::now();
    const std::size_t n = items.boxes.size();
    std::vector<std::uint32_t> lightPlusOne(scene.shapes.size(), 0u);
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        if (scene.lights[l] >= scene.shapes.size())
            throw InputError(scene.path.string() + ": light " + std::to_string(l) + ": shape index out of range");
        lightPlusOne[scene.lights[l]] = std::uint32_t(l + 1);
    }
    FlatBvh top;
    top.prims.reserve(n);
    top.primToShape.reserve(n);
    for (std::uint32_t item : tree.primIndices) {
        if (item < items.shapeCount) {
            const Shape& s = scene.shapes[item];
            if (s.material >= kMaxHeaderIndex)
                throw InputError(scene.path.string() + ": shape " + std::to_string(item) + ": material index too large");
            top.prims.push_back(packShape(s, lightPlusOne[item]));
            top.primToShape.push_back(item);
        } else {
            top.prims.push_back(instancePrim(std::uint32_t(item - items.shapeCount)));
            top.primToShape.push_back(FlatBvh::kNotAShape);
        }
    }
    flattenNodes(tree, n, top);
    top.wideNodes = buildWideNodes(top);
    const BvhStats topStats = top.stats;

    FlatBvh out;
    appendBvh(out, top, 0);
    std::vector<AppendedLevel> roots;
    for (std::size_t m = 0; m < meshes.size(); ++m) roots.push_back(appendBvh(out, meshes[m], std::uint32_t(m + 1)));
    out.instances.reserve(scene.instances.size());
    for (const MeshInstance& inst : scene.instances)
        out.instances.push_back(packInstance(inst, roots.at(inst.mesh).wideNode, roots.at(inst.mesh).node));

    BvhStats& st = out.stats;
    st = topStats;
    st.buildMs = buildMs;
    st.flattenMs = msSince(t1);
    std::uint32_t meshDepth = 0;
    for (const FlatBvh& m : meshes) {
        st.leafCount += m.stats.leafCount;
        st.buildMs += m.stats.buildMs;
        st.flattenMs += m.stats.flattenMs;
        st.wideMs += m.stats.wideMs;
        meshDepth = std::max(meshDepth, m.stats.maxDepth);
    }
    st.maxDepth = topStats.maxDepth + meshDepth;
    st.primCount = out.prims.size();
    st.nodeCount = out.nodes.size();
    st.wideNodeCount = out.wideNodes.size();
    st.instanceCount = scene.instances.size();
    st.meshCount = scene.meshes.size();
    st.topPrimCount = n;
    return out;
}

FlatBvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options) {
    return scene.instances.empty() ? buildFlatBvh(scene, options) : buildTwoLevelBvh(scene, options);
}

}  // namespace vkp
