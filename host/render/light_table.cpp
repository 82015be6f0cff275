#include "render/light_table.h"

#include <bit>

#include "render/emitter_power.h"

namespace vkp {

namespace {
double powerOf(const Scene& scene, const EmissionEstimator& est, std::uint32_t shape) {
    const Shape& s = scene.shapes.at(shape);
    const Material m = kernelMaterial(scene.materials.at(s.material));
    if (!m.emits()) return 0.0;
    const double faces = (m.twoSided || m.type == MaterialType::Lambertian) ? 2.0 : 1.0;
    return est.meanLuminance(shape) * double(shapeArea(s)) * faces;
}
}  // namespace

double lightPower(const Scene& scene, std::uint32_t shape) { return powerOf(scene, EmissionEstimator(scene), shape); }

std::vector<double> lightPowers(const Scene& scene) {
    const EmissionEstimator est(scene);
    std::vector<double> out;
    out.reserve(scene.lights.size());
    for (std::uint32_t shape : scene.lights) out.push_back(powerOf(scene, est, shape));
    return out;
}

AliasTable buildAliasTable(const std::vector<double>& weights) {
    AliasTable t;
    const std::size_t n = weights.size();
    double sum = 0.0;
    for (double w : weights) sum += w > 0.0 ? w : 0.0;
    t.probability.assign(n, 0.0f);
    t.threshold.assign(n, 1.0f);
    t.alias.resize(n);
    for (std::size_t i = 0; i < n; ++i) t.alias[i] = std::uint32_t(i);
    if (!(sum > 0.0)) return t;
    // Vose: scaled weights p_i * n; split into columns below and above 1, pair them up.
    std::vector<double> scaled(n);
    std::vector<std::uint32_t> small, large;
    for (std::size_t i = 0; i < n; ++i) {
        const double p = (weights[i] > 0.0 ? weights[i] : 0.0) / sum;
        t.probability[i] = float(p);
        scaled[i] = p * double(n);
        (scaled[i] < 1.0 ? small : large).push_back(std::uint32_t(i));
    }
    while (!small.empty() && !large.empty()) {
        const std::uint32_t s = small.back(), l = large.back();
        small.pop_back();
        t.threshold[s] = float(scaled[s]);
        t.alias[s] = l;
        scaled[l] = (scaled[l] + scaled[s]) - 1.0;
        if (scaled[l] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // Left-overs are 1 up to rounding: they keep every pick of their column.
    for (std::uint32_t i : small) t.threshold[i] = 1.0f;
    for (std::uint32_t i : large) t.threshold[i] = 1.0f;
    return t;
}

std::vector<gpu::GpuLight> packLights(const Scene& scene, const std::vector<std::uint32_t>& primOfShape, LightPick pick) {
    std::vector<double> power = lightPowers(scene);
    if (pick == LightPick::Uniform)
        for (double& w : power) w = w > 0.0 ? 1.0 : 0.0;
    const AliasTable table = buildAliasTable(power);
    std::vector<gpu::GpuLight> out;
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        gpu::GpuLight l{};
        l.l0 = glm::vec4(std::bit_cast<float>(primOfShape.at(scene.lights[i])), table.probability[i], table.threshold[i],
                         std::bit_cast<float>(table.alias[i]));
        out.push_back(l);
    }
    return out;
}

std::uint32_t emittingLightCount(const Scene& scene) {
    std::uint32_t n = 0;
    for (std::uint32_t shape : scene.lights) n += scene.materials.at(scene.shapes.at(shape).material).emits();
    return n;
}

}  // namespace vkp
