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

/// Collapse and pack in one call: the wide node array of a FlatBvh (whose prims it uses).
inline std::vector<gpu::GpuWideNode> buildWideNodes(const FlatBvh& bvh) { return packWide(collapseToWide(bvh)); }

}  // namespace vkp
