// The denoiser's own time (docs/performance.md "Denoiser"): the piecewise-smooth synthetic scene
// (tests/gpu/denoise_scenes.h) at 16 spp, 256x256 and 512x512, on the default device, for both
// filters (DenoiseFilter: the default, non-local means first, and the a-trous filter alone), their
// runs alternated. Prints each filter's first run (pipeline compilation included), the median of 7
// more (upload, dispatches, read-back) and the ratio of the medians. Issue 17's budget is the time
// of 4 spp of cornell-classic at the same size; the benchmark asserts nothing about speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "denoise_scenes.h"
#include "gpu_env.h"
#include "render/denoiser.h"

namespace vkp::test {
namespace {

double seconds(Denoiser& d, const DenoiseInput& in) {
    const auto t0 = std::chrono::steady_clock::now();
    const Image out = d.run(in);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(BenchDenoise, TimeAt256And512) {
    VKP_REQUIRE_DEVICE(dev);
    DenoiseOptions atrousOptions;
    atrousOptions.filter = DenoiseFilter::ATrous;
    Denoiser byDefault(dev), atrous(dev, atrousOptions);
    for (std::uint32_t size : {256u, 512u}) {
        const CleanScene s = piecewiseScene(size, size);
        const NoisyRender r = renderNoisy(s, 16, 1);
        const DenoiseInput in{&r.color, &r.variance, &s.albedo, &s.normal, &s.depth};
        const double firstDefault = seconds(byDefault, in), firstATrous = seconds(atrous, in);
        std::vector<double> td, ta;
        for (int i = 0; i < 7; ++i) {
            td.push_back(seconds(byDefault, in));
            ta.push_back(seconds(atrous, in));
        }
        std::sort(td.begin(), td.end());
        std::sort(ta.begin(), ta.end());
        std::printf("  %ux%u: default (non-local means first): first run %.3f s, median of 7 %.3f s (min %.3f, max %.3f)\n",
                    size, size, firstDefault, td[3], td[0], td[6]);
        std::printf("  %ux%u: a-trous alone: first run %.3f s, median of 7 %.3f s (min %.3f, max %.3f); default / a-trous %.2f\n",
                    size, size, firstATrous, ta[3], ta[0], ta[6], td[3] / ta[3]);
        // A measurement, not an assertion (speed is never a pass/fail test): docs/performance.md.
    }
}

}  // namespace
}  // namespace vkp::test
