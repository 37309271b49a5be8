#include "scene/draco_test_encoder.hpp"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

namespace tessera::test {

DracoEncoded encode_draco_triangles(const float* positions, const float* normals, const float* uvs, const float* tangents,
                                    const std::uint32_t* indices, std::size_t index_count, bool bool_tangents) {
    draco::TriangleSoupMeshBuilder builder;
    const int faces = int(index_count / 3);
    builder.Start(faces);
    const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int normal = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    const int tangent =
        builder.AddAttribute(draco::GeometryAttribute::GENERIC, 4, bool_tangents ? draco::DT_BOOL : draco::DT_FLOAT32);
    static const std::uint8_t kBoolBytes[4] = {93, 1, 0, 200};
    for (int f = 0; f < faces; ++f) {
        const std::uint32_t* c = &indices[std::size_t(f) * 3];
        const draco::FaceIndex face(static_cast<std::uint32_t>(f));
        builder.SetAttributeValuesForFace(position, face, positions + 3 * c[0], positions + 3 * c[1], positions + 3 * c[2]);
        builder.SetAttributeValuesForFace(normal, face, normals + 3 * c[0], normals + 3 * c[1], normals + 3 * c[2]);
        builder.SetAttributeValuesForFace(uv, face, uvs + 2 * c[0], uvs + 2 * c[1], uvs + 2 * c[2]);
        if (bool_tangents) builder.SetAttributeValuesForFace(tangent, face, kBoolBytes, kBoolBytes, kBoolBytes);
        else builder.SetAttributeValuesForFace(tangent, face, tangents + 4 * c[0], tangents + 4 * c[1], tangents + 4 * c[2]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    draco::EncoderBuffer buffer;
    if (!mesh || !encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) return {};
    DracoEncoded result;
    result.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    result.position_id = int(mesh->attribute(position)->unique_id());
    result.normal_id = int(mesh->attribute(normal)->unique_id());
    result.uv_id = int(mesh->attribute(uv)->unique_id());
    result.tangent_id = int(mesh->attribute(tangent)->unique_id());
    return result;
}

}  // namespace tessera::test
