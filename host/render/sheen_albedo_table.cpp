#include "render/sheen_albedo_table.h"

#include <cmath>

namespace vkp {

namespace {

/// E_s(mu) for one (mu, alpha): cos theta_l = t^2 (denser samples at grazing l, where the lobe of a
/// small alpha lives: its half vectors lie near the horizon), phi over [0, pi] (the lobe is
/// symmetric about the plane of v and n), midpoint rule on 64 x 64 cells:
/// E = 2 int_0^1 int_0^pi f(l) t^2 (2 t) dphi dt.
double sheenAlbedoAt(double mu, float alpha) {
    using namespace gpu;
    constexpr int nt = 64, nphi = 64;
    const double pi = 3.14159265358979323846;
    const vec3 v(float(std::sqrt(std::max(0.0, 1.0 - mu * mu))), 0.0f, float(mu));
    double sum = 0.0;
    for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) / nt, c = t * t, s = std::sqrt(std::max(0.0, 1.0 - c * c));
        double row = 0.0;
        for (int k = 0; k < nphi; ++k) {
            const double phi = pi * (k + 0.5) / nphi;
            const vec3 l(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c));
            row += double(sheenLobe(v, l, alpha)) * c;
        }
        sum += row * (pi / nphi) * (2.0 * t) / nt;
    }
    return 2.0 * sum;
}

std::vector<glm::vec4> computeTable() {
    const int n = int(gpu::SHEEN_ALBEDO_N);
    std::vector<glm::vec4> t(std::size_t(n) * std::size_t(n), glm::vec4(0.0f));
    for (int j = 0; j < n; ++j) {
        const float alpha = gpu::sheenAlpha(float(j) / float(n - 1));
        for (int i = 0; i < n; ++i) {
            const double s = double(i) / double(n - 1);
            const double mu = std::max(1e-6, s * s * s * s);  // mu = 0: the limit
            t[std::size_t(j) * std::size_t(n) + std::size_t(i)].x = float(sheenAlbedoAt(mu, alpha));
        }
    }
    return t;
}

}  // namespace

const std::vector<glm::vec4>& sheenAlbedoTable() {
    static const std::vector<glm::vec4> table = computeTable();
    return table;
}

}  // namespace vkp

namespace vkp::gpu {
/// The host's definition of layers.h's table access (the kernel reads the same texels).
vec4 sheenAlbedoFetch(uint t) { return vkp::sheenAlbedoTable()[t]; }
}  // namespace vkp::gpu
