#include "render/perlin_table.h"

#include <bit>
#include <cstdint>
#include <random>
#include <utility>

#include "shared/kinds.h"

namespace vkp {

std::vector<glm::uvec4> perlinTable() {
    constexpr std::uint32_t n = gpu::PERLIN_POINTS;
    std::mt19937 rng(20240401u);  // fixed: every render and every machine gets the same noise
    // Uniform in [0, 1) from the top 24 bits (std::uniform_real_distribution is not the same on
    // every standard library).
    auto uniform = [&rng] { return float(rng() >> 8u) * (1.0f / 16777216.0f); };
    std::vector<glm::uvec4> table(n, glm::uvec4(0));
    for (std::uint32_t i = 0; i < n; ++i) {
        glm::vec3 g(0.0f);
        float len = 0.0f;
        while (!(len > 1e-3f)) {  // a point at the cube's centre has no direction: draw again
            g = glm::vec3(2.0f * uniform() - 1.0f, 2.0f * uniform() - 1.0f, 2.0f * uniform() - 1.0f);
            len = glm::length(g);
        }
        g /= len;
        table[i] = glm::uvec4(std::bit_cast<std::uint32_t>(g.x), std::bit_cast<std::uint32_t>(g.y),
                              std::bit_cast<std::uint32_t>(g.z), 0u);
    }
    for (std::uint32_t axis = 0; axis < 3; ++axis) {
        std::uint32_t perm[n];
        for (std::uint32_t i = 0; i < n; ++i) perm[i] = i;
        for (std::uint32_t i = n - 1; i > 0; --i) std::swap(perm[i], perm[rng() % (i + 1)]);
        for (std::uint32_t i = 0; i < n; ++i) table[i].w |= perm[i] << (8u * axis);
    }
    return table;
}

}  // namespace vkp
