#include "render/light_table.h"

#include <bit>
#include <cmath>
#include <numbers>

#include "render/emitter_power.h"
#include "render/environment.h"
#include "shared/punctual_light.h"

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

std::vector<double> pickWeights(const Scene& scene) {
    std::vector<double> w = lightPowers(scene);
    if (scene.punctualLights.empty()) return w;
    const double radius = sceneRadius(scene);
    for (const PunctualLight& l : scene.punctualLights) w.push_back(l.power(radius) / std::numbers::pi);
    return w;
}

std::vector<gpu::GpuLight> packLights(const Scene& scene, const std::vector<std::uint32_t>& primOfShape, LightPick pick) {
    std::vector<double> power = pickWeights(scene);
    if (pick == LightPick::Uniform)
        for (double& w : power) w = w > 0.0 ? 1.0 : 0.0;
    const AliasTable table = buildAliasTable(power);
    const std::size_t surfaces = scene.lights.size();
    std::vector<gpu::GpuLight> out;
    for (std::size_t i = 0; i < power.size(); ++i) {
        const std::uint32_t what = i < surfaces ? primOfShape.at(scene.lights[i]) : (gpu::LIGHT_PUNCTUAL_BIT | std::uint32_t(i - surfaces));
        gpu::GpuLight l{};
        l.l0 = glm::vec4(std::bit_cast<float>(what), table.probability[i], table.threshold[i], std::bit_cast<float>(table.alias[i]));
        out.push_back(l);
    }
    // The punctual lights' records, with the pick among them alone (the bsdf and mixture samplers).
    const AliasTable own = buildAliasTable(std::vector<double>(power.begin() + std::ptrdiff_t(surfaces), power.end()));
    for (std::size_t k = 0; k < scene.punctualLights.size(); ++k) {
        const PunctualLight& p = scene.punctualLights[k];
        const float cosOuter = std::cos(p.outerCone);
        gpu::GpuPunctualLight r{};
        const glm::vec3 at = p.kind == PunctualLight::Kind::Directional ? -p.direction : p.position;
        r.q0 = glm::vec4(at, std::bit_cast<float>(std::uint32_t(p.kind)));
        r.q1 = glm::vec4(p.intensity, gpu::spotScale(std::cos(p.innerCone), cosOuter));
        r.q2 = glm::vec4(p.direction, cosOuter);
        r.q3 = glm::vec4(0.0f, own.probability[k], own.threshold[k], std::bit_cast<float>(own.alias[k]));  // a GpuLight entry
        static_assert(sizeof(r) == gpu::GPU_PUNCTUAL_TEXELS * sizeof(gpu::GpuLight));
        for (const glm::vec4& t : {r.q0, r.q1, r.q2, r.q3}) out.push_back(gpu::GpuLight{t});
    }
    return out;
}

std::uint32_t emittingLightCount(const Scene& scene) {
    std::uint32_t n = 0;
    for (std::uint32_t shape : scene.lights) n += scene.materials.at(scene.shapes.at(shape).material).emits();
    return n;
}

}  // namespace vkp
