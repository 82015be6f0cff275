// The two-level BVH of a scene with instances (Scene::meshes, Scene::instances), in the one-array
// GPU layout the kernels read (FlatBvh): the only host code that knows how the levels are joined.
//
//   prims:     [top level | mesh 0's triangles | mesh 1's triangles | ...]
//   nodes:     [top level | mesh 0's binary nodes | ...]  (each level flattened as flatten.h does)
//   wideNodes: [top level | mesh 0's 4-wide nodes | ...]  (each level collapsed as wide_collapse.h does)
//
// Node and primitive indices of an appended level are offset so that they index these arrays. The
// top level's primitives are the scene's shapes and one PRIM_INSTANCE primitive per instance
// (shared/instance.h), whose GpuInstance holds the object-to-world map, its inverse and its mesh's
// root in both node arrays. Builder (build.h, tlas.h), layout (this file) and traversal
// (traverse_wide_cpu.h, lib/traverse_wide.glsl) are separate pieces with separate tests.
#pragma once
#include <cstdint>

#include "bvh/build.h"
#include "bvh/flatten.h"

namespace vkp {

/// The GPU record of one instance (shared/instance.h): rows of objectToWorld and of its inverse
/// (computed in double), each rounded to float once; info = (wideRoot, binaryRoot, INSTANCE_MIRROR
/// if the determinant is negative, mesh). Throws std::invalid_argument for a singular or non-finite map.
gpu::GpuInstance packInstance(const MeshInstance& inst, std::uint32_t wideRoot, std::uint32_t binaryRoot);

/// Where appendBvh put a level: its root in dst.nodes and in dst.wideNodes, its first primitive.
struct AppendedLevel {
    std::uint32_t node = 0, wideNode = 0, firstPrim = 0;
};

/// Appends src's nodes, wide nodes (both must be filled) and prims to dst, with child node indices
/// and leaf primitive ranges offset into dst's arrays; primToShape is appended as is and primMesh
/// with `mesh` (0: top level, m + 1: Scene::meshes[m]). Empty child slots stay empty.
AppendedLevel appendBvh(FlatBvh& dst, const FlatBvh& src, std::uint32_t mesh);

/// One bottom-level BVH: the binned-SAH tree over mesh.shapes (object space), flattened and
/// collapsed; its prims are not lights. Throws InputError on non-finite data.
FlatBvh buildMeshBvh(const Scene& scene, const InstancedMesh& mesh, const BvhBuildOptions& options = {});

/// The two-level BVH of `scene` (see above); stats are totals over the levels (sahCost: the top
/// level's), with instanceCount, meshCount and topPrimCount set. Throws InputError like buildFlatBvh.
FlatBvh buildTwoLevelBvh(const Scene& scene, const BvhBuildOptions& options = {});

/// buildTwoLevelBvh when the scene has instances, else buildFlatBvh: what the renderer uploads.
FlatBvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options = {});

}  // namespace vkp
