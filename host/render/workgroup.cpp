#include "render/workgroup.h"

#include <algorithm>

#include "render/features.h"
#include "render/gpu_arrays.h"

namespace vkp {

glm::uvec2 autoWorkgroup(const DeviceLimits& limits) {
    // Vulkan's subgroupSize is a power of two; anything else is taken as unknown.
    const std::uint32_t subgroupSize = limits.subgroupSize;
    const bool known = subgroupSize != 0 && (subgroupSize & (subgroupSize - 1)) == 0;
    const std::uint32_t invocations = std::max<std::uint32_t>(64, known ? std::min<std::uint32_t>(subgroupSize, 1024) : 0);
    glm::uvec2 wg(8, invocations / 8);
    const std::uint32_t maxX = limits.maxComputeWorkGroupSize[0], maxY = limits.maxComputeWorkGroupSize[1];
    const std::uint32_t maxInvocations = limits.maxComputeWorkGroupInvocations;
    while (maxX && wg.x > maxX && wg.x > 1) wg.x /= 2;
    while (maxY && wg.y > maxY && wg.y > 1) wg.y /= 2;
    while (maxInvocations && wg.x * wg.y > maxInvocations && wg.y > 1) wg.y /= 2;
    while (maxInvocations && wg.x * wg.y > maxInvocations && wg.x > 1) wg.x /= 2;
    return wg;
}

glm::uvec2 kernelWorkgroup(const Features& features, const DeviceLimits& limits) {
    if (features.workgroupX != 0 && features.workgroupY != 0) return glm::uvec2(features.workgroupX, features.workgroupY);
    return autoWorkgroup(limits);
}

}  // namespace vkp
