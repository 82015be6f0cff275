// Draco encoding for the compression tests (test_gltf_compression.cpp), built as an island of its
// own (cmake/DracoIsland.cmake, every libdraco symbol local) next to the renderer's decoder.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vkp::draco_test {

struct Encoded {
    std::vector<std::uint8_t> bytes;  ///< the Draco bitstream
    std::size_t points = 0;           ///< decoded vertex count (after Draco's deduplication)
    std::uint32_t position = 0, normal = 0, uv = 0;  ///< unique ids of the three attributes
    std::string error;                ///< non-empty: encoding failed
};

/// Encode an indexed triangle mesh (positions and normals 3 floats, UVs 2 floats per vertex).
/// quantBits 0: no quantisation (lossless); otherwise positions quantBits, normals 10, UVs 12
/// bits. method: -1 Draco's choice (Edgebreaker), else draco::MESH_*_ENCODING.
Encoded encode(const float* pos, const float* nrm, const float* uv, const std::uint32_t* indices, std::size_t triangles,
               int quantBits, int method);

/// draco::MESH_SEQUENTIAL_ENCODING (the test keeps Draco's headers out of its own file).
int sequentialMethod();

}  // namespace vkp::draco_test
