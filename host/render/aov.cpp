#include "render/aov.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "render/render_state.h"

namespace vkp {

const char* aovName(Aov a) {
    switch (a) {
        case Aov::Albedo: return "albedo";
        case Aov::Normal: return "normal";
        case Aov::Depth: return "depth";
        case Aov::Position: return "position";
        case Aov::Emission: return "emission";
        case Aov::Variance: return "variance";
        case Aov::Spp: return "spp";
    }
    return "?";
}

bool aovNeedsKernel(Aov a) { return a != Aov::Variance && a != Aov::Spp; }

std::string parseAovList(const std::string& list, std::vector<Aov>& out) {
    std::vector<bool> want(std::size(kAllAovs), false);
    std::size_t start = 0;
    while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, comma - start);
        bool known = false;
        if (name == "all") {
            want.assign(want.size(), true);
            known = true;
        }
        for (std::size_t k = 0; k < std::size(kAllAovs); ++k)
            if (name == aovName(kAllAovs[k])) want[k] = known = true;
        if (!known) {
            std::string names;
            for (Aov a : kAllAovs) names += std::string(names.empty() ? "" : ", ") + aovName(a);
            return "unknown AOV '" + name + "' (known: " + names + ", all)";
        }
        start = comma + 1;
    }
    out.clear();
    for (std::size_t k = 0; k < std::size(kAllAovs); ++k)
        if (want[k]) out.push_back(kAllAovs[k]);
    return {};
}

FeatureImages featureImages(std::span<const float> sums, std::uint32_t width, std::uint32_t height, const AovFrame& frame) {
    const std::size_t n = std::size_t(width) * height;
    if (sums.size() != n * kAovFloatsPerPixel) throw std::invalid_argument("featureImages: the sums do not hold the image's pixels");
    FeatureImages f;
    f.albedo = Image(width, height);
    f.normal = Image(width, height);
    f.position = Image(width, height);
    f.emission = Image(width, height);
    f.depth.assign(n, std::numeric_limits<float>::infinity());
    f.hitFraction.assign(n, 0.0f);
    f.samples.assign(n, 0.0f);
    f.indirectVariance.assign(n, 0.0f);
    const glm::dvec3 axis(frame.viewAxis), eye(frame.eye);
    for (std::size_t i = 0; i < n; ++i) {
        const float* s = sums.data() + i * kAovFloatsPerPixel;  // shared/aov.h: (albedo, samples), (normal, hits), (position, indirect), (emission, indirect^2)
        const double samples = s[3], hits = s[7];
        if (samples > 0.0) {
            for (int c = 0; c < 3; ++c) {
                f.albedo.rgb[3 * i + c] = s[c];
                f.normal.rgb[3 * i + c] = s[4 + c];
                f.emission.rgb[3 * i + c] = s[12 + c];
            }
            f.hitFraction[i] = float(hits / samples);
            f.samples[i] = float(samples);
            if (samples >= 2.0) {
                const double mean = s[11], sampleVariance = std::max(0.0, double(s[15]) - mean * mean) * samples / (samples - 1.0);
                f.indirectVariance[i] = float(sampleVariance / samples);
            }
        }
        if (hits > 0.0) {
            const glm::dvec3 p(s[8], s[9], s[10]);  // camera-relative
            const glm::dvec3 world = p + frame.worldOrigin;
            for (int c = 0; c < 3; ++c) f.position.rgb[3 * i + c] = float(world[c]);
            f.depth[i] = float(glm::dot(p - eye, axis));
        }
    }
    return f;
}

std::vector<ImageLayer> aovLayers(const std::vector<Aov>& which, const FeatureImages* features, const PixelSums& sums) {
    std::vector<ImageLayer> out;
    for (Aov a : which) {
        if (aovNeedsKernel(a) && !features) throw std::invalid_argument(std::string("aovLayers: no feature images for ") + aovName(a));
        ImageLayer l;
        l.name = aovName(a);
        switch (a) {
            case Aov::Albedo:
                l.channels = {"R", "G", "B"};
                l.values = features->albedo;
                break;
            case Aov::Normal:
                l.channels = {"X", "Y", "Z"};
                l.values = features->normal;
                break;
            case Aov::Position:
                l.channels = {"X", "Y", "Z"};
                l.values = features->position;
                break;
            case Aov::Emission:
                l.channels = {"R", "G", "B"};
                l.values = features->emission;
                break;
            case Aov::Depth:
                l.channels = {"Z"};
                l.values = Image(features->albedo.width, features->albedo.height);
                for (std::size_t i = 0; i < features->depth.size(); ++i) l.values.rgb[3 * i] = features->depth[i];
                break;
            case Aov::Variance:
                l.channels = {"R", "G", "B"};
                l.values = sums.varianceOfMean();
                break;
            case Aov::Spp:
                l.channels = {"V"};
                l.values = Image(sums.width, sums.height);
                for (std::size_t i = 0; i < l.values.pixelCount(); ++i) l.values.rgb[3 * i] = float(sums.sum[4 * i + 3]);
                break;
        }
        out.push_back(std::move(l));
    }
    return out;
}

}  // namespace vkp
