// Whether the device rounds the kernels' plain float arithmetic as the host does. The GPU tests
// compare the kernels with their C++ twins (shared/ code compiled twice) and one kernel variant
// with another bit for bit; that holds only on a device that rounds every division, reciprocal and
// square root exactly and never fuses a * b + c into an fma, as lavapipe does (its JIT is LLVM
// without fast-math). Vulkan promises less: 2.5 ulp for a division, sqrt as 1 / inversesqrt, and
// contraction wherever NoContraction is absent (Vulkan specification, appendix "Precision and
// Operation of SPIR-V Instructions"), and GPUs use that freedom. On such a device the comparisons
// hold the results to rounding instead (sums_agreement.h, bvh_trace_compare.h); docs/accuracy.md
// "Exact and rounding-tolerant comparisons".
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vk/device.h"

namespace vkp::test {

/// What the probe kernel (shaders/tests/rounding_probe.comp) found: of `items` operand triples,
/// how many results differ from the host's in any bit, per operation.
struct RoundingProbe {
    std::size_t items = 0;
    std::size_t quotient = 0;    ///< a / b
    std::size_t reciprocal = 0;  ///< 1 / b
    std::size_t root = 0;        ///< sqrt(|a|)
    std::size_t mulAdd = 0;      ///< a * b + c, unfused on the host
    bool exact() const { return items > 0 && quotient + reciprocal + root + mulAdd == 0; }
    /// One line for test output: "rounds as the host" or the operations that differ and how often.
    std::string describe() const;
};

/// The probe's operand triples (x, y, z; w unused): 4096 normal floats of both signs, magnitudes
/// 2^-20 to 2^21, from a fixed seed.
std::vector<glm::vec4> roundingProbeInputs();

/// Runs the probe on `dev` (4096 triples of normal floats from a fixed seed, magnitudes 2^-20 to
/// 2^21, both signs), once per device per process.
const RoundingProbe& probeRounding(VulkanDevice& dev);

/// probeRounding(dev).exact(): bit-for-bit comparisons with the host, and between kernel variants,
/// are meaningful on this device.
inline bool roundsLikeTheHost(VulkanDevice& dev) { return probeRounding(dev).exact(); }

}  // namespace vkp::test
