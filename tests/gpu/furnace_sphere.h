// The furnace sphere of the device tests of the glTF BRDF and its layers (test_gpu_pbr.cpp,
// test_gpu_layers.cpp): a unit sphere seen from 4 units away in a 24 x 24 image under a uniform
// background of radiance 1. Light leaving a convex object never returns to it, so a sample of a
// sphere pixel is the weight of ONE scattering and its expectation the material's directional
// albedo at that pixel's view angle; the host estimates the same pixels with the kernel's camera
// jitter and the C++ build of the material.
#pragma once
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "file_frame.h"
#include "render/gpu_scene.h"
#include "stat_suite.h"
#include "test_gpu_analytic_common.h"

namespace vkp::test {

constexpr std::uint32_t kFurnaceSize = 24;

/// The scene with a white lambertian sphere (material 0, which the test replaces).
inline Scene furnaceSphereScene(const std::string& name) {
    return parseSceneJson(R"({
      "camera": {"lookfrom": [0, 0, 4], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 24, "height": 24},
      "render": {"max_depth": 50, "background": [1, 1, 1]},
      "materials": {"m": {"type": "lambertian", "albedo": [1, 1, 1]}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m", "sample": true}]})",
                          name);
}

inline glm::dvec3 cameraTarget(const gpu::GpuFrame& f, double i, double j) {
    return glm::dvec3(f.pixel00) + i * glm::dvec3(f.pixelDu) + j * glm::dvec3(f.pixelDv);
}

/// Cosine between the unit sphere's normal and -d where the ray o + t d first hits it (0: miss).
inline double hitCosine(glm::dvec3 o, glm::dvec3 d) {
    d = glm::normalize(d);
    const double b = glm::dot(o, d), c = glm::dot(o, o) - 1.0, disc = b * b - c;
    if (disc <= 0.0) return 0.0;
    const double t = -b - std::sqrt(disc);
    if (t <= 0.0) return 0.0;
    return -glm::dot(o + t * d, d);
}

/// Pixels whose four corners all see the sphere (the silhouette is convex: the whole pixel does).
inline std::vector<Pixel> spherePixels(const Scene& scene) {
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    const glm::dvec3 o(f.origin);
    std::vector<Pixel> out;
    for (std::uint32_t y = 0; y < kFurnaceSize; ++y)
        for (std::uint32_t x = 0; x < kFurnaceSize; ++x) {
            bool all = true;
            for (double sx : {-0.5, 0.5})
                for (double sy : {-0.5, 0.5}) all = all && hitCosine(o, cameraTarget(f, x + sx, y + sy) - o) > 0.0;
            if (all) out.push_back({x, y});
        }
    return out;
}

/// One scattering's weight for the local view direction v (z = the normal), from numbers of rng.
using ScatterWeight = std::function<double(glm::vec3 v, UniformSource& rng)>;

/// Host estimate of the sphere pixels' average: per pixel n camera rays with the kernel's
/// box-filter jitter, one scattering each.
inline Estimate hostFurnaceEstimate(const Scene& scene, const std::vector<Pixel>& pixels, int n, std::uint32_t seed,
                                    const ScatterWeight& weight) {
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    const glm::dvec3 o(f.origin);
    UniformSource rng(seed);
    Estimate e;
    for (const Pixel& p : pixels) {
        double s = 0.0, s2 = 0.0;
        for (int i = 0; i < n; ++i) {
            const glm::vec2 j = rng.next2() - glm::vec2(0.5f);
            const double mu = hitCosine(o, cameraTarget(f, p.x + j.x, p.y + j.y) - o);
            const glm::vec3 v(float(std::sqrt(std::max(0.0, 1.0 - mu * mu))), 0.0f, float(mu));
            const double w = weight(v, rng);
            s += w;
            s2 += w * w;
        }
        const double mean = s / n;
        e.mean += mean;
        e.var += std::max(0.0, s2 / n - mean * mean) / (n - 1);
    }
    const double k = double(pixels.size());
    e.mean /= k;
    e.var /= k * k;
    e.n = n;
    return e;
}

}  // namespace vkp::test
