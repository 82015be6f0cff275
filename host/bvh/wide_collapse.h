// Collapse of a flattened binary BVH (FlatBvh, two child boxes per node) into a 4-wide tree (or
// N-wide: the layout benchmark measures 8): each wide node takes the up to four (N) subtrees
// found by repeatedly opening the inner child of largest surface area (the usual greedy collapse,
// e.g. Wald et al. 2008 "Getting rid of packets" and madmann91/bvh's mini-tree collapse). Leaves
// stay the binary tree's leaves, so FlatBvh::prims is reused unchanged. Knows nothing of the GPU
// layout (that is wide_pack.h).
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

/// An N-wide tree. nodes[0] is the root; an inner child's node comes after its parent (depth
/// first). Used slots come first in each node, in the binary tree's left-to-right order.
template <std::size_t N>
struct WideTreeOf {
    std::vector<std::array<WideChild, N>> nodes;
    std::uint32_t maxDepth = 0;  ///< deepest wide node (root = 0)
};
/// The kernels' tree: 4 wide (shared/wide_bvh.h).
using WideTree = WideTreeOf<4>;

/// Collapse `bvh`'s binary nodes into N-wide nodes (N = 4: the kernels'; 8: only the layout
/// benchmark's 8-wide variant). Throws std::invalid_argument if a node refers outside bvh.nodes /
/// bvh.prims (a malformed FlatBvh).
template <std::size_t N>
WideTreeOf<N> collapseToWideOf(const FlatBvh& bvh);

/// Collapse `bvh` into the kernels' 4-wide nodes.
inline WideTree collapseToWide(const FlatBvh& bvh) { return collapseToWideOf<4>(bvh); }

}  // namespace vkp
