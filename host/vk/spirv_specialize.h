// Specialization on the host: the values of a pipeline's specialization constants baked into its
// SPIR-V, and the code they make unreachable removed, before the driver sees the module.
//
// Why: lavapipe (Mesa 22.3) applies specialization constants only after it has translated the
// whole module to NIR and inlined every function into the entry point, the ones a variant never
// calls included; for the path tracer that is seconds per pipeline, most of it on code the
// variant's constants switch off (docs/design.md "Shader compilation"). SPIRV-Tools removes that
// code first, in a fraction of the time, and the driver gets a module of about half the size.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace vkp {

/// What specializeSpirv did.
struct SpirvSpecialization {
    std::vector<std::uint32_t> words;    ///< the specialized module (valid SPIR-V of the same version)
    std::vector<std::uint32_t> keptIds;  ///< constant_ids left as specialization constants (sorted)
};

/// Bakes specialization constant i = values[i] (32-bit bit patterns; bools 0 or 1) into `spirv`,
/// then folds the expressions built on them and removes the branches, functions and constants
/// they make dead (SPIRV-Tools: constant propagation, dead-branch and aggressive dead-code
/// elimination). Left as specialization constants, still set through VkSpecializationInfo: the
/// ones that make up the WorkgroupSize built-in or that an OpExecutionModeId names (the
/// workgroup size; a driver treats a baked workgroup size differently), ids without a value in
/// `values`, and constants wider than 32 bits. The result computes what the driver would compute
/// from the original module and the same VkSpecializationInfo.
/// Throws std::runtime_error if `spirv` is not a SPIR-V module or SPIRV-Tools refuses it.
SpirvSpecialization specializeSpirv(std::span<const std::uint32_t> spirv, std::span<const std::uint32_t> values);

/// The kernel cache's key of specializeSpirv(spirv, values).words (vk/compute_pipeline.cpp): an
/// FNV-1a hash of the module, the values, this specializer's revision and SPIRV-Tools' version, so
/// that a change of any of them misses the cache.
std::uint64_t specializationKey(std::span<const std::uint32_t> spirv, std::span<const std::uint32_t> values);

}  // namespace vkp
