// host/vk/spirv_specialize.cpp: specialization constants baked into SPIR-V on the host. A small
// hand-written module shows exactly what is baked, kept and removed; the path tracer's kernel,
// specialized for every shipped scene and for the full variant, stays valid SPIR-V (the SPIRV-Tools
// validator, Vulkan 1.2 rules) and shrinks. That the result renders what the driver's own
// specialization renders, bit for bit, is test_gpu_render's HostSpecializationRendersTheSameBits.
#include <gtest/gtest.h>

#include <bit>
#include <regex>
#include <string>

#include <spirv-tools/libspirv.hpp>

#include "bvh/two_level.h"
#include "pathtrace.spv.h"
#include "render/gpu_arrays.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "test_paths.h"
#include "vk/spirv_specialize.h"

namespace vkp {
namespace {

// A compute shader with a bool, a uint and a float specialization constant (ids 0-2), one without
// a value (id 7) and the workgroup size (id 19). The bool chooses between a call of a function and
// storing k + unset; f and the workgroup size's x are stored too.
const char* kModule = R"(
               OpCapability Shader
               OpMemoryModel Logical GLSL450
               OpEntryPoint GLCompute %main "main" %out
               OpExecutionMode %main LocalSize 1 1 1
               OpDecorate %wgx SpecId 19
               OpDecorate %wgs BuiltIn WorkgroupSize
               OpDecorate %useCall SpecId 0
               OpDecorate %k SpecId 1
               OpDecorate %f SpecId 2
               OpDecorate %unset SpecId 7
               OpDecorate %Buf Block
               OpMemberDecorate %Buf 0 Offset 0
               OpMemberDecorate %Buf 1 Offset 4
               OpMemberDecorate %Buf 2 Offset 8
               OpDecorate %out DescriptorSet 0
               OpDecorate %out Binding 0
       %void = OpTypeVoid
       %bool = OpTypeBool
       %uint = OpTypeInt 32 0
      %float = OpTypeFloat 32
     %v3uint = OpTypeVector %uint 3
         %fn = OpTypeFunction %void
     %fnUint = OpTypeFunction %uint
        %Buf = OpTypeStruct %uint %float %uint
    %ptrBuf = OpTypePointer StorageBuffer %Buf
   %ptrUint = OpTypePointer StorageBuffer %uint
  %ptrFloat = OpTypePointer StorageBuffer %float
        %out = OpVariable %ptrBuf StorageBuffer
         %u0 = OpConstant %uint 0
         %u1 = OpConstant %uint 1
         %u2 = OpConstant %uint 2
        %wgx = OpSpecConstant %uint 1
        %wgs = OpSpecConstantComposite %v3uint %wgx %u1 %u1
    %useCall = OpSpecConstantFalse %bool
          %k = OpSpecConstant %uint 5
          %f = OpSpecConstant %float 1.5
      %unset = OpSpecConstant %uint 9
     %kUnset = OpSpecConstantOp %uint IAdd %k %unset
       %main = OpFunction %void None %fn
      %entry = OpLabel
         %p0 = OpAccessChain %ptrUint %out %u0
               OpSelectionMerge %merge None
               OpBranchConditional %useCall %then %else
       %then = OpLabel
          %r = OpFunctionCall %uint %called
               OpStore %p0 %r
               OpBranch %merge
       %else = OpLabel
               OpStore %p0 %kUnset
               OpBranch %merge
      %merge = OpLabel
         %p1 = OpAccessChain %ptrFloat %out %u1
               OpStore %p1 %f
         %p2 = OpAccessChain %ptrUint %out %u2
       %size = OpCompositeExtract %uint %wgs 0
               OpStore %p2 %size
               OpReturn
               OpFunctionEnd
     %called = OpFunction %uint None %fnUint
          %l = OpLabel
               OpReturnValue %u1
               OpFunctionEnd
)";

std::vector<std::uint32_t> assemble(const char* text) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
    std::vector<std::uint32_t> words;
    EXPECT_TRUE(tools.Assemble(text, &words));
    return words;
}

std::string disassemble(const std::vector<std::uint32_t>& words) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
    std::string text;
    EXPECT_TRUE(tools.Disassemble(words, &text, SPV_BINARY_TO_TEXT_OPTION_NO_HEADER));
    return text;
}

/// Validator messages of `words` under Vulkan 1.2 rules ("" if valid).
std::string validate(const std::vector<std::uint32_t>& words) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
    std::string messages;
    tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { messages += std::string(m) + "\n"; });
    return tools.Validate(words) ? std::string() : messages + " ";
}

std::size_t count(const std::string& text, const std::string& pattern) {
    const std::regex re(pattern);
    return std::size_t(std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

/// kModule specialized with useCall (id 0), k = 7 (id 1) and f = 2.5 (id 2), checked valid; its
/// disassembly, and the result in `out`.
std::string specializedModule(bool useCall, SpirvSpecialization& out) {
    const std::vector<std::uint32_t> in = assemble(kModule);
    EXPECT_EQ(validate(in), "");
    EXPECT_EQ(count(disassemble(in), "= OpFunction "), 2u);
    const std::uint32_t values[] = {useCall ? 1u : 0u, 7u, std::bit_cast<std::uint32_t>(2.5f)};
    out = specializeSpirv(in, values);
    EXPECT_EQ(validate(out.words), "");
    return disassemble(out.words);
}

/// Expects each pattern to occur in `text` as often as given.
void expectCounts(const std::string& text, std::initializer_list<std::pair<const char*, std::size_t>> expected) {
    for (const auto& [pattern, n] : expected) EXPECT_EQ(count(text, pattern), n) << pattern << " in\n" << text;
}

TEST(SpirvSpecialize, BakesTheValuesAndRemovesWhatTheyMakeDead) {
    SpirvSpecialization s;
    expectCounts(specializedModule(false, s),
                 {// The bool was false: the branch with the call and the called function are gone.
                  {"OpFunctionCall", 0},
                  {"= OpFunction ", 1},
                  {"OpBranchConditional", 0},
                  // The float is the value given, bit for bit, as a plain constant.
                  {"OpConstant %[a-z0-9_]+ 2\\.5\\b", 1},
                  // Ids 0-2 are no longer specialization constants; 7 (no value) and 19 (workgroup size) are.
                  {"SpecId (0|1|2)\\b", 0},
                  {"SpecId 7\\b", 1},
                  {"SpecId 19\\b", 1},
                  {"OpSpecConstantComposite", 1},
                  // k + unset stays an expression of the unset constant, with k's value folded in.
                  {"OpConstant %[a-z0-9_]+ 7\\b", 1},
                  {"OpSpecConstantOp %[a-z0-9_]+ IAdd", 1}});
    EXPECT_EQ(s.keptIds, (std::vector<std::uint32_t>{7u, 19u}));
}

TEST(SpirvSpecialize, ATrueBoolKeepsItsBranch) {
    SpirvSpecialization s;
    // The call and its function stay; the else branch (k + unset) is gone.
    expectCounts(specializedModule(true, s), {{"OpFunctionCall", 1}, {"= OpFunction ", 2}, {"IAdd", 0}});
}

TEST(SpirvSpecialize, NoValuesBakeNothing) {
    const std::vector<std::uint32_t> in = assemble(kModule);
    const SpirvSpecialization s = specializeSpirv(in, {});
    EXPECT_EQ(validate(s.words), "");
    EXPECT_EQ(s.keptIds, (std::vector<std::uint32_t>{0u, 1u, 2u, 7u, 19u}));
    const std::string text = disassemble(s.words);
    EXPECT_EQ(count(text, "SpecId"), 5u) << text;
    EXPECT_EQ(count(text, "OpFunctionCall"), 1u) << text;
}

TEST(SpirvSpecialize, RefusesWhatIsNotSpirv) {
    const std::vector<std::uint32_t> notSpirv = {1u, 2u, 3u, 4u, 5u, 6u};
    EXPECT_THROW(specializeSpirv(notSpirv, {}), std::runtime_error);
    EXPECT_THROW(specializeSpirv(std::span<const std::uint32_t>(), {}), std::runtime_error);
    std::vector<std::uint32_t> truncated = assemble(kModule);
    truncated.resize(truncated.size() - 2);  // drops OpFunctionEnd and OpReturnValue's operand: it runs past the end
    try {
        specializeSpirv(truncated, {});
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bad instruction at word"), std::string::npos) << e.what();
    }
}

/// The path tracer's kernel specialized as a render of `scene` with `options` specializes it.
SpirvSpecialization specializedKernel(Scene scene, const RenderOptions& options) {
    scene.camera.width = scene.camera.height = 8;
    const FlatBvh bvh = buildSceneBvh(scene);
    const GpuArrays arrays = packGpuArrays(scene, bvh, options);
    const std::span<const std::uint32_t> kernel(kPathtraceSpv, sizeof(kPathtraceSpv) / sizeof(kPathtraceSpv[0]));
    return specializeSpirv(kernel, arrays.features.specConstants());
}

TEST(SpirvSpecialize, PathTracerStaysValidForEveryShippedSceneAndShrinks) {
    const std::size_t original = sizeof(kPathtraceSpv) / sizeof(kPathtraceSpv[0]);
    for (const char* file : {"cornell-classic.json", "cornell-book3.json", "cornell-lights.json", "spheres-book1.json", "env-sky.json",
                             "furnace.json", "lamps.json", "next-week/bouncing-spheres.json", "next-week/final-scene.json"}) {
        SCOPED_TRACE(file);
        const SpirvSpecialization s = specializedKernel(loadSceneJson(test::scenesDir() / file), {});
        EXPECT_EQ(validate(s.words), "");
        EXPECT_EQ(s.keptIds, (std::vector<std::uint32_t>{VKP_SPEC_WORKGROUP_X, VKP_SPEC_WORKGROUP_Y}));
        // Measured: 44-55% of the words for these scenes; a variant that keeps most of the kernel
        // would show here.
        EXPECT_LT(s.words.size(), original * 7 / 10) << s.words.size() << " of " << original << " words";
    }
    for (const char* file : {"gltf/emissive.glb", "gltf/textures.gltf", "gltf/materials.gltf", "gltf/layer-textures.gltf", "gltf/alpha.gltf",
                             "gltf/lights.gltf", "gltf/vertex-colors.gltf", "gltf/instances.gltf", "gltf/transmission-textures.gltf"}) {
        SCOPED_TRACE(file);
        const SpirvSpecialization s = specializedKernel(loadSceneGltf(test::scenesDir() / file), {});
        EXPECT_EQ(validate(s.words), "");
    }
    GltfOptions instancing;
    instancing.instancing = true;
    const Scene instanced = loadSceneGltf(test::scenesDir() / "gltf/instances.gltf", instancing);
    ASSERT_FALSE(instanced.instances.empty());
    EXPECT_EQ(validate(specializedKernel(instanced, {}).words), "");
    RenderOptions full;
    full.fullVariant = true;
    full.aov = true;
    const SpirvSpecialization s = specializedKernel(loadSceneJson(test::scenesDir() / "cornell-classic.json"), full);
    EXPECT_EQ(validate(s.words), "");
}

}  // namespace
}  // namespace vkp
