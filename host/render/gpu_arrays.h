// The one CPU-side packing step of a render: every array the kernel reads, built from the scene, its
// BVH and the render options, with the sizes of the per-pixel buffers the kernel writes; and the one
// check of all of them against a device's limits (fitProblem). This is the only code that knows
// device-side sizes. No Vulkan: unit-tested on the host (tests/unit/test_gpu_arrays.cpp);
// render/renderer.cpp uploads the arrays as they are, `vkpath info` prints their sizes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/flatten.h"
#include "render/aov.h"
#include "render/features.h"
#include "render/kernel_bindings.h"
#include "render/render_options.h"
#include "scene/scene.h"
#include "shared/aov.h"
#include "shared/gpu_types.h"
#include "shared/instance.h"
#include "shared/wide_bvh.h"

namespace vkp {

struct DeviceInfo;

/// What decides whether a render fits a device: its Vulkan limits (0 where not reported) and the
/// host's memory, which holds the read-back sums (and, on lavapipe, the device memory itself).
struct DeviceLimits {
    std::uint64_t maxTexelBufferElements = 0;
    std::uint64_t maxStorageBufferRange = 0;   ///< bytes one storage-buffer binding may span
    std::uint64_t maxUniformBufferRange = 0;
    std::uint64_t maxMemoryAllocationSize = 0;  ///< bytes of one buffer (0: not reported, not checked)
    std::uint64_t deviceLocalBytes = 0;         ///< largest device-local heap (0: not checked)
    std::uint64_t hostMemoryBytes = 0;          ///< physical memory of the host (0: not checked)
    std::uint32_t maxComputeWorkGroupCount[2] = {0, 0};
    std::uint32_t maxComputeWorkGroupSize[2] = {0, 0};
    std::uint32_t maxComputeWorkGroupInvocations = 0;
    /// Descriptors per compute stage (DeviceInfo's; 0: not checked): the kernel's bindings of each kind
    /// (kernelBindingCount) must fit.
    std::uint32_t maxPerStageDescriptorUniformBuffers = 0;
    std::uint32_t maxPerStageDescriptorStorageBuffers = 0;
    std::uint32_t maxPerStageDescriptorSampledImages = 0;
    std::uint32_t maxPerStageResources = 0;
    std::uint32_t subgroupSize = 0;  ///< lanes of a subgroup (0: not reported): the automatic workgroup's
};

/// The limits of a device as vk/instance.cpp described it, with this host's physical memory.
DeviceLimits deviceLimits(const DeviceInfo& device);
/// The physical memory of this host (sysconf), 0 if unknown.
std::uint64_t hostPhysicalMemory();

/// One buffer of the kernel, in binding order (kKernelBindings).
struct BufferSize {
    const KernelBinding* binding;
    std::uint64_t bytes = 0;   ///< what the kernel may address (before GpuBuffer's rounding)
    std::uint64_t texels = 0;  ///< texel buffers: elements of its format, else 0
};

/// Host bytes per pixel while rendering: the read-back of one compensated sum (floats, reused for
/// the other), both combined in double (PixelSums) and the mean image.
inline constexpr std::uint64_t kHostBytesPerPixel = 32 + 2 * 32 + 12;
/// Device bytes per pixel of each accumulation buffer: two vec4 (the sum and its compensation).
inline constexpr std::uint64_t kAccumBytesPerPixel = 2 * 16;
/// Device bytes per pixel of the feature images' sums (`--aov`): shared/aov.h's vec4s.
inline constexpr std::uint64_t kAovBytesPerPixel = 16 * gpu::AOV_VEC4_PER_PIXEL;
/// Adaptive sampling dispatches its active pixels as rows of this many workgroups.
inline constexpr std::uint32_t kAdaptiveGroupsPerRow = 4096;

struct GpuArrays {
    Features features;        ///< the pipeline variant (specialization constants)
    gpu::GpuFrame frame{};    ///< the uniform block
    std::vector<gpu::GpuWideNode> nodes;  ///< 4-wide BVH nodes (the layout the kernel traverses)
    std::vector<gpu::GpuPrim> prims;
    std::vector<glm::vec4> materials;     ///< GpuMaterial texels, then the GGX albedo table (glTF BRDF variants)
    std::vector<gpu::GpuLight> lights;
    std::vector<glm::vec4> envTexels;
    std::vector<float> envDistribution;
    std::vector<glm::uvec4> attributes;   ///< vertex-attribute records (token texel when unused)
    std::vector<glm::uvec4> texInfo;      ///< texture headers and material texture records
    std::vector<std::uint32_t> texels;    ///< RGBA8 texels of every image
    std::vector<gpu::GpuInstance> instances;  ///< a token record when there are none
    std::vector<gpu::GpuMotion> motion;       ///< per primitive (motion blur); a token texel without HAS_MOTION
    std::vector<std::uint32_t> activePixels;  ///< adaptive sampling: the first active-pixel list (every pixel)
    std::uint32_t width = 0, height = 0;
    bool adaptive = false;
    // For fitProblem's messages: the scene file, its images and its environment map.
    std::string sceneName;
    std::size_t imageCount = 0;
    std::string largestImage;  ///< name and size, e.g. "\"checker.png\" 512x512" (empty: no image)
    std::uint32_t envWidth = 0, envHeight = 0;
    /// The kernel's frame for the feature images' position and depth (render/aov.h).
    AovFrame aovFrame;

    std::uint64_t pixels() const { return std::uint64_t(width) * height; }
    /// The host data of a read-only binding, or empty for a buffer the kernel writes (zeroed).
    std::span<const std::byte> hostData(std::uint32_t binding) const;
    /// The size of every binding, in binding order, for the whole image (one band).
    std::vector<BufferSize> sizes() const;
    /// Bytes per pixel of a per-pixel binding (accumulation, adaptive sampling), 0 for the others.
    std::uint64_t bytesPerPixel(std::uint32_t binding) const;
    /// Bytes of the read-only scene data (every texel buffer and the frame).
    std::uint64_t sceneBytes() const;
    /// Bytes of the buffers the kernel writes (accumulation, adaptive sampling, counters).
    std::uint64_t pixelBytes() const;
};

/// Rows [firstRow, firstRow + rows) of the image: what one dispatch covers, with accumulation
/// buffers of its own (GpuPush::band).
struct Band {
    std::uint32_t firstRow = 0, rows = 0;
};

/// The bands of a render on a device: the whole image as one band when every per-pixel buffer fits
/// one storage-buffer binding (maxStorageBufferRange) and one allocation (maxMemoryAllocationSize);
/// else bands of as many whole rows as fit, a multiple of 8 (adaptive sampling's tiles) and of the
/// workgroup's height, the last one shorter. Empty when not even that many rows fit (fitProblem
/// then refuses the render). Splitting changes no pixel's sums: each pixel's samples are the same.
std::vector<Band> planBands(const GpuArrays& arrays, const DeviceLimits& limits);

/// The largest absolute coordinate (world units, camera-relative) of the box of everything the
/// kernel can hit: the root node's child boxes. 0 for an empty BVH. Its rayOffsetScale
/// (shared/ray_offset.h) goes to the kernel in GpuFrame::origin.w.
float sceneExtent(const FlatBvh& bvh);

/// The motion of every primitive of bvh (GpuMotion, in the primitives' order): its shape's
/// Shape::velocity; 0 for instances and the triangles of instanced meshes.
std::vector<gpu::GpuMotion> packMotion(const Scene& scene, const FlatBvh& bvh);

/// Packs everything the kernel reads for `scene` (with the BVH built for it by buildSceneBvh) and
/// `options`. Throws std::invalid_argument when the BVH was not built with the scene's instances.
GpuArrays packGpuArrays(const Scene& scene, const FlatBvh& bvh, const RenderOptions& options);

/// Empty if the render fits the device, else the one line that refuses it, naming the scene, the
/// buffer (or the workgroup / dispatch size, the memory) and the limit, e.g. "scene.json: a
/// 600000x8 image needs 153600000 bytes for accumSum in a band of 8 rows (32 per pixel), more than
/// this device's maxStorageBufferRange = 134217728".
std::string fitProblem(const GpuArrays& arrays, const DeviceLimits& limits);

}  // namespace vkp
