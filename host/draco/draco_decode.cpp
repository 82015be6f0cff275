// Draco decoding (draco_decode.h) with Debian's libdraco: draco::Decoder, attribute values by
// unique id (KHR_draco_mesh_compression: "attributes" maps glTF names to Draco unique ids).
#include "draco/draco_decode.h"

#include <cstring>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

namespace vkp::draco_island {

struct Mesh::Impl {
    std::unique_ptr<draco::Mesh> mesh;
};

Mesh::Mesh() : impl(std::make_unique<Impl>()) {}
Mesh::~Mesh() = default;

std::size_t Mesh::points() const { return impl->mesh->num_points(); }
std::size_t Mesh::faces() const { return impl->mesh->num_faces(); }

std::array<std::uint32_t, 3> Mesh::face(std::size_t f) const {
    const auto& face = impl->mesh->face(draco::FaceIndex(std::uint32_t(f)));
    return {face[0].value(), face[1].value(), face[2].value()};
}

int Mesh::components(std::uint32_t id) const {
    const draco::PointAttribute* a = impl->mesh->GetAttributeByUniqueId(id);
    return a ? int(a->num_components()) : 0;
}

namespace {

template <class T>
bool convertAll(const draco::PointAttribute& a, std::size_t points, int components, std::vector<unsigned char>& out) {
    out.resize(points * std::size_t(components) * sizeof(T));
    T value[4] = {};
    for (std::size_t i = 0; i < points; ++i) {
        if (!a.ConvertValue<T>(a.mapped_index(draco::PointIndex(std::uint32_t(i))), std::int8_t(components), value)) return false;
        std::memcpy(out.data() + i * std::size_t(components) * sizeof(T), value, std::size_t(components) * sizeof(T));
    }
    return true;
}

}  // namespace

bool Mesh::values(std::uint32_t id, Component type, int components, std::vector<unsigned char>& out) const {
    const draco::PointAttribute* a = impl->mesh->GetAttributeByUniqueId(id);
    if (!a || components < 1 || components > 4 || a->num_components() != components) return false;
    const std::size_t n = points();
    const draco::DataType d = a->data_type();
    switch (type) {
    case Component::Float: return convertAll<float>(*a, n, components, out);
    case Component::Int8: return d == draco::DT_INT8 && convertAll<std::int8_t>(*a, n, components, out);
    case Component::Uint8: return d == draco::DT_UINT8 && convertAll<std::uint8_t>(*a, n, components, out);
    case Component::Int16: return d == draco::DT_INT16 && convertAll<std::int16_t>(*a, n, components, out);
    case Component::Uint16: return d == draco::DT_UINT16 && convertAll<std::uint16_t>(*a, n, components, out);
    case Component::Uint32: return d == draco::DT_UINT32 && convertAll<std::uint32_t>(*a, n, components, out);
    }
    return false;
}

std::unique_ptr<Mesh> decode(const std::uint8_t* data, std::size_t size, std::string& error) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
        error = decoded.status().error_msg_string();
        return nullptr;
    }
    auto out = std::make_unique<Mesh>();
    out->impl->mesh = std::move(decoded).value();
    if (!out->impl->mesh) {
        error = "no mesh in the stream";
        return nullptr;
    }
    return out;
}

}  // namespace vkp::draco_island
