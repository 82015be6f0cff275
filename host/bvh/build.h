// Binned SAH BVH builder: world-space boxes + centroids -> a binary tree of boxes and a permutation
// of the primitives in which every leaf is a contiguous range. Knows nothing of the GPU layout
// (that is flatten.h). References: Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies" (RT'07) for binning; MacDonald & Booth (1990) for the surface area heuristic.
#pragma once
#include <atomic>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkp {

/// Axis-aligned box [lo, hi] in world units. Default-constructed: empty (lo = +max, hi = -max),
/// so growing it by any point or box gives that point or box.
struct Aabb {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{-std::numeric_limits<float>::max()};

    void grow(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    /// Half the surface area (world units^2); 0 for an empty box. Flat boxes have a positive area.
    float halfArea() const {
        if (empty()) return 0.0f;
        glm::vec3 e = hi - lo;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
    /// True when b lies inside this box (closed on both sides); an empty b is inside everything.
    bool contains(const Aabb& b) const {
        if (b.empty()) return true;
        return glm::all(glm::lessThanEqual(lo, b.lo)) && glm::all(glm::lessThanEqual(b.hi, hi));
    }
};

/// Bounding box of one shape: sphere centre +- |radius| (a negative radius, the book's hollow glass
/// trick, has the same box), quad's 4 corners, triangle's 3 vertices. Not padded: a flat box is
/// hit by the robust slab test (shared/intersect.h). A moving shape (Shape::velocity, motion blur)
/// gets the union of its boxes at times 0 and 1 (shapeAt), which holds it at every time between.
Aabb shapeBounds(const Shape& s);

/// Builder parameters. Costs are those of the SAH: C(split) = Ct + Ci (A_L N_L + A_R N_R) / A,
/// C(leaf) = Ci N.
struct BvhBuildOptions {
    std::uint32_t binCount = 16;     ///< SAH bins per axis over the centroid bounds, in [2, 256]
    std::uint32_t maxLeafSize = 4;   ///< primitives per leaf at most, >= 1
    std::uint32_t maxDepth = 32;     ///< leaf depth bound (root = 0), in [1, 32]; always honoured
    float traversalCost = 1.0f;      ///< Ct
    float intersectionCost = 1.0f;   ///< Ci
    /// Threads to build with (subtrees of >= 4096 primitives go to free threads); 0: one per
    /// hardware thread. The tree is the same, node for node, for every count.
    std::uint32_t threads = 0;
    /// > 0: the BVHs built over shapes (buildBvh's shape overload: a scene's shapes, each
    /// instanced mesh) get spatial splits (host/bvh/sbvh.h), with at most this fraction
    /// of extra primitive references; 0: off (binned SAH over whole primitives).
    float spatialSplits = 0.0f;
};

/// One node of the build tree. Inner nodes: count == 0, children at nodes[index] and
/// nodes[index + 1]. Leaves: count >= 1 primitives, primIndices[index .. index + count).
struct BvhBuildNode {
    Aabb box;
    std::uint32_t index = 0;
    std::uint32_t count = 0;
    bool isLeaf() const { return count != 0; }
};

/// The build result. nodes[0] is the root; nodes is empty when there are no primitives.
/// primIndices is a permutation of 0..n-1 (input order) such that each leaf is a range of it.
struct BvhBuildTree {
    std::vector<BvhBuildNode> nodes;
    std::vector<std::uint32_t> primIndices;
    std::uint32_t maxDepth = 0;  ///< deepest leaf (root = 0)
};

/// Levels of balanced binary splits needed to bring n primitives (or references) down to leaves of
/// at most leafSize (>= 1): the depth budget both builders keep (build.cpp, sbvh.cpp).
std::uint32_t levelsNeeded(std::size_t n, std::uint32_t leafSize);

/// Claims one of the threads counted in `freeThreads` for a forked subtree (both builders; the
/// claimer adds it back when the subtree is built): false when none is free.
bool takeThread(std::atomic<int>& freeThreads);

/// Build a BVH over n primitives given by their boxes and centroids (equal sizes, finite, lo <= hi;
/// otherwise std::invalid_argument). Iterative (no recursion), on options.threads threads, with the
/// same result for every thread count. Guarantees: every leaf holds
/// 1..maxLeafSize primitives; a root with >= 2 primitives is always split (so only n <= 1 gives a
/// leaf root); leaf depth <= options.maxDepth, enforced by switching from SAH to object-median
/// splits when the remaining depth budget becomes tight (so adversarial input, e.g. exponentially
/// spaced primitives, cannot make the tree deeper than the GPU traversal stack). Primitives whose
/// centroids all coincide are split at the median index.
BvhBuildTree buildBvh(std::span<const Aabb> boxes, std::span<const glm::vec3> centroids,
                      const BvhBuildOptions& options = {});

/// Convenience: buildBvh over shapeBounds() of each shape, centroids = box centres; with
/// options.spatialSplits > 0, buildSbvh (sbvh.h) instead, whose primIndices may name a shape more
/// than once.
BvhBuildTree buildBvh(std::span<const Shape> shapes, const BvhBuildOptions& options = {});

}  // namespace vkp
