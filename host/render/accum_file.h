// The accumulation file: a render's state (render/render_state.h) and key (render/render_key.h) as
// an OpenEXR image that standard tools read (oiiotool --info -v, Blender's compositor). It is both
// the checkpoint (`--checkpoint`, continued by `--resume`) and the partial of a sample range
// (`--partial`, added up by `vkpath merge`). docs/farm.md describes the channels and attributes.
//
// Channels, 32-bit float, ZIP (lossless: every bit of the device's sums survives):
//   sum.R sum.G sum.B count          per pixel: the sum of its finite samples and their number
//   sum_lo.R sum_lo.G sum_lo.B count_lo   their compensation terms (sum = sum + sum_lo exactly)
//   sumsq.R sumsq.G sumsq.B, sumsq_lo.R ...   the sums of squares and theirs
//   adaptive sampling only: active (1 = still receiving samples), decision.R .G .B .count and
//   decision_sq.R .G .B (the decision stream's sums, render/adaptive.h)
//   feature images only (`--aov`): aov_albedo.R .G .B, aov_samples, aov_normal.X .Y .Z, aov_hits,
//   aov_position.X .Y .Z, aov_emission.R .G .B (shared/aov.h's running means and counts)
// String attributes: vkpath.format ("accumulation 1"), vkpath.samples ("A:B": sample indices
// [A, B) of every pixel are in the sums), vkpath.samplesTaken, vkpath.rays, vkpath.nonfinite,
// vkpath.loopGuard, and vkpath.key.<name> for every entry of the key (spaces in names as '_').
#pragma once
#include <filesystem>
#include <iosfwd>

#include "render/render_key.h"
#include "render/render_state.h"

namespace vkp {

struct AccumFile {
    RenderKey key;
    RenderState state;
};

/// Writes `state` and `key` to `path` atomically (core/atomic_file.h). Throws InputError
/// "<path>: ..." on an I/O failure; `path` is then untouched.
void writeAccumFile(const std::filesystem::path& path, const RenderKey& key, const RenderState& state);

/// The bytes of such a file, into `out` (`path` only names it in messages).
void encodeAccumFile(std::ostream& out, const std::filesystem::path& path, const RenderKey& key, const RenderState& state);

/// Reads a file writeAccumFile wrote. Throws InputError "<path>: ..." naming what is wrong (not
/// an EXR, not an accumulation file, a missing channel or attribute, a bad value).
AccumFile readAccumFile(const std::filesystem::path& path);

}  // namespace vkp
