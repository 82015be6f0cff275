#include "render/gpu_arrays.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <stdexcept>

#include "bvh/wide_pack.h"
#include "render/adaptive.h"
#include "render/environment.h"
#include "render/ggx_albedo_table.h"
#include "render/workgroup.h"
#include "render/sheen_albedo_table.h"
#include "render/gpu_scene.h"
#include "render/light_table.h"
#include "render/texture_pack.h"
#include "shared/ray_offset.h"
#include "vk/device_select.h"

namespace vkp {

namespace {
template <class T>
std::span<const std::byte> bytesOf(const std::vector<T>& v) {
    return std::as_bytes(std::span<const T>(v.data(), v.size()));
}

std::string size(std::uint32_t w, std::uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }
}  // namespace

DeviceLimits deviceLimits(const DeviceInfo& d) {
    DeviceLimits l;
    l.maxTexelBufferElements = d.maxTexelBufferElements;
    l.maxStorageBufferRange = d.maxStorageBufferRange;
    l.maxUniformBufferRange = d.maxUniformBufferRange;
    l.maxMemoryAllocationSize = d.maxMemoryAllocationSize;
    l.deviceLocalBytes = d.deviceLocalBytes;
    l.hostMemoryBytes = hostPhysicalMemory();
    for (int i = 0; i < 2; ++i) {
        l.maxComputeWorkGroupCount[i] = d.maxComputeWorkGroupCount[i];
        l.maxComputeWorkGroupSize[i] = d.maxComputeWorkGroupSize[i];
    }
    l.maxComputeWorkGroupInvocations = d.maxComputeWorkGroupInvocations;
    l.maxPerStageDescriptorUniformBuffers = d.maxPerStageDescriptorUniformBuffers;
    l.maxPerStageDescriptorStorageBuffers = d.maxPerStageDescriptorStorageBuffers;
    l.maxPerStageDescriptorSampledImages = d.maxPerStageDescriptorSampledImages;
    l.maxPerStageResources = d.maxPerStageResources;
    l.subgroupSize = d.subgroupSize;
    return l;
}

std::uint64_t hostPhysicalMemory() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
}

float sceneExtent(const FlatBvh& bvh) {
    // The root's two child boxes bound everything the kernel can hit (instances placed in the
    // world included); an empty child's inverted box is skipped.
    float extent = 0.0f;
    if (bvh.nodes.empty()) return extent;
    const gpu::GpuNode& root = bvh.nodes[0];
    for (const auto& [lo, hi] : {std::pair(root.a, root.b), std::pair(root.c, root.d)}) {
        if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) continue;
        for (int i = 0; i < 3; ++i) extent = std::max({extent, std::abs(lo[i]), std::abs(hi[i])});
    }
    return extent;
}

std::vector<gpu::GpuMotion> packMotion(const Scene& scene, const FlatBvh& bvh) {
    std::vector<gpu::GpuMotion> out(bvh.prims.size(), gpu::GpuMotion{});
    for (std::size_t i = 0; i < out.size(); ++i)
        if (const Shape* s = primShape(scene, bvh, i)) out[i].v = glm::vec4(s->velocity, 0.0f);
    return out;
}

GpuArrays packGpuArrays(const Scene& scene, const FlatBvh& bvh, const RenderOptions& options) {
    if (bvh.instances.size() != scene.instances.size())
        throw std::invalid_argument("packGpuArrays: the BVH was not built with the scene's instances (use buildSceneBvh)");
    GpuArrays a;
    a.sceneName = scene.path.string();
    a.features = sceneFeatures(scene, options);
    a.width = scene.camera.width;
    a.height = scene.camera.height;
    a.adaptive = options.adaptive();
    a.aovFrame.worldOrigin = scene.origin;
    a.aovFrame.eye = scene.camera.lookfrom;
    a.aovFrame.viewAxis = glm::normalize(scene.camera.lookat - scene.camera.lookfrom);
    // The kernel traverses the 4-wide layout: FlatBvh::wideNodes, or collapsed here for a FlatBvh
    // that came from flattenBvh alone.
    a.nodes = bvh.wideNodes.empty() ? buildWideNodes(bvh) : bvh.wideNodes;
    a.prims = bvh.prims;
    a.frame = packFrame(scene, options.lightPick);
    a.frame.origin.w = gpu::rayOffsetScale(sceneExtent(bvh));
    // Material texels, then (for glTF BRDF variants) the GGX albedo table at texel counts.w.
    for (const gpu::GpuMaterial& m : packMaterials(scene.materials))
        for (const glm::vec4& t : {m.m0, m.m1, m.m2, m.m3, m.m4, m.m5}) a.materials.push_back(t);
    static_assert(gpu::GPU_MATERIAL_TEXELS == 6, "one push_back per GpuMaterial member");
    a.frame.counts.w = std::uint32_t(a.materials.size());
    if (a.features.hasMaterial(gpu::MAT_PBR)) {
        const std::vector<glm::vec4>& table = ggxAlbedoTable();
        a.materials.insert(a.materials.end(), table.begin(), table.end());
        if (a.features.layers & gpu::LAYER_SHEEN) {  // the sheen albedo table right after it (lib/bindings.glsl)
            const std::vector<glm::vec4>& sheen = sheenAlbedoTable();
            a.materials.insert(a.materials.end(), sheen.begin(), sheen.end());
        }
    }
    // Then the media (shared/medium.h), at texel media.y.
    a.frame.media = glm::uvec4(std::uint32_t(scene.media.size()), std::uint32_t(a.materials.size()), 0, 0);
    for (const gpu::GpuMedium& m : packMedia(scene.media))
        for (const glm::vec4& t : {m.r0, m.r1, m.r2, m.params}) a.materials.push_back(t);
    static_assert(gpu::GPU_MEDIUM_TEXELS == 4, "one push_back per GpuMedium member");
    if (a.materials.empty()) a.materials.assign(1, glm::vec4(0.0f));
    std::vector<std::uint32_t> primOfShape(scene.shapes.size(), 0);
    for (std::uint32_t i = 0; i < bvh.primToShape.size(); ++i) {
        const bool topShape = (bvh.primMesh.empty() || bvh.primMesh[i] == 0) && bvh.primToShape[i] != FlatBvh::kNotAShape;
        if (topShape) primOfShape[bvh.primToShape[i]] = i;
    }
    a.lights = packLights(scene, primOfShape, options.lightPick);
    if (a.lights.empty()) a.lights.assign(1, gpu::GpuLight{});
    EnvTables env = packEnvironment(scene);
    a.envTexels = std::move(env.texels);
    a.envDistribution = std::move(env.distribution);
    // Textures and vertex attributes (lib/surface.glsl): only what the variant reads is packed in
    // full; the others get a token texel.
    if (a.features.textures || a.features.alpha || a.features.solidTextures) {
        TexturePack tex = packTextures(scene, a.features.textures || a.features.alpha);
        a.texInfo = std::move(tex.info);
        a.texels = std::move(tex.texels);
    }
    if (a.texInfo.empty()) a.texInfo.assign(1, glm::uvec4(0));
    if (a.texels.empty()) a.texels.assign(1, 0u);
    a.attributes = a.features.vertexAttributes ? packVertexAttributes(scene, bvh) : std::vector<glm::uvec4>(1, glm::uvec4(0));
    a.instances = bvh.instances;  // two-level BVH; a token record when there are none (HAS_INSTANCES is then false)
    if (a.instances.empty()) a.instances.resize(1, gpu::GpuInstance{});
    // Motion blur: every primitive's displacement, read by variants with HAS_MOTION only.
    if (a.features.motion) a.motion = packMotion(scene, bvh);
    if (a.motion.empty()) a.motion.resize(1, gpu::GpuMotion{});
    if (a.adaptive) a.activePixels = activePixelList(std::vector<std::uint8_t>(a.pixels(), 1), a.width, a.height);
    a.imageCount = scene.images.size();
    std::size_t big = 0;
    for (std::size_t i = 1; i < scene.images.size(); ++i)
        if (std::uint64_t(scene.images[i].width) * scene.images[i].height >
            std::uint64_t(scene.images[big].width) * scene.images[big].height)
            big = i;
    if (!scene.images.empty())
        a.largestImage = "\"" + scene.images[big].name + "\" " + size(scene.images[big].width, scene.images[big].height);
    a.envWidth = scene.environment.image.width;
    a.envHeight = scene.environment.image.height;
    return a;
}

std::span<const std::byte> GpuArrays::hostData(std::uint32_t binding) const {
    switch (binding) {
        case VKP_BINDING_FRAME: return std::as_bytes(std::span<const gpu::GpuFrame>(&frame, 1));
        case VKP_BINDING_NODES: return bytesOf(nodes);
        case VKP_BINDING_PRIMS: return bytesOf(prims);
        case VKP_BINDING_MATERIALS: return bytesOf(materials);
        case VKP_BINDING_LIGHTS: return bytesOf(lights);
        case VKP_BINDING_ENV_TEXELS: return bytesOf(envTexels);
        case VKP_BINDING_ENV_DIST: return bytesOf(envDistribution);
        case VKP_BINDING_ATTRIBUTES: return bytesOf(attributes);
        case VKP_BINDING_TEX_INFO: return bytesOf(texInfo);
        case VKP_BINDING_TEXELS: return bytesOf(texels);
        case VKP_BINDING_INSTANCES: return bytesOf(instances);
        case VKP_BINDING_MOTION: return bytesOf(motion);
        case VKP_BINDING_ACTIVE: return bytesOf(activePixels);
        default: return {};  // written by the kernel: zeroed before the first dispatch
    }
}

std::uint64_t GpuArrays::bytesPerPixel(std::uint32_t binding) const {
    switch (binding) {
        case VKP_BINDING_ACCUM_SUM:
        case VKP_BINDING_ACCUM_SQ: return kAccumBytesPerPixel;
        case VKP_BINDING_DECISION: return adaptive ? kAccumBytesPerPixel : 0;
        case VKP_BINDING_ACTIVE: return adaptive ? 4 : 0;
        case VKP_BINDING_AOV: return features.aov ? kAovBytesPerPixel : 0;
        default: return 0;
    }
}

std::vector<BufferSize> GpuArrays::sizes() const {
    std::vector<BufferSize> out;
    for (const KernelBinding& b : kKernelBindings) {
        BufferSize s{&b};
        if (isPerPixelBinding(b.binding)) s.bytes = std::max<std::uint64_t>(pixels() * bytesPerPixel(b.binding), 16);  // a token when unused
        else if (b.binding == VKP_BINDING_COUNTERS) s.bytes = gpu::COUNTER_COUNT * 4;
        else s.bytes = hostData(b.binding).size();
        if (b.format != TexelFormat::None) s.texels = s.bytes / texelBytes(b.format);
        out.push_back(s);
    }
    return out;
}

namespace {
std::uint64_t gcd(std::uint64_t a, std::uint64_t b) { return b ? gcd(b, a % b) : a; }

/// Bytes one band may give a per-pixel buffer on the device.
std::uint64_t bandBytesLimit(const DeviceLimits& l) {
    return l.maxMemoryAllocationSize ? std::min(l.maxStorageBufferRange, l.maxMemoryAllocationSize) : l.maxStorageBufferRange;
}

/// Bytes of a row of the widest per-pixel buffer.
std::uint64_t widestRowBytes(const GpuArrays& a) {
    std::uint64_t perPixel = 0;
    for (const KernelBinding& b : kKernelBindings)
        if (isPerPixelBinding(b.binding)) perPixel = std::max(perPixel, a.bytesPerPixel(b.binding));
    return perPixel * a.width;
}

/// Rows a band is a multiple of: adaptive sampling's 8-row tiles and the workgroup's height.
std::uint32_t bandRowUnit(const GpuArrays& a, const DeviceLimits& l) {
    const std::uint64_t h = std::max<std::uint32_t>(kernelWorkgroup(a.features, l).y, 1);
    return std::uint32_t(8 / gcd(8, h) * h);
}
}  // namespace

std::vector<Band> planBands(const GpuArrays& a, const DeviceLimits& l) {
    const std::uint64_t rowBytes = widestRowBytes(a), limit = bandBytesLimit(l);
    if (rowBytes == 0 || std::uint64_t(a.height) * rowBytes <= limit) return {Band{0, a.height}};
    const std::uint32_t unit = bandRowUnit(a, l);
    const std::uint64_t rows = limit / rowBytes / unit * unit;
    if (rows == 0) return {};
    std::vector<Band> bands;
    for (std::uint32_t first = 0; first < a.height; first += std::uint32_t(rows))
        bands.push_back(Band{first, std::uint32_t(std::min<std::uint64_t>(rows, a.height - first))});
    return bands;
}

std::uint64_t GpuArrays::sceneBytes() const {
    std::uint64_t n = 0;
    for (const BufferSize& s : sizes())
        if (s.binding->kind != BindingKind::StorageBuffer) n += s.bytes;
    return n;
}

std::uint64_t GpuArrays::pixelBytes() const {
    std::uint64_t n = 0;
    for (const BufferSize& s : sizes())
        if (s.binding->kind == BindingKind::StorageBuffer) n += s.bytes;
    return n;
}

std::string fitProblem(const GpuArrays& a, const DeviceLimits& l) {
    const std::string file = a.sceneName + ": ";
    // The workgroup: every invocation of the kernel's own size (`--workgroup`, else autoWorkgroup's).
    const glm::uvec2 wg = kernelWorkgroup(a.features, l);
    if (wg.x == 0 || wg.y == 0 || wg.x > l.maxComputeWorkGroupSize[0] || wg.y > l.maxComputeWorkGroupSize[1] ||
        std::uint64_t(wg.x) * wg.y > l.maxComputeWorkGroupInvocations)
        return "workgroup " + size(wg.x, wg.y) + " is beyond this device's limits (maxComputeWorkGroupSize " +
               size(l.maxComputeWorkGroupSize[0], l.maxComputeWorkGroupSize[1]) + ", maxComputeWorkGroupInvocations " +
               std::to_string(l.maxComputeWorkGroupInvocations) + ")";
    // The kernel's descriptors, by kind, within what one compute stage may use (a limit of 0 was not
    // reported and is not checked). Uniform texel buffers count against the sampled-image limit.
    const struct {
        std::uint32_t need, limit;
        const char* what;
        const char* name;
    } descriptors[] = {
        {kernelBindingCount(BindingKind::UniformBuffer), l.maxPerStageDescriptorUniformBuffers, "uniform buffers",
         "maxPerStageDescriptorUniformBuffers"},
        {kernelBindingCount(BindingKind::StorageBuffer), l.maxPerStageDescriptorStorageBuffers, "storage buffers",
         "maxPerStageDescriptorStorageBuffers"},
        {kernelBindingCount(BindingKind::UniformTexelBuffer), l.maxPerStageDescriptorSampledImages, "uniform texel buffers",
         "maxPerStageDescriptorSampledImages"},
        {std::uint32_t(std::size(kKernelBindings)), l.maxPerStageResources, "descriptors in all", "maxPerStageResources"},
    };
    for (const auto& d : descriptors)
        if (d.limit && d.need > d.limit)
            return "the path-tracing kernel binds " + std::to_string(d.need) + " " + d.what + ", more than this device's " +
                   d.name + " = " + std::to_string(d.limit);
    // Read-only scene data: each texel buffer within maxTexelBufferElements, with the messages that
    // say which part of the scene is too large.
    const std::uint64_t texelLimit = l.maxTexelBufferElements;
    const std::string texelTail = ", more than this device's maxTexelBufferElements = " + std::to_string(texelLimit);
    if (a.texels.size() > texelLimit || a.texInfo.size() > texelLimit)
        return file + "textures: " + std::to_string(a.imageCount) + " images need " + std::to_string(a.texels.size()) +
               " texels" + (a.largestImage.empty() ? "" : ", the largest " + a.largestImage) + texelTail;
    if (a.attributes.size() > texelLimit)
        return file + "the vertex attributes (UVs, normals, tangents) of the scene's primitives need " +
               std::to_string(a.attributes.size()) + " texels" + texelTail;
    if (a.envTexels.size() > texelLimit || a.envDistribution.size() > texelLimit)
        return file + "the environment map " + size(a.envWidth, a.envHeight) + " needs " +
               std::to_string(std::max(a.envTexels.size(), a.envDistribution.size())) + " texels" + texelTail;
    if (a.prims.size() * gpu::GPU_PRIM_TEXELS > texelLimit || a.nodes.size() * gpu::GPU_WIDE_NODE_TEXELS > texelLimit)
        return file + std::to_string(a.prims.size()) + " primitives need " +
               std::to_string(std::max(a.prims.size() * gpu::GPU_PRIM_TEXELS, a.nodes.size() * gpu::GPU_WIDE_NODE_TEXELS)) +
               " texels of BVH data" + texelTail;
    for (const BufferSize& s : a.sizes()) {
        if (s.texels > texelLimit)
            return file + "the scene needs " + std::to_string(s.texels) + " texels for " + s.binding->name + texelTail;
        if (s.binding->kind == BindingKind::UniformBuffer && s.bytes > l.maxUniformBufferRange)
            return file + s.binding->name + " needs " + std::to_string(s.bytes) +
                   " bytes, more than this device's maxUniformBufferRange = " + std::to_string(l.maxUniformBufferRange);
    }
    // The per-pixel buffers the kernel writes, in bands of rows that fit (planBands), and the
    // dispatch that covers the image.
    const std::string image = file + "a " + size(a.width, a.height) + " image";
    if (planBands(a, l).empty()) {
        const std::uint32_t rows = std::min(a.height, bandRowUnit(a, l));
        for (const BufferSize& s : a.sizes()) {
            const std::uint64_t perPixel = a.bytesPerPixel(s.binding->binding);
            const std::uint64_t bytes = perPixel * a.width * rows;
            auto refuse = [&](const char* limit, std::uint64_t value) {
                return image + " needs " + std::to_string(bytes) + " bytes for " + s.binding->name + " in a band of " +
                       std::to_string(rows) + " rows (" + std::to_string(perPixel) + " per pixel), more than this device's " +
                       limit + " = " + std::to_string(value);
            };
            if (bytes > l.maxStorageBufferRange) return refuse("maxStorageBufferRange", l.maxStorageBufferRange);
            if (l.maxMemoryAllocationSize && bytes > l.maxMemoryAllocationSize)
                return refuse("maxMemoryAllocationSize", l.maxMemoryAllocationSize);
        }
    }
    // The dispatch of the tallest band (the first).
    const std::vector<Band> bands = planBands(a, l);
    const std::uint64_t bandRows = bands.empty() ? a.height : bands.front().rows;
    const std::uint64_t groupsX = (a.width + wg.x - 1) / wg.x, groupsY = (bandRows + wg.y - 1) / wg.y;
    const std::uint64_t adaptiveRows = (groupsX * groupsY + kAdaptiveGroupsPerRow - 1) / kAdaptiveGroupsPerRow;
    if (groupsX > l.maxComputeWorkGroupCount[0] || groupsY > l.maxComputeWorkGroupCount[1] ||
        (a.adaptive && (kAdaptiveGroupsPerRow > l.maxComputeWorkGroupCount[0] || adaptiveRows > l.maxComputeWorkGroupCount[1])))
        return image + " with workgroup " + size(wg.x, wg.y) + " needs " +
               size(std::uint32_t(groupsX), std::uint32_t(groupsY)) + " workgroups, more than this device's maxComputeWorkGroupCount " +
               size(l.maxComputeWorkGroupCount[0], l.maxComputeWorkGroupCount[1]);
    // Memory: the device's largest heap, and the host's (read-back sums and the image).
    const std::uint64_t deviceBytes = a.sceneBytes() + a.pixelBytes();
    if (l.deviceLocalBytes && deviceBytes > l.deviceLocalBytes)
        return file + "the render needs " + std::to_string(deviceBytes) + " bytes of device memory, more than this device's " +
               std::to_string(l.deviceLocalBytes) + " (its largest device-local heap)";
    const std::uint64_t hostBytes = a.pixels() * kHostBytesPerPixel;
    if (l.hostMemoryBytes && hostBytes > l.hostMemoryBytes / 2)
        return image + " needs " + std::to_string(hostBytes) + " bytes of host memory to read back (" +
               std::to_string(kHostBytesPerPixel) + " per pixel), more than half of this machine's " +
               std::to_string(l.hostMemoryBytes);
    return {};
}

}  // namespace vkp
