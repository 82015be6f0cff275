// The kernel's workgroup size: chosen from the device's subgroup size unless `--workgroup` set it
// (render/workgroup.h).
#include <gtest/gtest.h>

#include "render/features.h"
#include "render/gpu_arrays.h"
#include "render/workgroup.h"

namespace vkp {
namespace {

DeviceLimits limits(std::uint32_t subgroupSize, std::uint32_t maxX, std::uint32_t maxY, std::uint32_t maxInvocations) {
    DeviceLimits l;
    l.subgroupSize = subgroupSize;
    l.maxComputeWorkGroupSize[0] = maxX;
    l.maxComputeWorkGroupSize[1] = maxY;
    l.maxComputeWorkGroupInvocations = maxInvocations;
    return l;
}

TEST(Workgroup, AtLeast64InvocationsAndWholeSubgroupsEightPixelsWide) {
    // lavapipe (4 or 8 lanes, by the CPU's vector width), Intel (8-32), NVIDIA (32), AMD (32, 64),
    // Adreno (64, 128); 0 and non-powers of two are "not reported".
    const struct {
        std::uint32_t subgroup;
        glm::uvec2 expected;
    } cases[] = {{0, {8, 8}}, {1, {8, 8}}, {4, {8, 8}}, {8, {8, 8}}, {16, {8, 8}}, {32, {8, 8}},
                 {64, {8, 8}}, {128, {8, 16}}, {48, {8, 8}}, {4096, {8, 128}}};
    for (const auto& c : cases) {
        const glm::uvec2 wg = autoWorkgroup(limits(c.subgroup, 1024, 1024, 1024));
        EXPECT_EQ(wg, c.expected) << "subgroup " << c.subgroup;
        const std::uint32_t n = wg.x * wg.y;
        EXPECT_GE(n, 64u);
        if (c.subgroup != 0 && (c.subgroup & (c.subgroup - 1)) == 0 && c.subgroup <= 1024) EXPECT_EQ(n % c.subgroup, 0u);
    }
}

TEST(Workgroup, ShrinksToTheDevicesLimits) {
    // Vulkan's minimums are 128x128 and 128 invocations: 8x8 always fits them.
    EXPECT_EQ(autoWorkgroup(limits(8, 128, 128, 128)), glm::uvec2(8, 8));
    EXPECT_EQ(autoWorkgroup(limits(128, 128, 128, 128)), glm::uvec2(8, 16));
    EXPECT_EQ(autoWorkgroup(limits(128, 128, 128, 64)), glm::uvec2(8, 8));   // invocations: height first
    EXPECT_EQ(autoWorkgroup(limits(128, 128, 4, 1024)), glm::uvec2(8, 4));   // the height's own limit
    EXPECT_EQ(autoWorkgroup(limits(8, 4, 128, 1024)), glm::uvec2(4, 8));     // the width's
    EXPECT_EQ(autoWorkgroup(limits(8, 0, 0, 0)), glm::uvec2(8, 8));          // not reported: not checked
    for (std::uint32_t s : {1u, 8u, 32u, 64u, 128u, 256u})
        for (std::uint32_t inv : {1u, 7u, 16u, 100u, 128u, 1024u}) {
            const glm::uvec2 wg = autoWorkgroup(limits(s, 16, 16, inv));
            EXPECT_GE(wg.x, 1u);
            EXPECT_GE(wg.y, 1u);
            EXPECT_LE(wg.x, 16u);
            EXPECT_LE(wg.y, 16u);
            EXPECT_LE(wg.x * wg.y, inv) << "subgroup " << s << ", " << inv << " invocations";
        }
}

TEST(Workgroup, TheUsersSizeWins) {
    const DeviceLimits l = limits(128, 1024, 1024, 1024);
    Features f;
    EXPECT_EQ(kernelWorkgroup(f, l), glm::uvec2(8, 16));  // 0x0: the device's
    f.workgroupX = 4;
    f.workgroupY = 2;
    EXPECT_EQ(kernelWorkgroup(f, l), glm::uvec2(4, 2));  // `--workgroup 4x2`, even below a subgroup
}

}  // namespace
}  // namespace vkp
