#include "vk/spirv_specialize.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include <spirv-tools/libspirv.h>
#include <spirv-tools/optimizer.hpp>

#include "core/fnv1a.h"

namespace vkp {

namespace {

// SPIR-V opcodes, decorations and built-ins used here (SPIR-V specification 1.6, section 3).
constexpr std::uint32_t kMagic = 0x07230203u;
constexpr std::uint32_t kHeaderWords = 5;
constexpr std::uint32_t kOpConstantTrue = 41, kOpConstantFalse = 42, kOpConstant = 43;
constexpr std::uint32_t kOpSpecConstantTrue = 48, kOpSpecConstantFalse = 49, kOpSpecConstant = 50;
constexpr std::uint32_t kOpSpecConstantComposite = 51;
constexpr std::uint32_t kOpDecorate = 71, kOpExecutionModeId = 331;
// What specializeSpirv makes of its input. Raise it with every change to bake() or to the passes
// below: the kernel cache keys its entries with it (specializationKey).
constexpr std::uint64_t kSpecializerRevision = 1;
constexpr std::uint32_t kDecorationSpecId = 1, kDecorationBuiltIn = 11, kBuiltInWorkgroupSize = 25;

struct Instruction {
    std::size_t at;        // index of its first word
    std::uint32_t op;      // opcode
    std::uint32_t words;   // word count
};

std::vector<Instruction> instructions(std::span<const std::uint32_t> spirv) {
    if (spirv.size() < kHeaderWords || spirv[0] != kMagic) throw std::runtime_error("specializeSpirv: not a SPIR-V module");
    std::vector<Instruction> out;
    for (std::size_t i = kHeaderWords; i < spirv.size();) {
        const std::uint32_t words = spirv[i] >> 16;
        if (words == 0 || i + words > spirv.size())
            throw std::runtime_error("specializeSpirv: bad instruction at word " + std::to_string(i));
        out.push_back({i, spirv[i] & 0xffffu, words});
        i += words;
    }
    return out;
}

// Bakes the values in; returns the module and the constant_ids left as specialization constants.
SpirvSpecialization bake(std::span<const std::uint32_t> spirv, std::span<const std::uint32_t> values) {
    const std::vector<Instruction> ins = instructions(spirv);
    std::map<std::uint32_t, std::uint32_t> specIdOf;              // result id -> constant_id
    std::map<std::uint32_t, std::vector<std::uint32_t>> parts;    // spec composite -> constituents
    std::vector<std::uint32_t> keepRoots;                         // ids the workgroup size is made of
    for (const Instruction& in : ins) {
        const std::uint32_t* w = &spirv[in.at];
        if (in.op == kOpDecorate && in.words >= 4 && w[2] == kDecorationSpecId) specIdOf[w[1]] = w[3];
        if (in.op == kOpDecorate && in.words >= 4 && w[2] == kDecorationBuiltIn && w[3] == kBuiltInWorkgroupSize) keepRoots.push_back(w[1]);
        if (in.op == kOpExecutionModeId)
            for (std::uint32_t k = 3; k < in.words; ++k) keepRoots.push_back(w[k]);
        if (in.op == kOpSpecConstantComposite && in.words >= 3) parts[w[2]].assign(w + 3, w + in.words);
    }
    std::set<std::uint32_t> kept;  // result ids
    while (!keepRoots.empty()) {
        const std::uint32_t id = keepRoots.back();
        keepRoots.pop_back();
        if (!kept.insert(id).second) continue;
        if (auto it = parts.find(id); it != parts.end()) keepRoots.insert(keepRoots.end(), it->second.begin(), it->second.end());
    }
    // The 32-bit constants and bools that get a value (result ids), then one pass that writes
    // them as constants and drops their SpecId decorations.
    std::set<std::uint32_t> baked;
    for (const Instruction& in : ins) {
        const std::uint32_t* w = &spirv[in.at];
        const bool bakeable = ((in.op == kOpSpecConstantTrue || in.op == kOpSpecConstantFalse) && in.words == 3) ||
                              (in.op == kOpSpecConstant && in.words == 4);
        if (!bakeable || kept.count(w[2])) continue;
        if (auto it = specIdOf.find(w[2]); it != specIdOf.end() && it->second < values.size()) baked.insert(w[2]);
    }
    SpirvSpecialization out;
    out.words.reserve(spirv.size());
    out.words.assign(spirv.begin(), spirv.begin() + kHeaderWords);
    for (const Instruction& in : ins) {
        const std::uint32_t* w = &spirv[in.at];
        if (in.op == kOpDecorate && in.words >= 4 && w[2] == kDecorationSpecId && baked.count(w[1])) continue;
        if ((in.op == kOpSpecConstantTrue || in.op == kOpSpecConstantFalse || in.op == kOpSpecConstant) && baked.count(w[2])) {
            const std::uint32_t v = values[specIdOf[w[2]]];
            if (in.op == kOpSpecConstant) out.words.insert(out.words.end(), {(4u << 16) | kOpConstant, w[1], w[2], v});
            else out.words.insert(out.words.end(), {(3u << 16) | (v ? kOpConstantTrue : kOpConstantFalse), w[1], w[2]});
            continue;
        }
        out.words.insert(out.words.end(), w, w + in.words);
    }
    for (const auto& [id, specId] : specIdOf)
        if (!baked.count(id)) out.keptIds.push_back(specId);
    std::sort(out.keptIds.begin(), out.keptIds.end());
    out.keptIds.erase(std::unique(out.keptIds.begin(), out.keptIds.end()), out.keptIds.end());
    return out;
}

}  // namespace

SpirvSpecialization specializeSpirv(std::span<const std::uint32_t> spirv, std::span<const std::uint32_t> values) {
    SpirvSpecialization s = bake(spirv, values);
    std::string messages;
    spvtools::Optimizer opt(SPV_ENV_VULKAN_1_2);
    opt.SetMessageConsumer([&](spv_message_level_t level, const char*, const spv_position_t& pos, const char* m) {
        if (level <= SPV_MSG_ERROR) messages += (messages.empty() ? "" : "; ") + std::string(m) + " (word " + std::to_string(pos.index) + ")";
    });
    // Fold what the baked values decide, then remove what became dead. Twice: a removed branch
    // can make a later condition constant (on cornell-classic one round already gave the same
    // module; the second round costs little).
    opt.RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
        .RegisterPass(spvtools::CreateUnifyConstantPass());
    for (int round = 0; round < 2; ++round)
        opt.RegisterPass(spvtools::CreateCCPPass())
            .RegisterPass(spvtools::CreateDeadBranchElimPass())
            .RegisterPass(spvtools::CreateBlockMergePass())
            .RegisterPass(spvtools::CreateAggressiveDCEPass())
            .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass());
    opt.RegisterPass(spvtools::CreateEliminateDeadConstantPass());
    spvtools::OptimizerOptions options;
    options.set_run_validator(false);  // the input is our own build output; the tests validate the result
    std::vector<std::uint32_t> optimized;
    if (!opt.Run(s.words.data(), s.words.size(), &optimized, options))
        throw std::runtime_error("specializeSpirv: SPIRV-Tools failed" + (messages.empty() ? std::string() : ": " + messages));
    s.words = std::move(optimized);
    return s;
}

std::uint64_t specializationKey(std::span<const std::uint32_t> spirv, std::span<const std::uint32_t> values) {
    Fnv1a h;
    h.add(std::string_view("specializeSpirv"));
    h.add(kSpecializerRevision);
    h.add(std::string_view(spvSoftwareVersionDetailsString()));
    h.add(std::uint64_t(spirv.size()));
    h.add(std::as_bytes(spirv));
    h.add(std::uint64_t(values.size()));
    h.add(std::as_bytes(values));
    return h.h;
}

}  // namespace vkp
