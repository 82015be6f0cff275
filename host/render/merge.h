// Adding up the partial renders of sample ranges (`vkpath merge`, several devices): the image of the
// union equals that of one render of the same samples within float rounding.
#pragma once
#include <string>
#include <vector>

#include "render/accum_file.h"

namespace vkp {

/// Merges `parts` (named `names` in messages) into one state holding the union of their sample
/// ranges. The parts must have equal keys and sizes, no adaptive sampling, and ranges that tile an
/// interval without overlap or gap (in any order). Per pixel the sums are added in double in the
/// order of the ranges, whatever the order of `parts`, and stored as a compensated (hi, lo) float
/// pair; the counters and samplesTaken are added. Throws InputError with one line naming the
/// part(s) and what is wrong, e.g. "b.exr: samples [32:96) overlap a.exr's [0:64)".
/// The per-pixel sums of `states` (equal sizes, no adaptive sampling) added in double in the
/// given order and stored as compensated (hi, lo) float pairs; counters and samplesTaken added.
/// The result's sample range is [firstSample, nextSample) as given: the caller knows what union
/// the states hold.
RenderState addStates(const std::vector<const RenderState*>& states, std::uint32_t firstSample, std::uint32_t nextSample);

AccumFile mergeParts(const std::vector<AccumFile>& parts, const std::vector<std::string>& names);

}  // namespace vkp
