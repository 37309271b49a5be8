#include "scene/gltf/gltf_compression.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <optional>
#include <string_view>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "io/memory_budget.hpp"
#include "scene/gltf/draco_codec.hpp"
#include "scene/gltf/gltf_accessors.hpp"
#include "scene/gltf/gltf_geometry.hpp"
#include "scene/gltf/meshopt_codec_v1.hpp"

namespace tessera::gltf {
namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";
// The ratified successor: the same JSON, plus vertex codec version 1 and the COLOR
// filter (gltfpack -ce khr writes codec version 1), which meshopt_codec_v1.hpp decodes.
constexpr const char* kKhrMeshopt = "KHR_meshopt_compression";
constexpr const char* kMeshoptNames[] = {kMeshopt, kKhrMeshopt};
constexpr const char* kDraco = "KHR_draco_mesh_compression";

// ---- Meshopt fallback buffers, before parsing ---------------------------------------------------

// A placeholder tinygltf accepts (3 zero bytes; an empty data URI it does not).
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AAAA";
constexpr int kPlaceholderBytes = 3;

std::uint32_t read_u32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

void append_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

// Replaces the fallback buffers of `json` (see gltf_compression.hpp); false if
// there were none. In a .glb, buffer 0 without a uri is the BIN chunk.
bool replace_fallback_buffers(nlohmann::json& json, bool binary, std::vector<int>& replaced) {
    if (!json.is_object()) return false;
    const auto buffers = json.find("buffers");
    if (buffers == json.end() || !buffers->is_array()) return false;
    for (std::size_t b = 0; b < buffers->size(); ++b) {
        nlohmann::json& buffer = (*buffers)[b];
        if (!buffer.is_object()) continue;
        bool fallback = !buffer.contains("uri") && (!binary || b > 0);
        const auto extensions = buffer.find("extensions");
        if (extensions != buffer.end() && extensions->is_object()) {
            for (const char* name : kMeshoptNames) {
                const auto meshopt = extensions->find(name);
                if (meshopt != extensions->end() && meshopt->is_object()) {
                    const auto flag = meshopt->find("fallback");
                    fallback = fallback || (flag != meshopt->end() && flag->is_boolean() && flag->get<bool>());
                }
            }
        }
        if (!fallback) continue;
        buffer["uri"] = kPlaceholderUri;
        buffer["byteLength"] = kPlaceholderBytes;
        replaced.push_back(int(b));
    }
    return !replaced.empty();
}

// tinygltf 2.7 refuses a primitive whose indices accessor has no buffer view,
// which is how KHR_draco_mesh_compression files declare them: the indices of
// Draco primitives are dropped before parsing (Draco's faces replace them).
bool drop_draco_indices(nlohmann::json& json) {
    const auto meshes = json.find("meshes");
    if (meshes == json.end() || !meshes->is_array()) return false;
    bool changed = false;
    for (nlohmann::json& mesh : *meshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (nlohmann::json& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !primitive.contains("indices")) continue;
            const auto extensions = primitive.find("extensions");
            if (extensions == primitive.end() || !extensions->is_object() || !extensions->contains(kDraco)) continue;
            primitive.erase("indices");
            changed = true;
        }
    }
    return changed;
}

bool mentions(std::string_view json, const char* name) { return json.find(name) != std::string_view::npos; }

}  // namespace

ParseInput prepare_for_tinygltf(std::span<const std::uint8_t> bytes, bool binary) {
    ParseInput input;
    std::string_view json_text;
    std::size_t json_start = 0, json_length = 0;
    if (binary) {
        // 12-byte header, then the JSON chunk: its length and type, then its bytes.
        if (bytes.size() < 20 || read_u32(bytes.data() + 16) != 0x4E4F534Au) return input;
        json_length = read_u32(bytes.data() + 12);
        json_start = 20;
        if (json_length > bytes.size() - json_start) return input;
    } else {
        json_length = bytes.size();
    }
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()) + json_start, json_length);
    const bool meshopt = mentions(json_text, kMeshopt) || mentions(json_text, kKhrMeshopt),
               draco = mentions(json_text, kDraco);
    if (!meshopt && !draco) return input;
    nlohmann::json json = nlohmann::json::parse(json_text, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.is_object()) return input;
    const bool replaced = meshopt && replace_fallback_buffers(json, binary, input.fallback_buffers);
    const bool dropped = draco && drop_draco_indices(json);
    if (!replaced && !dropped) return input;
    // Strings are kept byte for byte where valid; dump() must not throw on the rest.
    std::string patched = json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (!binary) {
        input.bytes.assign(patched.begin(), patched.end());
        return input;
    }
    while (patched.size() % 4 != 0) patched += ' ';
    const std::size_t rest = json_start + json_length;  // the BIN chunk and anything after it, verbatim
    input.bytes = {'g', 'l', 'T', 'F'};
    append_u32(input.bytes, read_u32(bytes.data() + 4));
    append_u32(input.bytes, std::uint32_t(12 + 8 + patched.size() + (bytes.size() - rest)));
    append_u32(input.bytes, std::uint32_t(patched.size()));
    append_u32(input.bytes, 0x4E4F534Au);
    input.bytes.insert(input.bytes.end(), patched.begin(), patched.end());
    input.bytes.insert(input.bytes.end(), bytes.begin() + std::ptrdiff_t(rest), bytes.end());
    return input;
}

namespace {

// ---- Extension fields ----------------------------------------------------------------------------

// A whole number >= 0 from an extension object; `fallback` when absent (none: required).
std::size_t size_field(const tinygltf::Value& object, const char* key, std::optional<std::size_t> fallback,
                       const std::string& what, const std::string& source) {
    if (!object.Has(key)) {
        if (fallback) return *fallback;
        fail(source, what + " has no '" + key + "'");
    }
    const tinygltf::Value& value = object.Get(key);
    const double number = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
    if (!(number >= 0.0 && number <= 9007199254740992.0) || number != std::floor(number))
        fail(source, what + " '" + key + "' is not a whole number >= 0");
    return std::size_t(number);
}

std::string string_field(const tinygltf::Value& object, const char* key, const char* fallback, const std::string& what,
                         const std::string& source) {
    if (!object.Has(key)) {
        if (fallback) return fallback;
        fail(source, what + " has no '" + key + "'");
    }
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsString()) fail(source, what + " '" + key + "' is not a string");
    return value.Get<std::string>();
}

// Bytes [offset, offset + length) of buffer `buffer_index`, checked.
const unsigned char* buffer_range(const tinygltf::Model& model, std::size_t buffer_index, std::size_t offset,
                                  std::size_t length, const std::string& what, const std::string& source) {
    if (buffer_index >= model.buffers.size())
        fail(source, what + " uses buffer " + std::to_string(buffer_index) + " but the file has " +
                         std::to_string(model.buffers.size()));
    const std::vector<unsigned char>& data = model.buffers[buffer_index].data;
    std::size_t end = 0;
    if (__builtin_add_overflow(offset, length, &end) || end > data.size())
        fail(source, what + " spans bytes " + std::to_string(offset) + " + " + std::to_string(length) +
                         ", past the end of buffer " + std::to_string(buffer_index) + " (" +
                         std::to_string(data.size()) + " bytes)");
    return data.data() + offset;
}

// Puts `bytes` in a new buffer of the model; returns its index.
int add_buffer(tinygltf::Model& model, std::vector<unsigned char> bytes) {
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes);
    model.buffers.push_back(std::move(buffer));
    return int(model.buffers.size() - 1);
}

// ---- EXT_meshopt_compression ---------------------------------------------------------------------

// The most bytes a valid stream of `compressed` bytes can decode to. ATTRIBUTES
// spends at least 2 header bits per 16 bytes of output (64×); TRIANGLES one code
// byte per triangle (12 bytes of u32 indices); INDICES a byte per index. Checked
// before allocating, so that a small file cannot ask for gigabytes.
constexpr std::size_t kMaxMeshoptExpansion = 64;
// Codec version 1 can store a block's byte position as "all deltas zero" in 2 bits: a block of
// n <= 256 elements costs at least its control header (stride / 4 bytes), at most 4n = 1024×.
constexpr std::size_t kMaxMeshoptV1Expansion = 1024;

void decode_meshopt_view(tinygltf::Model& model, std::size_t view_index, const std::vector<int>& fallback_buffers,
                         const std::string& source, const char* extension) {
    tinygltf::BufferView& view = model.bufferViews[view_index];
    const tinygltf::Value& ext = view.extensions.at(extension);
    const std::string what = "bufferView " + std::to_string(view_index) + " " + extension;
    if (!ext.IsObject()) fail(source, what + " is not an object");
    const std::size_t buffer = size_field(ext, "buffer", std::nullopt, what, source);
    const std::size_t offset = size_field(ext, "byteOffset", 0, what, source);
    const std::size_t length = size_field(ext, "byteLength", std::nullopt, what, source);
    const std::size_t stride = size_field(ext, "byteStride", std::nullopt, what, source);
    const std::size_t count = size_field(ext, "count", std::nullopt, what, source);
    const std::string mode = string_field(ext, "mode", nullptr, what, source);
    const std::string filter = string_field(ext, "filter", "NONE", what, source);

    // The extension's validity rules.
    if (mode != "ATTRIBUTES" && mode != "TRIANGLES" && mode != "INDICES")
        fail(source, what + " mode is '" + mode + "', expected ATTRIBUTES, TRIANGLES or INDICES");
    const bool khr = std::string_view(extension) == kKhrMeshopt;  // COLOR is KHR_meshopt_compression's only
    if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL" &&
        !(khr && filter == "COLOR"))
        fail(source, what + " filter is '" + filter + "', expected NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL" +
                         (khr ? " or COLOR" : " (COLOR is KHR_meshopt_compression's)"));
    if (mode == "ATTRIBUTES" && (stride == 0 || stride % 4 != 0 || stride > 256))
        fail(source, what + " byteStride is " + std::to_string(stride) + "; ATTRIBUTES needs a multiple of 4 up to 256");
    if (mode != "ATTRIBUTES" && stride != 2 && stride != 4)
        fail(source, what + " byteStride is " + std::to_string(stride) + "; " + mode + " needs 2 or 4");
    if (mode != "ATTRIBUTES" && filter != "NONE")
        fail(source, what + " has filter " + filter + " with mode " + mode + "; filters are for ATTRIBUTES");
    if (mode == "TRIANGLES" && count % 3 != 0)
        fail(source, what + " has " + std::to_string(count) + " TRIANGLES indices, not a multiple of 3");
    if (((filter == "OCTAHEDRAL" || filter == "COLOR") && stride != 4 && stride != 8) ||
        (filter == "QUATERNION" && stride != 8))
        fail(source, what + " byteStride is " + std::to_string(stride) + ", which filter " + filter + " does not allow");
    if (view.byteStride != 0 && view.byteStride != stride)
        fail(source, what + " byteStride " + std::to_string(stride) + " differs from the bufferView's " +
                         std::to_string(view.byteStride));
    std::size_t decoded_size = 0;
    if (__builtin_mul_overflow(count, stride, &decoded_size) || decoded_size != view.byteLength)
        fail(source, what + ": count " + std::to_string(count) + " × byteStride " + std::to_string(stride) +
                         " is not the bufferView's byteLength " + std::to_string(view.byteLength));
    if (std::find(fallback_buffers.begin(), fallback_buffers.end(), int(buffer)) != fallback_buffers.end())
        fail(source, what + " reads its compressed data from buffer " + std::to_string(buffer) +
                         ", a fallback buffer without data");
    const unsigned char* compressed = buffer_range(model, buffer, offset, length, what, source);
    // ATTRIBUTES streams whose header is not codec version 0's go to meshopt_codec_v1.hpp, which
    // decodes version 1 and says what is wrong with anything else; the rest to libmeshoptimizer.
    const bool codec_v1 = mode == "ATTRIBUTES" && length > 0 && compressed[0] != 0xa0;
    if (decoded_size / (codec_v1 ? kMaxMeshoptV1Expansion : kMaxMeshoptExpansion) > length)
        fail(source, what + " is too short: " + std::to_string(length) + " bytes cannot hold " +
                         std::to_string(count) + " elements of " + std::to_string(stride) + " bytes");

    try {
        io::check_memory(decoded_size, what + " decoded");
    } catch (const io::MemoryBudgetError& e) {
        fail(source, e.what());
    }
    std::vector<unsigned char> decoded(decoded_size);
    int status = 0;
    if (codec_v1) {
        const std::string why = decode_meshopt_attributes({compressed, length}, count, stride, decoded);
        if (!why.empty()) fail(source, what + ": the ATTRIBUTES data (" + std::to_string(length) + " bytes): " + why);
    } else if (mode == "ATTRIBUTES") status = meshopt_decodeVertexBuffer(decoded.data(), count, stride, compressed, length);
    else if (mode == "TRIANGLES") status = meshopt_decodeIndexBuffer(decoded.data(), count, stride, compressed, length);
    else status = meshopt_decodeIndexSequence(decoded.data(), count, stride, compressed, length);
    if (status != 0)
        fail(source, what + ": the " + mode + " data (" + std::to_string(length) + " bytes) does not decode to " +
                         std::to_string(count) + " elements of " + std::to_string(stride) +
                         " bytes (meshoptimizer error " + std::to_string(status) + ")");
    if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data(), count, stride);
    else if (filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data(), count, stride);
    else if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data(), count, stride);
    else if (filter == "COLOR") {
        const std::string why = decode_meshopt_color_filter(decoded, count, stride);
        if (!why.empty()) fail(source, what + ": " + why);
    }

    const int decoded_buffer = add_buffer(model, std::move(decoded));
    tinygltf::BufferView& same_view = model.bufferViews[view_index];
    same_view.buffer = decoded_buffer;
    same_view.byteOffset = 0;
    same_view.extensions.erase(extension);
}

void decode_meshopt(tinygltf::Model& model, const std::vector<int>& fallback_buffers, const std::string& source) {
    for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
        if (model.bufferViews[v].extensions.count(kMeshopt)) {
            decode_meshopt_view(model, v, fallback_buffers, source, kMeshopt);
        } else if (model.bufferViews[v].extensions.count(kKhrMeshopt)) {
            decode_meshopt_view(model, v, fallback_buffers, source, kKhrMeshopt);
        } else if (std::find(fallback_buffers.begin(), fallback_buffers.end(), model.bufferViews[v].buffer) !=
                   fallback_buffers.end()) {
            fail(source, "bufferView " + std::to_string(v) + " reads buffer " +
                             std::to_string(model.bufferViews[v].buffer) + ", a " + kMeshopt +
                             " fallback buffer without data, but is not compressed");
        }
    }
}

// ---- KHR_draco_mesh_compression ------------------------------------------------------------------

// One decoded primitive: the bytes of its attributes and indices, and the
// accessors (copies of the primitive's, pointing into those bytes) to use.
struct DecodedDraco {
    std::size_t mesh = 0, primitive = 0;
    std::vector<unsigned char> bytes;
    struct Part {
        std::string attribute;  // empty for the indices
        tinygltf::Accessor accessor;
        std::size_t offset = 0, length = 0;  // in bytes
    };
    std::vector<Part> parts;
};

std::string primitive_label(const tinygltf::Model& model, std::size_t mesh, std::size_t primitive) {
    std::string label = "meshes[" + std::to_string(mesh) + "]";
    if (!model.meshes[mesh].name.empty()) label += " '" + model.meshes[mesh].name + "'";
    return label + " primitives[" + std::to_string(primitive) + "]";
}

DecodedDraco decode_draco_primitive(const tinygltf::Model& model, std::size_t mesh_index, std::size_t primitive_index,
                                    const std::string& source) {
    const tinygltf::Primitive& primitive = model.meshes[mesh_index].primitives[primitive_index];
    const std::string label = primitive_label(model, mesh_index, primitive_index);
    const std::string what = label + " " + kDraco;
    const tinygltf::Value& ext = primitive.extensions.at(kDraco);
    if (!ext.IsObject()) fail(source, what + " is not an object");
    const std::size_t view_index = size_field(ext, "bufferView", std::nullopt, what, source);
    if (view_index >= model.bufferViews.size())
        fail(source, what + " uses bufferView " + std::to_string(view_index) + " but the file has " +
                         std::to_string(model.bufferViews.size()));
    const tinygltf::BufferView& view = model.bufferViews[view_index];
    const std::string view_what = "bufferView " + std::to_string(view_index) + " (for " + what + ")";
    if (view.buffer < 0) fail(source, view_what + " has no buffer");
    const unsigned char* data = buffer_range(model, std::size_t(view.buffer), view.byteOffset, view.byteLength, view_what, source);

    const auto declared = [&](int accessor_index, const std::string& name) -> const tinygltf::Accessor& {
        if (accessor_index < 0 || std::size_t(accessor_index) >= model.accessors.size())
            fail(source, label + " " + name + " uses accessor " + std::to_string(accessor_index) +
                             " but the file has " + std::to_string(model.accessors.size()) + " accessors");
        return model.accessors[std::size_t(accessor_index)];
    };

    // Attributes: the extension maps names to Draco's attribute ids.
    const tinygltf::Value& attributes = ext.Get("attributes");
    if (!attributes.IsObject()) fail(source, what + " has no 'attributes' object");
    DecodedDraco result;
    result.mesh = mesh_index;
    result.primitive = primitive_index;
    std::vector<draco_codec::AttributeRequest> requests;
    std::vector<int> accessor_indices;
    for (const std::string& name : attributes.Keys()) {
        const std::string attribute_what = what + " attribute " + name;
        const auto found = primitive.attributes.find(name);
        if (found == primitive.attributes.end())
            fail(source, attribute_what + " is not among the primitive's attributes");
        const std::size_t id = size_field(attributes, name.c_str(), std::nullopt, what + " attributes", source);
        DecodedDraco::Part part;
        part.attribute = name;
        part.accessor = declared(found->second, name);
        const int components = component_count(part.accessor.type);
        if (components < 1 || components > 4 || component_size(part.accessor.componentType) == 0)
            fail(source, attribute_what + " (accessor " + std::to_string(found->second) + ") is " +
                             type_name(part.accessor.type) + " of " + component_name(part.accessor.componentType) +
                             "; Draco attributes are scalars or vectors");
        if (id > 0xFFFFFFFFu) fail(source, attribute_what + " has Draco id " + std::to_string(id) + ", not a 32-bit id");
        requests.push_back({std::uint32_t(id), part.accessor.componentType, components});
        result.parts.push_back(std::move(part));
    }

    const draco_codec::DecodedMesh decoded = draco_codec::decode_draco_mesh(data, view.byteLength, requests);
    if (!decoded.error.empty()) {
        if (decoded.failed_attribute >= 0)
            fail(source, what + " attribute " + result.parts[std::size_t(decoded.failed_attribute)].attribute + ": " +
                             decoded.error);
        fail(source, what + ": the Draco data in bufferView " + std::to_string(view_index) + " (" +
                         std::to_string(view.byteLength) + " bytes) does not decode: " + decoded.error);
    }

    // Indices: the Draco faces, as u32, first in the bytes; the attributes after them.
    DecodedDraco::Part indices;
    if (primitive.indices >= 0) indices.accessor = declared(primitive.indices, "indices");
    indices.accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.accessor.type = TINYGLTF_TYPE_SCALAR;
    indices.accessor.normalized = false;
    indices.accessor.count = decoded.indices.size();
    indices.length = decoded.indices.size() * sizeof(std::uint32_t);
    result.bytes.resize(indices.length);
    if (indices.length) std::memcpy(result.bytes.data(), decoded.indices.data(), indices.length);
    for (std::size_t r = 0; r < result.parts.size(); ++r) {
        DecodedDraco::Part& part = result.parts[r];
        part.accessor.count = decoded.points;  // what Draco decoded, whatever the file declared (encoders may split points)
        part.offset = result.bytes.size();
        part.length = decoded.attributes[r].size();
        result.bytes.insert(result.bytes.end(), decoded.attributes[r].begin(), decoded.attributes[r].end());
        while (result.bytes.size() % 4 != 0) result.bytes.push_back(0);
    }
    result.parts.insert(result.parts.begin(), std::move(indices));
    for (DecodedDraco::Part& part : result.parts) {
        part.accessor.bufferView = -1;  // set when the parts are added to the model
        part.accessor.byteOffset = 0;
        part.accessor.sparse = {};
    }
    return result;
}

void decode_draco(tinygltf::Model& model, const std::string& source) {
    std::vector<std::pair<std::size_t, std::size_t>> compressed;  // (mesh, primitive)
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            const tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
            if (!primitive.extensions.count(kDraco)) continue;
            const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
            if (mode == TINYGLTF_MODE_TRIANGLES) {
                compressed.emplace_back(m, p);
            } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
                fail(source, primitive_label(model, m, p) + " " + kDraco + " on a primitive of mode " +
                                 std::to_string(mode) + "; Draco meshes are triangle lists (mode 4)");
            }  // points and lines are not drawn: left compressed
        }
    }
    if (compressed.empty()) return;
    // Decoded in parallel (Draco is slow); the first failure in file order is the one reported.
    std::vector<DecodedDraco> decoded(compressed.size());
    std::vector<std::exception_ptr> errors(compressed.size());
    tbb::parallel_for(std::size_t(0), compressed.size(), [&](std::size_t i) {
        try {
            decoded[i] = decode_draco_primitive(model, compressed[i].first, compressed[i].second, source);
        } catch (...) {
            errors[i] = std::current_exception();
        }
    });
    for (const std::exception_ptr& error : errors)
        if (error) std::rethrow_exception(error);

    for (DecodedDraco& primitive_data : decoded) {
        const int buffer = add_buffer(model, std::move(primitive_data.bytes));
        tinygltf::Primitive& primitive = model.meshes[primitive_data.mesh].primitives[primitive_data.primitive];
        for (DecodedDraco::Part& part : primitive_data.parts) {
            tinygltf::BufferView view;
            view.buffer = buffer;
            view.byteOffset = part.offset;
            view.byteLength = part.length;
            model.bufferViews.push_back(view);
            part.accessor.bufferView = int(model.bufferViews.size() - 1);
            model.accessors.push_back(std::move(part.accessor));
            const int accessor = int(model.accessors.size() - 1);
            if (part.attribute.empty()) primitive.indices = accessor;
            else primitive.attributes[part.attribute] = accessor;
        }
        primitive.extensions.erase(kDraco);
    }
}

}  // namespace

void decode_compressed_geometry(tinygltf::Model& model, const std::string& source,
                                const std::vector<int>& fallback_buffers) {
    decode_meshopt(model, fallback_buffers, source);
    decode_draco(model, source);
}

}  // namespace tessera::gltf
