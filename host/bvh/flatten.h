// Flattening: the build tree -> the GPU layout (GpuNode, GpuPrim of shared/gpu_types.h). This is
// the only host code that knows how a GpuNode is laid out.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bvh/build.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"
#include "shared/instance.h"
#include "shared/wide_bvh.h"

namespace vkp {

/// Numbers describing a flattened BVH.
struct BvhStats {
    std::size_t primCount = 0;
    std::size_t nodeCount = 0;  ///< GpuNodes (each holds two child boxes); >= 1
    std::size_t leafCount = 0;  ///< non-empty leaves (child slots with a primitive count)
    std::uint32_t maxDepth = 0;   ///< deepest leaf; the root node is depth 0, its children depth 1
    /// SAH cost with Ct = Ci = 1: sum over GpuNodes of A(node)/A(root) + sum over leaves of
    /// A(leaf)/A(root) * count, A = surface area (ratios taken as 1 when A(root) = 0).
    double sahCost = 0.0;
    double buildMs = 0.0;    ///< wall time of buildBvh (milliseconds)
    double flattenMs = 0.0;  ///< wall time of flattening and packing (milliseconds)
    double wideMs = 0.0;     ///< wall time of the 4-wide collapse and packing (milliseconds)
    std::size_t wideNodeCount = 0;  ///< GpuWideNodes of FlatBvh::wideNodes
    /// Two-level BVH (host/bvh/two_level.h): instances, shared meshes, top-level primitives (the
    /// scene's shapes plus one per instance); the counts above are then totals over both levels.
    std::size_t instanceCount = 0, meshCount = 0, topPrimCount = 0;
};

/// A BVH in the GPU layout. nodes[0] is the root; inner children come after their parent
/// (depth-first, left child first, so a left inner child is parent + 1); each leaf is the
/// contiguous range [first, first + count) of prims. primToShape[i] is the Scene::shapes index of
/// prims[i].
struct FlatBvh {
    std::vector<gpu::GpuNode> nodes;
    std::vector<gpu::GpuPrim> prims;
    std::vector<std::uint32_t> primToShape;
    /// The same tree collapsed to 4-wide nodes (shared/wide_bvh.h, host/bvh/wide_pack.h) over the
    /// same prims: what the kernels traverse. Filled by buildFlatBvh (empty after flattenBvh alone).
    std::vector<gpu::GpuWideNode> wideNodes;
    /// Two-level BVH only (host/bvh/two_level.h): the instances that PRIM_INSTANCE primitives name,
    /// and per primitive 0 (a top-level primitive: primToShape indexes Scene::shapes, or is
    /// kNotAShape for an instance) or m + 1 (a triangle of Scene::meshes[m]: primToShape indexes its
    /// shapes). primMesh is empty for a one-level BVH.
    std::vector<gpu::GpuInstance> instances;
    std::vector<std::uint32_t> primMesh;
    static constexpr std::uint32_t kNotAShape = 0xffffffffu;
    BvhStats stats;
};

/// The shape behind primitive i of bvh (a Scene::shapes entry, or a triangle of an instanced mesh
/// in object space), or nullptr for an instance primitive.
const Shape* primShape(const Scene& scene, const FlatBvh& bvh, std::size_t i);

/// Pack one shape (layout: shaders/shared/gpu_types.h GpuPrim): header = kind | material << 2
/// (p0.w bits), sphere radius in p1.w, a triangle's three vertices and in p1.w its zero-area flag
/// (1: never hit), p2.w = bits of lightPlusOne (light index + 1, 0 = none).
gpu::GpuPrim packShape(const Shape& s, std::uint32_t lightPlusOne);

/// Flatten a build tree over scene.shapes (tree built from those shapes in that order; a
/// spatial-split tree, sbvh.h, may name a shape from several leaves: one prim per reference). A tree
/// whose root is a leaf (0 or 1 primitive) becomes one GpuNode whose unused child slot is empty
/// (GPU_NODE_EMPTY, inverted box). Throws InputError on a material index >= 2^30 or a light index
/// that is not a shape; std::invalid_argument when the tree does not match the shapes.
FlatBvh flattenBvh(const BvhBuildTree& tree, const Scene& scene);

/// The node half of flattenBvh: out.nodes and out.stats (counts, depth, SAH cost) of `tree`, built
/// over n primitives that out.prims holds (or will hold) in tree order. Throws std::invalid_argument
/// when the tree does not match n.
void flattenNodes(const BvhBuildTree& tree, std::size_t n, FlatBvh& out);

/// Throws InputError "<file>: <what> <i>: non-finite coordinates or radius" for the first shape
/// whose data or box is not finite.
void checkShapesFinite(const Scene& scene, std::span<const Shape> shapes, const std::string& what);

/// Build (binned SAH, buildBvh), flatten the scene's shapes and collapse the result to 4-wide
/// nodes (wideNodes); fills stats including times.
/// Throws InputError (one line, naming scene.path and the shape) on non-finite shape data.
FlatBvh buildFlatBvh(const Scene& scene, const BvhBuildOptions& options = {});

/// SAH cost of a build tree as defined in BvhStats::sahCost (the flat root counted once).
double sahCost(const BvhBuildTree& tree, float traversalCost = 1.0f, float intersectionCost = 1.0f);

}  // namespace vkp
