// The kernel's workgroup size: the one the user asked for (`--workgroup WxH`), or one chosen from
// the device's subgroup size (docs/design.md "Subgroups, workgroups and threads"). No Vulkan:
// unit-tested on the host (tests/unit/test_workgroup.cpp).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace vkp {

struct DeviceLimits;
struct Features;

/// The automatic workgroup for a device whose subgroups have limits.subgroupSize lanes (0: unknown,
/// as for 8): at least 64 invocations and a whole number of subgroups, 8 pixels wide, so that a
/// subgroup of 8 covers a row of 8 pixels, one of 32 an 8x4 block and one of 64 an 8x8 tile (rays of
/// neighbouring pixels traverse alike); a subgroup of 128 gets 8x16. Shrunk (height first) to fit
/// maxComputeWorkGroupSize and maxComputeWorkGroupInvocations where those are reported (non-zero).
glm::uvec2 autoWorkgroup(const DeviceLimits& limits);

/// The workgroup a render of `features` runs with on a device of `limits`: features' own
/// (Features::workgroupX/Y, from `--workgroup`) when set, else autoWorkgroup of the device.
glm::uvec2 kernelWorkgroup(const Features& features, const DeviceLimits& limits);

}  // namespace vkp
