#include "render/ggx_albedo_table.h"

#include <algorithm>

namespace vkp {

namespace {
std::vector<glm::vec4> computeTable() {
    using namespace gpu;
    const int n = int(GGX_ALBEDO_N), strata = 32;
    std::vector<glm::vec4> t(std::size_t(n) * n);
    for (int j = 0; j < n; ++j) {
        const float alpha = ggxAlpha(float(j) / float(n - 1));
        std::vector<double> a(n), b(n);
        for (int i = 0; i < n; ++i) {
            const double s = double(i) / double(n - 1);
            const double mu = std::max(1e-6, s * s * s * s);
            const vec3 v(float(std::sqrt(1.0 - mu * mu)), 0.0f, float(mu));
            double sa = 0.0, sb = 0.0;
            for (int y = 0; y < strata; ++y)
                for (int x = 0; x < strata; ++x) {
                    const vec2 u((float(x) + 0.5f) / strata, (float(y) + 0.5f) / strata);
                    const vec3 h = sampleGgxVisibleNormal(v, alpha, u);
                    const vec3 l = 2.0f * dot(v, h) * h - v;
                    if (!(l.z > 0.0f)) continue;
                    const float pdf = pdfGgxVndfHalf(v, h, alpha);
                    if (!(pdf > 0.0f)) continue;
                    const double weight = double(ggxD(h, alpha)) * ggxVisibility(v, l, alpha) * l.z / pdf;
                    const double w5 = schlickWeight(std::abs(dot(v, h)));
                    sa += weight * (1.0 - w5);
                    sb += weight * w5;
                }
            a[i] = sa / (strata * strata);
            b[i] = sb / (strata * strata);
        }
        // 2 int_0^1 E(mu) mu dmu = int_0^1 E(s^4) 8 s^7 ds, E linear in s between the samples as
        // ggxAlbedoLookup interpolates it (Simpson on 8 sub-intervals of each: the integrand is a
        // polynomial of degree 8 in s, integrated to < 1e-7).
        double aavg = 0.0, bavg = 0.0;
        for (int i = 0; i + 1 < n; ++i) {
            const double s0 = double(i) / (n - 1), s1 = double(i + 1) / (n - 1);
            const int m = 8;
            for (int k = 0; k <= m; ++k) {
                const double f = double(k) / m, sv = s0 + f * (s1 - s0);
                const double wk = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
                const double s7 = sv * sv * sv * sv * sv * sv * sv;
                const double g = 8.0 * s7 * (s1 - s0) / (3.0 * m) * wk;
                aavg += g * (a[i] * (1.0 - f) + a[i + 1] * f);
                bavg += g * (b[i] * (1.0 - f) + b[i + 1] * f);
            }
        }
        for (int i = 0; i < n; ++i)
            t[std::size_t(j) * n + i] = glm::vec4(float(a[i]), float(b[i]), float(aavg), float(bavg));
    }
    return t;
}
}  // namespace

const std::vector<glm::vec4>& ggxAlbedoTable() {
    static const std::vector<glm::vec4> table = computeTable();
    return table;
}

}  // namespace vkp

namespace vkp::gpu {
/// The host's definition of microfacet.h's table access (the kernel reads the same texels from a
/// buffer).
vec4 ggxAlbedoFetch(uint t) { return vkp::ggxAlbedoTable()[t]; }
}  // namespace vkp::gpu
