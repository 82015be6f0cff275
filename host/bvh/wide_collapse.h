// Collapse of a flattened binary BVH (FlatBvh, two child boxes per node) into a 4-wide tree: each
// wide node takes the up to four subtrees found by repeatedly opening the inner child of largest
// surface area (the usual greedy collapse, e.g. Wald et al. 2008 "Getting rid of packets" and
// madmann91/bvh's mini-tree collapse). Leaves stay the binary tree's leaves, so FlatBvh::prims is
// reused unchanged. Knows nothing of the GPU layout (that is wide_pack.h).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "bvh/build.h"
#include "bvh/flatten.h"

namespace vkp {

/// One child slot of a wide node. count >= 1: a leaf of prims [index, index + count);
/// count == 0: an inner child, node index `index`, or an empty slot (index == GPU_NODE_EMPTY, empty box).
struct WideChild {
    Aabb box;
    std::uint32_t index = gpu::GPU_NODE_EMPTY;
    std::uint32_t count = 0;
    bool empty() const { return count == 0 && index == gpu::GPU_NODE_EMPTY; }
    bool isLeaf() const { return count != 0; }
    bool isInner() const { return count == 0 && index != gpu::GPU_NODE_EMPTY; }
};

/// A 4-wide tree. nodes[0] is the root; an inner child's node comes after its parent (depth first).
/// Used slots come first in each node, in the binary tree's left-to-right order.
struct WideTree {
    std::vector<std::array<WideChild, 4>> nodes;
    std::uint32_t maxDepth = 0;  ///< deepest wide node (root = 0)
};

/// Collapse `bvh`'s binary nodes into 4-wide nodes. Throws std::invalid_argument if a node refers
/// outside bvh.nodes / bvh.prims (a malformed FlatBvh).
WideTree collapseToWide(const FlatBvh& bvh);

}  // namespace vkp
