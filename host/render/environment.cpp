#include "render/environment.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "render/distribution_table.h"
#include "render/light_table.h"

namespace vkp {

namespace {
constexpr double kPi = 3.14159265358979323846;
double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

/// Mean of sin(theta) over row j of h (theta from 0 at the top to pi at the bottom).
double rowMeanSin(std::uint32_t j, std::uint32_t h) {
    const double t0 = kPi * j / h, t1 = kPi * (j + 1) / h;
    return (std::cos(t0) - std::cos(t1)) / (t1 - t0);
}

}  // namespace

double sceneRadius(const Scene& scene) {
    glm::dvec3 lo(1e300), hi(-1e300);
    auto add = [&](glm::dvec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    };
    for (const Shape& s : scene.shapes) {
        const glm::dvec3 a(s.p0), b(s.p1), c(s.p2);
        if (s.type == ShapeType::Sphere) {
            add(a - glm::dvec3(s.radius));
            add(a + glm::dvec3(s.radius));
        } else if (s.type == ShapeType::Quad) {
            add(a), add(a + b), add(a + c), add(a + b + c);
        } else {
            add(a), add(b), add(c);
        }
    }
    // Instances: their meshes' boxes placed in the world (corners; slightly larger than the triangles).
    std::vector<std::pair<glm::dvec3, glm::dvec3>> meshBox(scene.meshes.size(), {glm::dvec3(1e300), glm::dvec3(-1e300)});
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Shape& s : scene.meshes[m].shapes)
            for (const glm::vec3& p : {s.p0, s.p1, s.p2}) {
                meshBox[m].first = glm::min(meshBox[m].first, glm::dvec3(p));
                meshBox[m].second = glm::max(meshBox[m].second, glm::dvec3(p));
            }
    for (const MeshInstance& inst : scene.instances) {
        const auto& [blo, bhi] = meshBox.at(inst.mesh);
        for (int c = 0; c < 8; ++c)
            add(glm::dvec3(inst.objectToWorld * glm::dvec4((c & 1) ? bhi.x : blo.x, (c & 2) ? bhi.y : blo.y, (c & 4) ? bhi.z : blo.z, 1.0)));
    }
    if (scene.shapes.empty() && scene.instances.empty()) return 1.0;
    return std::max(0.5 * glm::length(hi - lo), 1e-6);
}

bool hasEnvironmentLight(const Scene& scene) {
    return scene.environment.hasMap() || scene.render.background != glm::vec3(0.0f);
}

std::vector<double> envSamplingWeights(const Image& image) {
    std::vector<double> w(image.pixelCount());
    for (std::uint32_t j = 0; j < image.height; ++j) {
        const double s = rowMeanSin(j, image.height);
        for (std::uint32_t i = 0; i < image.width; ++i) {
            auto p = image.pixel(i, j);
            w[std::size_t(j) * image.width + i] = luminance(p[0], p[1], p[2]) * s;
        }
    }
    return w;
}

EnvTables packEnvironment(const Scene& scene) {
    EnvTables t;
    const Image& img = scene.environment.image;
    if (!scene.environment.hasMap()) {
        t.texels.assign(1, glm::vec4(0.0f));
        t.distribution = buildDistribution2D({1.0}, 1, 1);
        return t;
    }
    t.width = img.width;
    t.height = img.height;
    t.texels.reserve(img.pixelCount());
    for (std::uint32_t j = 0; j < img.height; ++j)
        for (std::uint32_t i = 0; i < img.width; ++i) {
            auto p = img.pixel(i, j);
            t.texels.emplace_back(p[0], p[1], p[2], 0.0f);
        }
    t.distribution = buildDistribution2D(envSamplingWeights(img), img.width, img.height);
    return t;
}

double envMeanLuminance(const Scene& scene) {
    if (!scene.environment.hasMap()) {
        const glm::vec3 b = scene.render.background;
        return luminance(b.x, b.y, b.z);
    }
    const std::vector<double> w = envSamplingWeights(scene.environment.image);
    double sum = 0.0;  // sum of lum * mean sin over texels, times the texel's dtheta dphi
    for (double x : w) sum += x;
    const Image& img = scene.environment.image;
    return sum * (kPi / img.height) * (2.0 * kPi / img.width) / (4.0 * kPi);
}

double envPickProbability(const Scene& scene, LightPick pick) {
    if (!hasEnvironmentLight(scene)) return 0.0;
    if (pick == LightPick::Uniform) return 1.0 / (1.0 + double(emittingLightCount(scene) + scene.punctualLights.size()));
    double emitters = 0.0;
    for (double w : pickWeights(scene)) emitters += w;
    if (!(emitters > 0.0)) return 1.0;
    const double r = sceneRadius(scene);
    const double env = 4.0 * kPi * r * r * envMeanLuminance(scene);
    if (!(env > 0.0)) return 0.1;  // a map of zero luminance but some (blue-free...) radiance: keep it sampled
    return std::clamp(env / (env + emitters), 0.1, 0.9);
}

}  // namespace vkp
