// Draco encoding for the tests (draco_encode.h), with Debian's libdraco.
#include "draco_encode.h"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

namespace vkp::draco_test {

Encoded encode(const float* pos, const float* nrm, const float* uv, const std::uint32_t* indices, std::size_t triangles,
               int quantBits, int method) {
    Encoded out;
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(int(triangles));
    const int p = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int n = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int t = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (std::size_t f = 0; f < triangles; ++f) {
        const std::uint32_t* c = indices + 3 * f;
        const draco::FaceIndex face{std::uint32_t(f)};
        builder.SetAttributeValuesForFace(p, face, pos + 3 * c[0], pos + 3 * c[1], pos + 3 * c[2]);
        builder.SetAttributeValuesForFace(n, face, nrm + 3 * c[0], nrm + 3 * c[1], nrm + 3 * c[2]);
        builder.SetAttributeValuesForFace(t, face, uv + 2 * c[0], uv + 2 * c[1], uv + 2 * c[2]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    if (!mesh) {
        out.error = "TriangleSoupMeshBuilder::Finalize failed";
        return out;
    }
    draco::Encoder encoder;
    if (quantBits > 0) {
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, quantBits);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    }
    if (method >= 0) encoder.SetEncodingMethod(method);
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
    if (!status.ok()) {
        out.error = status.error_msg_string();
        return out;
    }
    out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    out.points = mesh->num_points();
    out.position = mesh->attribute(p)->unique_id();
    out.normal = mesh->attribute(n)->unique_id();
    out.uv = mesh->attribute(t)->unique_id();
    return out;
}

int sequentialMethod() { return draco::MESH_SEQUENTIAL_ENCODING; }

}  // namespace vkp::draco_test
