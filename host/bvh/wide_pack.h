// Packing of a 4-wide tree (wide_collapse.h) into the GPU layout GpuWideNode
// (shaders/shared/wide_bvh.h): the only host code that knows that layout.
#pragma once
#include <vector>

#include "bvh/wide_collapse.h"
#include "shared/wide_bvh.h"

namespace vkp {

/// One GpuWideNode per WideTree node, same order. Empty slots get an inverted box
/// (min = +max float, max = -max float), index GPU_NODE_EMPTY, count 0.
std::vector<gpu::GpuWideNode> packWide(const WideTree& tree);

/// An 8-wide tree (the layout benchmark's variant, shaders/tests/traverse_wide8.glsl) as two
/// GpuWideNodes per node: 2i holds children 0-3 of node i, 2i + 1 children 4-7; an inner child's
/// index is its 8-wide node's.
std::vector<gpu::GpuWideNode> packWide8(const WideTreeOf<8>& tree);

/// Collapse and pack in one call: the wide node array of a FlatBvh (whose prims it uses).
inline std::vector<gpu::GpuWideNode> buildWideNodes(const FlatBvh& bvh) { return packWide(collapseToWide(bvh)); }

}  // namespace vkp
