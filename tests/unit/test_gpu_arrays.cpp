// host/render/gpu_arrays.cpp, the one CPU-side packing step of a render: what every binding holds
// and how large it is, and the one check of a render against a device's limits (fitProblem), with
// the limits of lavapipe (Mesa 22.3) and smaller, made-up ones. No device needed.
#include <gtest/gtest.h>

#include <string>

#include "bvh/two_level.h"
#include "render/gpu_arrays.h"
#include "scene/gltf.h"
#include "shared/microfacet.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace vkp {
namespace {

/// lavapipe's limits (vulkaninfo, Mesa 22.3.6), with a host of 24 GiB.
DeviceLimits lavapipe() {
    DeviceLimits l;
    l.maxTexelBufferElements = 134217728;
    l.maxStorageBufferRange = 134217728;
    l.maxUniformBufferRange = 65536;
    l.maxMemoryAllocationSize = 0x80000000ull;
    l.deviceLocalBytes = 24ull << 30;
    l.hostMemoryBytes = 24ull << 30;
    l.maxComputeWorkGroupCount[0] = l.maxComputeWorkGroupCount[1] = 65535;
    l.maxComputeWorkGroupSize[0] = l.maxComputeWorkGroupSize[1] = 1024;
    l.maxComputeWorkGroupInvocations = 1024;
    l.maxPerStageDescriptorUniformBuffers = 15;
    l.maxPerStageDescriptorStorageBuffers = 32;
    l.maxPerStageDescriptorSampledImages = 128;
    l.maxPerStageResources = 128;
    l.subgroupSize = 8;
    return l;
}

struct Packed {
    Scene scene;
    FlatBvh bvh;
    GpuArrays arrays;
};

Packed pack(Scene scene, const RenderOptions& o = {}) {
    Packed p;
    p.scene = std::move(scene);
    p.bvh = buildSceneBvh(p.scene);
    p.arrays = packGpuArrays(p.scene, p.bvh, o);
    return p;
}

Scene sized(const char* file, std::uint32_t w, std::uint32_t h) {
    Scene s = loadSceneJson(test::scenesDir() / file);
    s.camera.width = w;
    s.camera.height = h;
    return s;
}

TEST(GpuArrays, EveryBindingHoldsItsArray) {
    const Packed p = pack(sized("cornell-book3.json", 40, 30));
    const GpuArrays& a = p.arrays;
    const std::vector<BufferSize> sizes = a.sizes();
    ASSERT_EQ(sizes.size(), std::size_t(VKP_BINDING_COUNT));
    for (std::uint32_t i = 0; i < sizes.size(); ++i) EXPECT_EQ(sizes[i].binding->binding, i);
    EXPECT_EQ(sizes[VKP_BINDING_NODES].bytes, a.nodes.size() * sizeof(gpu::GpuWideNode));
    EXPECT_EQ(sizes[VKP_BINDING_NODES].texels, a.nodes.size() * gpu::GPU_WIDE_NODE_TEXELS);
    EXPECT_EQ(sizes[VKP_BINDING_PRIMS].texels, p.bvh.prims.size() * gpu::GPU_PRIM_TEXELS);
    EXPECT_EQ(a.prims.size(), p.scene.shapes.size());
    EXPECT_EQ(sizes[VKP_BINDING_MATERIALS].texels, p.scene.materials.size() * gpu::GPU_MATERIAL_TEXELS);  // no glTF BRDF: no table
    EXPECT_EQ(sizes[VKP_BINDING_LIGHTS].texels, p.scene.lights.size());
    EXPECT_EQ(sizes[VKP_BINDING_FRAME].bytes, sizeof(gpu::GpuFrame));
    EXPECT_EQ(sizes[VKP_BINDING_ENV_DIST].texels, a.envDistribution.size());  // R32F: 4 bytes a texel
    EXPECT_EQ(sizes[VKP_BINDING_TEXELS].texels, a.texels.size());            // R32UI
    // The per-pixel buffers: two vec4 per pixel each; adaptive sampling's are tokens when it is off.
    EXPECT_EQ(sizes[VKP_BINDING_ACCUM_SUM].bytes, 40u * 30u * 32u);
    EXPECT_EQ(sizes[VKP_BINDING_ACCUM_SQ].bytes, 40u * 30u * 32u);
    EXPECT_EQ(sizes[VKP_BINDING_DECISION].bytes, 16u);
    EXPECT_EQ(sizes[VKP_BINDING_ACTIVE].bytes, 16u);
    EXPECT_TRUE(a.hostData(VKP_BINDING_ACCUM_SUM).empty());
    std::uint64_t scene = 0, pixel = 0;
    for (const BufferSize& s : sizes) (s.binding->kind == BindingKind::StorageBuffer ? pixel : scene) += s.bytes;
    EXPECT_EQ(a.sceneBytes(), scene);
    EXPECT_EQ(a.pixelBytes(), pixel);
    EXPECT_EQ(a.frame.size.x, 40u);
    EXPECT_EQ(a.frame.counts.x, p.scene.lights.size());
    EXPECT_EQ(a.frame.counts.w, p.scene.materials.size() * gpu::GPU_MATERIAL_TEXELS);  // where the GGX table would start
    EXPECT_EQ(fitProblem(a, lavapipe()), "");
}

TEST(GpuArrays, AdaptiveSamplingListsEveryPixelFirst) {
    RenderOptions o;
    o.adaptiveThreshold = 0.05;
    const Packed p = pack(sized("cornell-classic.json", 20, 10), o);
    ASSERT_EQ(p.arrays.activePixels.size(), 200u);
    EXPECT_EQ(p.arrays.sizes()[VKP_BINDING_ACTIVE].bytes, 200u * 4u);
    EXPECT_EQ(p.arrays.sizes()[VKP_BINDING_DECISION].bytes, 200u * 32u);
    EXPECT_EQ(p.arrays.hostData(VKP_BINDING_ACTIVE).size(), 200u * 4u);
}

TEST(GpuArrays, GltfBrdfVariantsCarryTheAlbedoTable) {
    Scene scene = loadSceneGltf(test::scenesDir() / "gltf" / "materials.gltf");
    const Packed p = pack(std::move(scene));
    ASSERT_TRUE(p.arrays.features.hasMaterial(gpu::MAT_PBR));
    EXPECT_EQ(p.arrays.frame.counts.w, p.scene.materials.size() * gpu::GPU_MATERIAL_TEXELS);
    EXPECT_EQ(p.arrays.materials.size(), p.arrays.frame.counts.w + gpu::GGX_ALBEDO_N * gpu::GGX_ALBEDO_N);
}

// The refusals, one line each, naming the scene, the buffer and the limit.
void expectOneLine(const std::string& m) {
    EXPECT_FALSE(m.empty());
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(GpuArrays, AnImageBeyondOneStorageBindingIsSplitIntoBands) {
    // lavapipe: 128 MiB per storage binding = 4,194,304 pixels of 32 bytes, 2048 x 2048 exactly.
    const std::vector<Band> one = planBands(pack(sized("cornell-classic.json", 2048, 2048)).arrays, lavapipe());
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].rows, 2048u);
    // One column more: 2047 rows of 2049 pixels fit, so bands of 2040 rows (a multiple of 8).
    const Packed wide = pack(sized("cornell-classic.json", 2049, 2048));
    const std::vector<Band> two = planBands(wide.arrays, lavapipe());
    ASSERT_EQ(two.size(), 2u);
    EXPECT_EQ(two[0].firstRow, 0u);
    EXPECT_EQ(two[0].rows, 2040u);
    EXPECT_EQ(two[1].firstRow, 2040u);
    EXPECT_EQ(two[1].rows, 8u);
    EXPECT_EQ(fitProblem(wide.arrays, lavapipe()), "");
    // The allocation limit splits too; rows come in multiples of lcm(8, the workgroup's height).
    RenderOptions o;
    o.workgroupX = 3;
    o.workgroupY = 5;
    DeviceLimits l = lavapipe();
    l.maxMemoryAllocationSize = 79 * 64 * 32;  // 79 rows of 64 pixels: bands of 40
    const std::vector<Band> bands = planBands(pack(sized("cornell-classic.json", 64, 170), o).arrays, l);
    ASSERT_EQ(bands.size(), 5u);
    for (std::size_t i = 0; i < bands.size(); ++i) {
        EXPECT_EQ(bands[i].firstRow, 40u * i);
        EXPECT_EQ(bands[i].rows, i < 4 ? 40u : 10u);
    }
    // The automatic workgroup is the device's: subgroups of 128 lanes give 8x16, so bands of 64 rows
    // (79 fit; multiples of lcm(8, 16)).
    l.subgroupSize = 128;
    const std::vector<Band> tall = planBands(pack(sized("cornell-classic.json", 64, 170)).arrays, l);
    ASSERT_EQ(tall.size(), 3u);
    EXPECT_EQ(tall[0].rows, 64u);
    EXPECT_EQ(tall[2].firstRow, 128u);
    EXPECT_EQ(tall[2].rows, 42u);
    // Adaptive sampling's buffers split with the others.
    o = RenderOptions{};
    o.adaptiveThreshold = 0.05;
    l = lavapipe();
    l.maxStorageBufferRange = 16 * 64 * 32;
    EXPECT_EQ(planBands(pack(sized("cornell-classic.json", 64, 64), o).arrays, l).size(), 4u);
}

TEST(GpuArrays, AnImageWhoseRowsDoNotFitOneBindingIsRefused) {
    DeviceLimits l = lavapipe();
    l.maxStorageBufferRange = 8 * 256 * 32 - 1;  // less than one band of 8 rows of 256 pixels
    const Packed p = pack(sized("cornell-classic.json", 256, 64));
    EXPECT_TRUE(planBands(p.arrays, l).empty());
    const std::string m = fitProblem(p.arrays, l);
    expectOneLine(m);
    EXPECT_NE(m.find("cornell-classic.json: a 256x64 image needs 65536 bytes for accumSum in a band of 8 rows (32 per "
                     "pixel), more than this device's maxStorageBufferRange = 65535"),
              std::string::npos)
        << m;
    l = lavapipe();
    l.maxMemoryAllocationSize = 1000;
    const std::string a = fitProblem(p.arrays, l);
    EXPECT_NE(a.find("maxMemoryAllocationSize = 1000"), std::string::npos) << a;
}

TEST(GpuArrays, DispatchesBeyondTheWorkgroupCountAreRefused) {
    DeviceLimits l = lavapipe();
    l.maxComputeWorkGroupCount[1] = 100;  // 100 rows of 8x8 workgroups: 800 pixels high
    EXPECT_EQ(fitProblem(pack(sized("cornell-classic.json", 64, 800)).arrays, l), "");
    const std::string m = fitProblem(pack(sized("cornell-classic.json", 64, 801)).arrays, l);
    expectOneLine(m);
    EXPECT_NE(m.find("8x101 workgroups, more than this device's maxComputeWorkGroupCount 65535x100"), std::string::npos) << m;
    // The automatic workgroup is the device's: 8x16 for subgroups of 128 lanes, so 1600 rows fit.
    l.subgroupSize = 128;
    EXPECT_EQ(fitProblem(pack(sized("cornell-classic.json", 64, 1600)).arrays, l), "");
    const std::string tall = fitProblem(pack(sized("cornell-classic.json", 64, 1601)).arrays, l);
    EXPECT_NE(tall.find("with workgroup 8x16 needs 8x101 workgroups"), std::string::npos) << tall;
}

TEST(GpuArrays, AWorkgroupBeyondTheDeviceIsRefused) {
    RenderOptions o;
    o.workgroupX = 64;
    o.workgroupY = 32;
    const std::string m = fitProblem(pack(sized("cornell-classic.json", 16, 16), o).arrays, lavapipe());
    expectOneLine(m);
    EXPECT_NE(m.find("workgroup 64x32 is beyond this device's limits"), std::string::npos) << m;
}

// The kernel's descriptors by kind against what one stage of the device may use. Every kind but
// storage buffers is within what Vulkan guarantees every device (12 uniform buffers, 16 sampled
// images, which uniform texel buffers count against, 128 resources); the 6 storage buffers are
// above the guaranteed 4, so a device that offers fewer is refused in one line before anything runs.
TEST(GpuArrays, DescriptorsBeyondTheStageLimitsAreRefused) {
    EXPECT_LE(kernelBindingCount(BindingKind::UniformBuffer), 12u);
    EXPECT_LE(kernelBindingCount(BindingKind::UniformTexelBuffer), 16u);
    EXPECT_LE(std::size(kKernelBindings), 128u);
    EXPECT_EQ(kernelBindingCount(BindingKind::StorageBuffer), 6u);
    const GpuArrays a = pack(sized("cornell-classic.json", 16, 16)).arrays;
    EXPECT_EQ(fitProblem(a, lavapipe()), "");
    DeviceLimits l = lavapipe();
    l.maxPerStageDescriptorStorageBuffers = 4;
    std::string m = fitProblem(a, l);
    expectOneLine(m);
    EXPECT_NE(m.find("binds 6 storage buffers, more than this device's maxPerStageDescriptorStorageBuffers = 4"), std::string::npos)
        << m;
    l = lavapipe();
    l.maxPerStageDescriptorSampledImages = 8;
    m = fitProblem(a, l);
    EXPECT_NE(m.find("11 uniform texel buffers, more than this device's maxPerStageDescriptorSampledImages = 8"),
              std::string::npos)
        << m;
    l = lavapipe();
    l.maxPerStageResources = 17;
    EXPECT_NE(fitProblem(a, l).find("binds 18 descriptors in all"), std::string::npos);
    l = lavapipe();
    l.maxPerStageDescriptorStorageBuffers = 0;  // not reported: not checked
    EXPECT_EQ(fitProblem(a, l), "");
}

TEST(GpuArrays, TexelsBeyondTheLimitAreRefusedNamingWhat) {
    Scene scene = loadSceneGltf(test::scenesDir() / "gltf" / "textures.gltf");
    const Packed p = pack(std::move(scene));
    DeviceLimits l = lavapipe();
    l.maxTexelBufferElements = 20;
    const std::string m = fitProblem(p.arrays, l);
    expectOneLine(m);
    EXPECT_NE(m.find("textures.gltf: textures: 3 images need 21 texels, the largest \"image 0\" 4x4, more than this "
                     "device's maxTexelBufferElements = 20"),
              std::string::npos)
        << m;
    // Textures that fit with more vertex-attribute records than fit (as a scene of ~600 mesh
    // triangles would have).
    GpuArrays many = p.arrays;
    many.attributes.resize(5000);
    l.maxTexelBufferElements = 4096;
    const std::string a = fitProblem(many, l);
    EXPECT_NE(a.find("textures.gltf: the vertex attributes (UVs, normals, tangents) of the scene's primitives need 5000 "
                     "texels, more than this device's maxTexelBufferElements = 4096"),
              std::string::npos)
        << a;
}

TEST(GpuArrays, AnEnvironmentMapBeyondTheLimitIsRefused) {
    const Packed p = pack(sized("env-sky.json", 16, 16));
    ASSERT_GT(p.arrays.envWidth, 0u);
    DeviceLimits l = lavapipe();
    l.maxTexelBufferElements = p.arrays.envTexels.size() - 1;
    const std::string m = fitProblem(p.arrays, l);
    expectOneLine(m);
    EXPECT_NE(m.find("env-sky.json: the environment map " + std::to_string(p.arrays.envWidth) + "x" +
                     std::to_string(p.arrays.envHeight)),
              std::string::npos)
        << m;
}

TEST(GpuArrays, MemoryBeyondTheDeviceOrTheHostIsRefused) {
    const Packed p = pack(sized("cornell-classic.json", 512, 512));
    DeviceLimits l = lavapipe();
    l.deviceLocalBytes = p.arrays.sceneBytes() + p.arrays.pixelBytes() - 1;
    std::string m = fitProblem(p.arrays, l);
    expectOneLine(m);
    EXPECT_NE(m.find("bytes of device memory"), std::string::npos) << m;
    l = lavapipe();
    l.hostMemoryBytes = 2 * 512 * 512 * kHostBytesPerPixel - 1;  // the read-back may take half of it
    m = fitProblem(p.arrays, l);
    EXPECT_NE(m.find("bytes of host memory to read back"), std::string::npos) << m;
    l.hostMemoryBytes += 1;
    EXPECT_EQ(fitProblem(p.arrays, l), "");
}

}  // namespace
}  // namespace vkp
