#include "scene/gltf/draco_codec.hpp"

#include <cstring>
#include <memory>
#include <string>

#include <draco/compression/decode.h>

namespace tessera::draco_codec {
namespace {

template <typename T>
bool convert_point(const draco::PointAttribute& attribute, draco::PointIndex point, int components, unsigned char* out) {
    T values[4];
    if (!attribute.ConvertValue<T>(attribute.mapped_index(point), std::int8_t(components), values)) return false;
    std::memcpy(out, values, sizeof(T) * std::size_t(components));
    return true;
}

// Bytes per component of a glTF component type; 0 for others.
std::size_t component_size(int component_type) {
    switch (component_type) {
        case 5120: case 5121: return 1;
        case 5122: case 5123: return 2;
        case 5125: case 5126: return 4;
        default: return 0;
    }
}

}  // namespace

DecodedMesh decode_draco_mesh(const unsigned char* data, std::size_t size, const std::vector<AttributeRequest>& requests) {
    DecodedMesh result;
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
        result.error = decoded.status().error_msg_string();
        if (result.error.empty()) result.error = "Draco reports no reason";
        return result;
    }
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) {
        result.error = "it holds no mesh";
        return result;
    }
    result.points = mesh->num_points();
    result.indices.resize(std::size_t(mesh->num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
        const draco::Mesh::Face& face = mesh->face(f);
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t index = face[corner].value();
            if (index >= result.points) {
                result.error = "a triangle refers to point " + std::to_string(index) + " of " + std::to_string(result.points);
                return result;
            }
            result.indices[3 * std::size_t(f.value()) + std::size_t(corner)] = index;
        }
    }
    for (std::size_t r = 0; r < requests.size(); ++r) {
        const AttributeRequest& request = requests[r];
        const auto fail = [&](std::string message) {
            result.error = std::move(message);
            result.failed_attribute = int(r);
            return result;
        };
        const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(request.unique_id);
        if (!attribute) return fail("the Draco mesh has no attribute with id " + std::to_string(request.unique_id));
        // Only number types convert: Draco's conversion reads a bool attribute's
        // bytes as C++ bools, and any byte but 0 and 1 is undefined behaviour there.
        if (attribute->data_type() <= draco::DT_INVALID || attribute->data_type() >= draco::DT_BOOL)
            return fail("the Draco attribute holds " +
                        std::string(attribute->data_type() == draco::DT_BOOL ? "bool values" : "values of no number type") +
                        ", which no glTF accessor holds");
        if (attribute->num_components() != request.components)
            return fail("the Draco attribute has " + std::to_string(attribute->num_components()) + " components, the accessor " +
                        std::to_string(request.components));
        const std::size_t element_bytes = component_size(request.component_type) * std::size_t(request.components);
        if (element_bytes == 0 || request.components < 1 || request.components > 4)
            return fail("unsupported component type " + std::to_string(request.component_type));
        std::vector<unsigned char> bytes(result.points * element_bytes);
        for (draco::PointIndex p(0); p < mesh->num_points(); ++p) {
            unsigned char* out = bytes.data() + std::size_t(p.value()) * element_bytes;
            bool converted = false;
            switch (request.component_type) {
                case 5126: converted = convert_point<float>(*attribute, p, request.components, out); break;
                case 5120: converted = convert_point<std::int8_t>(*attribute, p, request.components, out); break;
                case 5121: converted = convert_point<std::uint8_t>(*attribute, p, request.components, out); break;
                case 5122: converted = convert_point<std::int16_t>(*attribute, p, request.components, out); break;
                case 5123: converted = convert_point<std::uint16_t>(*attribute, p, request.components, out); break;
                case 5125: converted = convert_point<std::uint32_t>(*attribute, p, request.components, out); break;
                default: break;
            }
            if (!converted) return fail("point " + std::to_string(p.value()) + " does not convert to the accessor's type");
        }
        result.attributes.push_back(std::move(bytes));
    }
    return result;
}

}  // namespace tessera::draco_codec
