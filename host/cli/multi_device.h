// `vkpath render --device all` or `--device 0,1`: one render split over several Vulkan devices of
// one process, merged as `vkpath merge` does (render/merge.h).
#pragma once
#include <chrono>
#include <string>
#include <vector>

#include "cli/args.h"
#include "render/gpu_arrays.h"
#include "render/render_job.h"

namespace vkp {

/// The device selectors of `--device`: "all" -> {"all"}; "0,1" -> {"0", "1"} (one entry per
/// device; the same device may be named twice: it is then opened twice). A single selector
/// (no comma, not "all") gives one entry.
std::vector<std::string> deviceSelectors(const std::string& option);

/// Renders `job` (its arrays packed, samples [firstSample, job.session.spp)) on every device
/// `selectors` names, in rounds: in each round device k adds the k-th of D equal chunks of
/// consecutive samples, so that the union of finished rounds is always one range. Ends at the
/// end of the range, at --time or at a signal (after the round in flight), then writes the
/// outputs and --partial of the union. Refuses options that need one device (adaptive sampling,
/// checkpoints, dumps, --reference, --stats-json) with one usage line. Returns the exit code.
int renderOnDevices(const CliArgs& args, RenderJob& job, const GpuArrays& arrays, std::uint32_t firstSample,
                    const std::vector<std::string>& selectors, std::chrono::steady_clock::time_point processStart);

}  // namespace vkp
