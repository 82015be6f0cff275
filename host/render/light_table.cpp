#include "render/light_table.h"

#include <bit>

#include "shared/texture_sample.h"

namespace vkp {

namespace {
glm::dvec3 emissionScale(const Scene& scene, const Material& original) {
    if (original.type != MaterialType::Pbr || !original.emits() || !original.pbr.emissiveTexture.valid()) return glm::dvec3(1.0);
    const Texture& t = scene.textures.at(std::size_t(original.pbr.emissiveTexture.texture));
    const TextureImage& img = scene.images.at(t.image);
    glm::dvec3 sum(0.0);
    const std::size_t n = std::size_t(img.width) * img.height;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = &img.rgba8[4 * i];
        const glm::vec4 c = gpu::texDecode(std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8u) |
                                               (std::uint32_t(p[2]) << 16u) | (std::uint32_t(p[3]) << 24u),
                                           t.srgb);
        sum += glm::dvec3(c.x, c.y, c.z);
    }
    return n > 0 ? sum / double(n) : glm::dvec3(0.0);
}
}  // namespace

std::vector<glm::dvec3> emissionScales(const Scene& scene) {
    std::vector<glm::dvec3> out;
    out.reserve(scene.materials.size());
    for (const Material& m : scene.materials) out.push_back(emissionScale(scene, m));
    return out;
}

double lightPower(const Scene& scene, std::uint32_t shape, const std::vector<glm::dvec3>* scales) {
    const Shape& s = scene.shapes.at(shape);
    const Material m = kernelMaterial(scene.materials.at(s.material));
    if (!m.emits()) return 0.0;
    const glm::dvec3 k = scales ? scales->at(s.material) : emissionScale(scene, scene.materials.at(s.material));
    const double lum = 0.2126 * m.emit.x * k.x + 0.7152 * m.emit.y * k.y + 0.0722 * m.emit.z * k.z;
    const double faces = (m.twoSided || m.type == MaterialType::Lambertian) ? 2.0 : 1.0;
    return lum * double(shapeArea(s)) * faces;
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
    std::vector<double> power;
    const std::vector<glm::dvec3> scales = emissionScales(scene);
    for (std::uint32_t shape : scene.lights) {
        const double w = lightPower(scene, shape, &scales);
        power.push_back(pick == LightPick::Uniform ? (w > 0.0 ? 1.0 : 0.0) : w);
    }
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
