// Build tree -> GpuNode/GpuPrim arrays (see flatten.h and the layout comments in gpu_types.h).
#include "bvh/flatten.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bvh/wide_pack.h"
#include "core/errors.h"
#include "shared/intersect.h"

namespace vkp {
namespace {

constexpr std::uint32_t kMaxMaterial = 1u << 30;

float bitsToFloat(std::uint32_t u) { return glm::uintBitsToFloat(u); }

glm::vec4 v4(const glm::vec3& v, float w) { return glm::vec4(v, w); }

/// Writes one child slot of a GpuNode: box in (lo, hi).xyz, index in lo.w, count in hi.w.
void setChild(glm::vec4& lo, glm::vec4& hi, const Aabb& box, std::uint32_t index,
              std::uint32_t count) {
    lo = v4(box.lo, bitsToFloat(index));
    hi = v4(box.hi, bitsToFloat(count));
}

void setEmpty(glm::vec4& lo, glm::vec4& hi) {
    setChild(lo, hi, Aabb{}, gpu::GPU_NODE_EMPTY, 0u);  // Aabb{}: min = +max, max = -max
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

gpu::GpuPrim packShape(const Shape& s, std::uint32_t lightPlusOne) {
    const auto kind = static_cast<std::uint32_t>(s.type);
    const float header = bitsToFloat(kind | (s.material << 2));
    const float light = bitsToFloat(lightPlusOne);
    gpu::GpuPrim p;
    switch (s.type) {
        case ShapeType::Sphere:
            p.p0 = v4(s.p0, header);
            p.p1 = glm::vec4(0.0f, 0.0f, 0.0f, s.radius);
            p.p2 = glm::vec4(0.0f, 0.0f, 0.0f, light);
            break;
        case ShapeType::Quad:
            p.p0 = v4(s.p0, header);
            p.p1 = v4(s.p1, 0.0f);
            p.p2 = v4(s.p2, light);
            break;
        case ShapeType::Triangle:
            p.p0 = v4(s.p0, header);
            // Vertices, not edges (shaders/shared/gpu_types.h); p1.w flags a zero-area triangle.
            p.p1 = v4(s.p1, gpu::triangleHasZeroArea(s.p0, s.p1, s.p2) ? 1.0f : 0.0f);
            p.p2 = v4(s.p2, light);
            break;
    }
    return p;
}

double sahCost(const BvhBuildTree& tree, float traversalCost, float intersectionCost) {
    if (tree.nodes.empty()) return 0.0;
    const double rootArea = tree.nodes[0].box.halfArea();
    auto ratio = [&](const Aabb& b) { return rootArea > 0.0 ? b.halfArea() / rootArea : 1.0; };
    double cost = tree.nodes[0].isLeaf() ? traversalCost : 0.0;  // the flat root above a leaf
    for (const BvhBuildNode& n : tree.nodes) {
        cost += n.isLeaf() ? ratio(n.box) * n.count * intersectionCost : ratio(n.box) * traversalCost;
    }
    return cost;
}

FlatBvh flattenBvh(const BvhBuildTree& tree, const Scene& scene) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = scene.shapes.size();
    // A spatial-split tree (sbvh.h) may reference a shape from several leaves: m >= n references.
    const std::size_t m = tree.primIndices.size();
    if (m < n || (n > 0) != !tree.nodes.empty())
        throw std::invalid_argument("flattenBvh: the tree was not built over these shapes");

    std::vector<std::uint32_t> lightPlusOne(n, 0u);
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        if (scene.lights[l] >= n)
            throw InputError(scene.path.string() + ": light " + std::to_string(l) +
                             ": shape index " + std::to_string(scene.lights[l]) + " out of range");
        lightPlusOne[scene.lights[l]] = static_cast<std::uint32_t>(l + 1);
    }

    FlatBvh out;
    out.prims.resize(m);
    out.primToShape = tree.primIndices;
    for (std::size_t i = 0; i < m; ++i) {
        const std::uint32_t s = tree.primIndices[i];
        if (s >= n) throw std::invalid_argument("flattenBvh: primitive index out of range");
        if (scene.shapes[s].material >= kMaxMaterial)
            throw InputError(scene.path.string() + ": shape " + std::to_string(s) +
                             ": material index too large");
        out.prims[i] = packShape(scene.shapes[s], lightPlusOne[s]);
    }

    flattenNodes(tree, m, out);
    out.stats.flattenMs = msSince(t0);
    return out;
}

void flattenNodes(const BvhBuildTree& tree, std::size_t n, FlatBvh& out) {
    if (tree.primIndices.size() != n || (n > 0) != !tree.nodes.empty())
        throw std::invalid_argument("flattenNodes: the tree was not built over these primitives");
    BvhStats& st = out.stats;
    st.primCount = n;
    st.sahCost = sahCost(tree);
    if (tree.nodes.empty() || tree.nodes[0].isLeaf()) {
        gpu::GpuNode root;
        if (tree.nodes.empty()) {
            setEmpty(root.a, root.b);
        } else {
            const BvhBuildNode& leaf = tree.nodes[0];
            setChild(root.a, root.b, leaf.box, leaf.index, leaf.count);
            st.leafCount = 1;
            st.maxDepth = 1;
        }
        setEmpty(root.c, root.d);
        out.nodes.push_back(root);
        st.nodeCount = 1;
        return;
    }

    // Depth-first, pre-order, left child first. Each entry: build node, flat parent, slot (0/1).
    struct Item {
        std::uint32_t node, parent, slot, depth;
    };
    out.nodes.reserve(tree.nodes.size() / 2 + 1);
    std::vector<Item> stack{{0u, gpu::GPU_NODE_EMPTY, 0u, 0u}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const auto flat = static_cast<std::uint32_t>(out.nodes.size());
        out.nodes.emplace_back();
        if (it.parent != gpu::GPU_NODE_EMPTY) {
            gpu::GpuNode& p = out.nodes[it.parent];
            (it.slot == 0 ? p.a : p.c).w = bitsToFloat(flat);
        }
        const BvhBuildNode& b = tree.nodes[it.node];
        if (b.index + 1 >= tree.nodes.size())
            throw std::invalid_argument("flattenBvh: child index out of range");
        for (std::uint32_t slot = 0; slot < 2; ++slot) {
            const BvhBuildNode& c = tree.nodes[b.index + slot];
            gpu::GpuNode& f = out.nodes[flat];
            glm::vec4& lo = slot == 0 ? f.a : f.c;
            glm::vec4& hi = slot == 0 ? f.b : f.d;
            if (c.isLeaf()) {
                if (std::size_t(c.index) + c.count > n)
                    throw std::invalid_argument("flattenBvh: leaf range out of range");
                setChild(lo, hi, c.box, c.index, c.count);
                ++st.leafCount;
                st.maxDepth = std::max(st.maxDepth, it.depth + 1);
            } else {
                setChild(lo, hi, c.box, gpu::GPU_NODE_EMPTY, 0u);  // index patched when visited
            }
        }
        // Right pushed first so the left subtree is emitted next (left inner child = flat + 1).
        for (int slot = 1; slot >= 0; --slot) {
            const std::uint32_t c = b.index + static_cast<std::uint32_t>(slot);
            if (!tree.nodes[c].isLeaf())
                stack.push_back({c, flat, static_cast<std::uint32_t>(slot), it.depth + 1});
        }
        if (out.nodes.size() > tree.nodes.size())
            throw std::invalid_argument("flattenBvh: the tree has a cycle");
    }
    st.nodeCount = out.nodes.size();
}

const Shape* primShape(const Scene& scene, const FlatBvh& bvh, std::size_t i) {
    const std::uint32_t s = bvh.primToShape.at(i);
    const std::uint32_t mesh = bvh.primMesh.empty() ? 0u : bvh.primMesh.at(i);
    if (mesh == 0) return s == FlatBvh::kNotAShape ? nullptr : &scene.shapes.at(s);
    return &scene.meshes.at(mesh - 1).shapes.at(s);
}

void checkShapesFinite(const Scene& scene, std::span<const Shape> shapes, const std::string& what) {
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const Shape& s = shapes[i];
        bool ok = finite(s.p0) && std::isfinite(s.radius);
        if (s.type != ShapeType::Sphere) ok = ok && finite(s.p1) && finite(s.p2);
        // Corners/extents may still overflow to infinity (a quad at 3e38 with a large edge).
        Aabb box = shapeBounds(s);
        ok = ok && finite(box.lo) && finite(box.hi) && finite(0.5f * (box.lo + box.hi));
        if (!ok)
            throw InputError(scene.path.string() + ": " + what + std::to_string(i) +
                             ": non-finite coordinates or radius");
    }
}

FlatBvh buildFlatBvh(const Scene& scene, const BvhBuildOptions& options) {
    checkShapesFinite(scene, scene.shapes, "shape ");
    const auto t0 = std::chrono::steady_clock::now();
    BvhBuildTree tree = buildBvh(scene.shapes, options);
    const double buildMs = msSince(t0);
    FlatBvh flat = flattenBvh(tree, scene);
    flat.stats.buildMs = buildMs;
    const auto t1 = std::chrono::steady_clock::now();
    flat.wideNodes = buildWideNodes(flat);
    flat.stats.wideMs = msSince(t1);
    flat.stats.wideNodeCount = flat.wideNodes.size();
    return flat;
}

}  // namespace vkp
