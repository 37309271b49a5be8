#include "scene/gltf/gltf_json_checks.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>

#include <nlohmann/json.hpp>

#include "io/nesting_depth.hpp"
#include "scene/gltf/gltf_geometry.hpp"

namespace tessera::gltf {

namespace {

using nlohmann::json;

// Every byteOffset, byteLength and byteStride of the document (bufferViews, accessors and their
// sparse parts, buffers, the meshopt extensions' views) outside "extras", which is the user's.
void check_sizes(const json& value, const std::string& where, const std::string& source) {
    if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i) check_sizes(value[i], where + "[" + std::to_string(i) + "]", source);
        return;
    }
    if (!value.is_object()) return;
    for (const auto& [key, member] : value.items()) {
        if (key == "extras") continue;
        if ((key == "byteOffset" || key == "byteLength" || key == "byteStride") && member.is_number() &&
            member.get<double>() < 0)
            fail(source, where + ": \"" + key + "\" is negative (" + member.dump() +
                             "); offsets, lengths and strides are >= 0");
        check_sizes(member, where.empty() ? key : where + "." + key, source);
    }
}

// Morph weights (a mesh's and a node's) are numbers.
void check_weights(const json& document, const char* array_name, const std::string& source) {
    const auto found = document.find(array_name);
    if (found == document.end() || !found->is_array()) return;
    for (std::size_t i = 0; i < found->size(); ++i) {
        const json& item = (*found)[i];
        if (!item.is_object()) continue;
        const auto weights = item.find("weights");
        if (weights == item.end()) continue;
        const bool numbers = weights->is_array() && std::all_of(weights->begin(), weights->end(),
                                                                [](const json& w) { return w.is_number(); });
        if (!numbers) {
            std::string shown = weights->dump();
            if (shown.size() > 24) shown = shown.substr(0, 24) + "...";
            fail(source, std::string(array_name) + "[" + std::to_string(i) +
                             "]: \"weights\" holds something other than numbers (" + shown +
                             "); morph weights are finite numbers");
        }
    }
}

}  // namespace

void check_json_before_parsing(std::span<const std::uint8_t> bytes, bool binary, const std::string& source) {
    std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (binary) {
        const auto u32 = [&](std::size_t at) {
            std::uint32_t v = 0;
            std::memcpy(&v, bytes.data() + at, 4);
            return v;
        };
        if (bytes.size() < 20) fail(source, "invalid glTF binary (.glb): " + std::to_string(bytes.size()) +
                                                " bytes, shorter than its 12-byte header and a chunk header");
        if (u32(4) != 2)
            fail(source, "invalid glTF binary (.glb): version " + std::to_string(u32(4)) + ", expected 2");
        const std::size_t length = std::min<std::size_t>(u32(12), bytes.size() - 20);
        text = text.substr(20, length);
    }
    // First the depth, so that the parsers below (nlohmann's is recursive) never see deeper JSON.
    const io::Depth depth = io::json_nesting_depth(text, io::kMaxJsonDepth);
    if (depth.line != 0)
        fail(source, std::string(binary ? "the JSON chunk's " : "") + "line " + std::to_string(depth.line) +
                         ": JSON nested deeper than " + std::to_string(io::kMaxJsonDepth) +
                         " levels (arrays and objects, e.g. in extras); refused before parsing");
    const json document = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (document.is_discarded() || !document.is_object()) return;  // tinygltf says what is wrong with it
    check_sizes(document, "", source);
    check_weights(document, "meshes", source);
    check_weights(document, "nodes", source);
}

}  // namespace tessera::gltf
