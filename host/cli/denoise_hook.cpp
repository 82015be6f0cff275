#include "cli/denoise_hook.h"

namespace vkp {

std::function<Image(const DenoiseRequest&)> denoiseHook(Denoiser& denoiser) {
    return [&denoiser](const DenoiseRequest& q) {
        const Image& emission = q.features.emission;
        Image indirect = q.color;
        for (std::size_t i = 0; i < indirect.rgb.size(); ++i) indirect.rgb[i] -= emission.rgb[i];
        const DenoiseInput in{&indirect, &q.variance, &q.features.albedo, &q.features.normal, &q.features.depth};
        Image out = denoiser.run(in);
        for (std::size_t i = 0; i < out.rgb.size(); ++i) out.rgb[i] += emission.rgb[i];
        return out;
    };
}

}  // namespace vkp
