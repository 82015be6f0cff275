// The top level of a two-level BVH (instancing, host/bvh/two_level.h): what the binned-SAH builder
// (build.h) is run over. Its items are the scene's world-space shapes and one box per instance, the
// instance's mesh box placed in the world. Knows nothing of the GPU layout.
// References: pbrt-v4 sec. 7.1.4 (object instancing: instances as primitives of the top-level
// BVH, each holding a transform and a shared bottom-level BVH); Wald, Benthin, Slusallek,
// "Distributed Interactive Ray Tracing of Dynamic Scenes" (2003), the two-level scheme.
#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/build.h"
#include "scene/scene.h"

namespace vkp {

/// The world box of object-space box `box` under the affine map m: its eight corners mapped in
/// double, then padded outwards by 2^-16 of the box's largest |coordinate| and extent before rounding
/// to float. The pad covers the rounding of the ray's map into object space (a few eps of the ray
/// origin's coordinates) for ray origins up to about 2^8 times farther from the world origin than
/// the box: a ray that hits the mesh in object space then always enters the world box. An empty box
/// stays empty.
Aabb transformedBounds(const Aabb& box, const glm::dmat4& m);

/// The top level's build input. Item i < shapeCount is Scene::shapes[i] (shapeBounds, centroid the
/// box centre); item shapeCount + j is instance j (its mesh's box placed by transformedBounds).
struct TopLevelItems {
    std::vector<Aabb> boxes;
    std::vector<glm::vec3> centroids;
    std::size_t shapeCount = 0;
};

/// The items of `scene` given each mesh's object-space box (meshBounds[m] for Scene::meshes[m]).
/// Throws std::invalid_argument if an instance names a mesh without a box.
TopLevelItems topLevelItems(const Scene& scene, std::span<const Aabb> meshBounds);

/// The binned-SAH tree over the items (buildBvh; primIndices are item numbers).
inline BvhBuildTree buildTopLevel(const TopLevelItems& items, const BvhBuildOptions& options = {}) {
    return buildBvh(items.boxes, items.centroids, options);
}

}  // namespace vkp
