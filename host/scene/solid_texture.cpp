#include "scene/solid_texture.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "shared/texture_sample.h"

namespace vkp {

std::uint32_t packRgb9e5(glm::vec3 rgb) {
    constexpr int kN = 9, kB = 15;
    constexpr float kMax = 65408.0f;  // (2^9 - 1) / 2^9 * 2^(31 - 15)
    float c[3];
    for (int i = 0; i < 3; ++i) c[i] = rgb[i] > 0.0f ? std::min(rgb[i], kMax) : 0.0f;  // NaN and negatives: 0
    const float maxc = std::max({c[0], c[1], c[2]});
    if (!(maxc > 0.0f)) return 0u;
    int e = std::max(-kB - 1, int(std::floor(std::log2(maxc)))) + 1 + kB;
    if (std::floor(maxc / std::ldexp(1.0f, e - kB - kN) + 0.5f) >= float(1 << kN)) ++e;  // rounding carried over
    std::uint32_t out = std::uint32_t(e) << 27u;
    for (int i = 0; i < 3; ++i) {
        const std::uint32_t m = std::min(511u, std::uint32_t(std::floor(c[i] / std::ldexp(1.0f, e - kB - kN) + 0.5f)));
        out |= m << (9u * std::uint32_t(i));
    }
    return out;
}

glm::vec3 solidTextureBound(const std::vector<SolidTexture>& textures, const std::vector<TextureImage>& images,
                            const std::vector<Texture>& samplers, std::uint32_t t) {
    const SolidTexture& s = textures.at(t);
    const float kNoiseBound = std::sqrt(3.0f);  // |noise| (see scene.h)
    switch (s.kind) {
        case gpu::STEX_CHECKER:
            return glm::max(solidTextureBound(textures, images, samplers, s.even),
                            solidTextureBound(textures, images, samplers, s.odd));
        case gpu::STEX_IMAGE: {
            const Texture& tex = samplers.at(s.texture);
            const TextureImage& img = images.at(tex.image);
            std::uint32_t flags = img.rgb9e5 ? gpu::TEXF_RGB9E5 : 0u;
            if (tex.srgb) flags |= gpu::TEXF_SRGB;
            glm::vec3 m(0.0f);
            for (std::size_t i = 0; i + 3 < img.rgba8.size(); i += 4) {
                const std::uint32_t packed = std::uint32_t(img.rgba8[i]) | std::uint32_t(img.rgba8[i + 1]) << 8 |
                                             std::uint32_t(img.rgba8[i + 2]) << 16 | std::uint32_t(img.rgba8[i + 3]) << 24;
                m = glm::max(m, glm::vec3(gpu::texTexel(packed, flags)));
            }
            return s.colour * m;  // bilinear filtering stays within the texels' range
        }
        case gpu::STEX_NOISE: return s.colour * (0.5f * (1.0f + kNoiseBound));
        case gpu::STEX_TURBULENCE: return s.colour * (2.0f * kNoiseBound);
        case gpu::STEX_MARBLE: return s.colour;
        default: return s.colour;
    }
}

}  // namespace vkp
