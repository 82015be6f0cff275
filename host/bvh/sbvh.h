// Spatial-split BVH builder (SBVH): the binned SAH build of build.h, where a node may also be split
// by a plane that cuts the primitives crossing it, each part going to its side with the box of
// the part (Stich, Friedrich and Dietrich 2009, "Spatial Splits in Bounding Volume Hierarchies").
// A primitive may then sit in several leaves. Measured as issue 18's lever in the layout
// benchmark (tests/bench/bench_bvh_layout.cpp, docs/performance.md "Levers that did not win");
// the renderer builds with buildBvh.
#pragma once
#include <cstdint>
#include <span>

#include "bvh/build.h"
#include "scene/scene.h"

namespace vkp {

/// Parameters of buildSbvh.
struct SbvhOptions {
    /// Bins, leaf size, depth bound, costs and threads as for buildBvh (the same tree for every
    /// thread count).
    BvhBuildOptions base;
    /// Spatial splits are tried only where the best object split's two boxes overlap by more than
    /// alpha x the root's surface area (Stich et al. sec. 4.4). Their 1e-5 lets almost every node
    /// try; on the suite's 1M-triangle dense mesh 1e-2 kept the whole gain (16,535 instructions
    /// per sample against 16,528; 18,422 without splits) for a third of the build's instructions
    /// (docs/performance.md "Spatial splits").
    float alpha = 1e-2f;
    /// Bins per axis over the node's box for the spatial split, in [2, 256].
    std::uint32_t spatialBins = 32;
    /// References beyond one per primitive, at most this fraction of the primitives (>= 0); once
    /// spent, nodes split by objects only.
    float maxDuplication = 0.3f;
};

/// The two parts of a primitive's reference cut by the plane x[axis] = pos: the boxes of the
/// primitive's parts on each side (its polygon clipped by the plane; a sphere's or a moving
/// shape's box is cut as a box), each within `box` (the reference's box so far) and closed at the
/// plane. An empty result box: nothing of the primitive inside `box` lies on that side.
/// The boxes are widened by a few ulps where they are not the plane or `box`'s own faces, so
/// rounding in the edge-plane intersections never leaves a part of the primitive outside them.
void splitReference(const Shape& s, const Aabb& box, int axis, float pos, Aabb& left, Aabb& right);

/// Build an SBVH over the shapes. The result is a BvhBuildTree whose primIndices holds one entry
/// per reference: every shape at least once, at most n (1 + maxDuplication) entries in all, each
/// leaf a range of 1..maxLeafSize distinct shapes whose box holds the part of each shape the leaf
/// is for. Leaf depth <= base.maxDepth (object-median splits when the budget becomes tight, as
/// buildBvh). Throws std::invalid_argument on options out of range or a non-finite shape box.
BvhBuildTree buildSbvh(std::span<const Shape> shapes, const SbvhOptions& options = {});

}  // namespace vkp
