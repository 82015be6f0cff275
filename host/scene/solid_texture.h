// Host helpers for the textures of JSON scenes (Scene::solidTextures; kernel side:
// shaders/shared/solid_texture.h): high-dynamic-range texels and the bounds of a texture.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace vkp {

/// Linear RGB as one RGB9E5 texel (EXT_texture_shared_exponent, sec. "Encoding"; the kernel's
/// rgb9e5Decode in shared/texture_sample.h): each channel clamped to [0, 65408], rounded to the
/// nearest value of the shared exponent, which the largest channel decides. NaN becomes 0.
std::uint32_t packRgb9e5(glm::vec3 rgb);

}  // namespace vkp
