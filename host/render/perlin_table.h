// The Perlin noise table of JSON textures (shaders/shared/solid_texture.h): the book's 256 random
// unit gradients and three permutations ("Ray Tracing: The Next Week", sec. 5), made once on the
// host from a fixed seed and uploaded, so that the host's and the device's noise read the same
// numbers.
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace vkp {

/// gpu::PERLIN_POINTS texels: (gradient.xyz as float bits, permX | permY << 8 | permZ << 16).
/// Gradients: random points of the cube [-1, 1]^3 made unit length (the book's
/// unit_vector(vec3::random(-1, 1))); permutations: Fisher-Yates shuffles of 0..255 (the book's
/// perlin_generate_perm). The same table on every machine (std::mt19937, seed fixed).
std::vector<glm::uvec4> perlinTable();

}  // namespace vkp
