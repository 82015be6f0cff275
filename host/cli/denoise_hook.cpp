#include "cli/denoise_hook.h"

namespace vkp {

std::function<Image(const DenoiseRequest&)> denoiseHook(Denoiser& denoiser) {
    return [&denoiser](const DenoiseRequest& q) {
        // The denoiser filters what is left after the emission seen directly (shared/aov.h), guided
        // by that part's own variance: the emission's coverage noise at a light's edge would
        // otherwise loosen the edge-stopping of the ceiling around it, which then takes in the
        // light's dark (emission-free) pixels.
        const FeatureImages& f = q.features;
        Image indirect = q.color, variance = q.color;
        for (std::size_t i = 0; i < indirect.rgb.size(); ++i) {
            indirect.rgb[i] -= f.emission.rgb[i];
            variance.rgb[i] = f.indirectVariance[i / 3];
        }
        const DenoiseInput in{&indirect, &variance, &f.albedo, &f.normal, &f.depth, &f.samples};
        Image out = denoiser.run(in);
        for (std::size_t i = 0; i < out.rgb.size(); ++i) out.rgb[i] += f.emission.rgb[i];
        return out;
    };
}

DenoiseOptions denoiseOptions(std::optional<DenoiseFilter> filter) {
    DenoiseOptions o;
    if (filter) o.filter = *filter;
    return o;
}

}  // namespace vkp
