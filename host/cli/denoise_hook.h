// What `--denoise` runs on a render's image (cli/commands.cpp, cli/multi_device.cpp): the emission
// the camera sees directly (FeatureImages::emission: lights and the background, noise-free but for
// the pixel filter) is taken out, the rest is denoised (render/denoiser.h) and the emission is
// added back, so lights' and the sky's edges stay exactly as rendered.
#pragma once
#include <functional>
#include <optional>

#include "render/denoiser.h"
#include "render/session.h"

namespace vkp {

/// The session's denoiser (SessionOptions::denoiser) running on `denoiser`, which must outlive it.
std::function<Image(const DenoiseRequest&)> denoiseHook(Denoiser& denoiser);

/// The denoiser's options for `--denoise-filter` (unset: the defaults).
DenoiseOptions denoiseOptions(std::optional<DenoiseFilter> filter);

}  // namespace vkp
