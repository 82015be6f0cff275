// The key of a render: everything that decides its samples, as named text values. Two renders
// with equal keys add exactly the same value for sample i of pixel p, so a checkpoint may be
// continued (`--resume`) and parts may be merged (`vkpath merge`) only under equal keys.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "render/gpu_arrays.h"
#include "render/render_options.h"

namespace vkp {

struct RenderKey {
    /// (name, value) in a fixed order: "vkpath" (version), "size", "seed", "max depth", "rr depth",
    /// "sampler", "sequence", "light pick", "light sampling", "solid-angle min", "adaptive",
    /// "variant", "kernel" (a 64-bit FNV-1a hash of the kernel's SPIR-V: builds of one version
    /// with other shaders differ), then "scene" last: a 64-bit FNV-1a hash (hex) of every array uploaded to the
    /// device (BVH, primitives, materials, lights, textures, environment, camera), which covers
    /// the scene file and everything it includes. Speed options (workgroup, tile order, samples per
    /// dispatch) and the outputs are not in it: they do not change a sample.
    std::vector<std::pair<std::string, std::string>> entries;
};

/// The key of the render that `arrays` (packGpuArrays of the scene with `options`) describes.
RenderKey renderKey(const GpuArrays& arrays, const RenderOptions& options);

/// Empty when `have` and `want` are equal; else one phrase naming the first entry that differs,
/// e.g. "seed is 7 in it, 1 here" (`have` is the file's, `want` this render's).
std::string keyMismatch(const RenderKey& have, const RenderKey& want);

}  // namespace vkp
