// Draco mesh decoding behind an interface free of Draco's types: the implementation and the parts
// of Debian's libdraco.a it needs are joined into one object (cmake/DracoIsland.cmake), so that
// libdraco's private copy of tinygltf and stb never meets the rest of the program.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vkp::draco_island {

/// The component types a glTF accessor can ask decoded values in.
enum class Component { Float, Int8, Uint8, Int16, Uint16, Uint32 };

/// One decoded Draco mesh (KHR_draco_mesh_compression's bitstream).
class Mesh {
public:
    Mesh();
    ~Mesh();
    Mesh(const Mesh&) = delete;
    Mesh& operator=(const Mesh&) = delete;

    std::size_t points() const;  ///< vertices (glTF accessor count of every attribute)
    std::size_t faces() const;   ///< triangles
    std::array<std::uint32_t, 3> face(std::size_t f) const;  ///< point indices, the file's winding
    /// Components of the attribute with Draco unique id `id`; 0 when the mesh has no such attribute.
    int components(std::uint32_t id) const;
    /// Every point's value of attribute id, converted to `type`, `components` per point, little
    /// endian. Float takes any Draco type (normalized integers normalized); an integer type must
    /// be the attribute's own type. False when that is not possible.
    bool values(std::uint32_t id, Component type, int components, std::vector<unsigned char>& out) const;

    struct Impl;
    std::unique_ptr<Impl> impl;
};

/// Decode size bytes of a Draco mesh bitstream; null with a reason in error when it does not decode.
std::unique_ptr<Mesh> decode(const std::uint8_t* data, std::size_t size, std::string& error);

}  // namespace vkp::draco_island
