// KHR_meshopt_compression as gltfpack -ce khr writes it (issue #31): attribute codec
// version 1 (and, with -cc, filter COLOR), decoded by meshopt_codec_v1.cpp, gives the
// accessors the same model exported with gltfpack -c (EXT_meshopt_compression, codec
// version 0, decoded by Debian's libmeshoptimizer) has: byte for byte where both use
// the same quantization. Files: tests/scene/models/exported/ (README there).
#include <doctest/doctest.h>

#include <cstdint>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf/gltf_compression.hpp"
#include "tessera/scene.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

struct Loaded {
    tinygltf::Model model;
    std::set<int> attribute_codec_versions;  // of the ATTRIBUTES streams, read before decoding
    std::set<std::string> filters;
};

std::vector<std::uint8_t> file_bytes(const std::string& name) {
    const std::filesystem::path file = test::source_dir() / "tests" / "scene" / "models" / "exported" / name;
    std::ifstream in(file, std::ios::binary);
    std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    REQUIRE(!bytes.empty());
    return bytes;
}

// Parsed (tinygltf), not yet decoded.
Loaded load_parsed(const std::vector<std::uint8_t>& bytes, std::vector<int>& fallback_buffers) {
    const gltf::ParseInput input = gltf::prepare_for_tinygltf(bytes, true);
    const std::vector<std::uint8_t>& parsed = input.bytes.empty() ? bytes : input.bytes;
    fallback_buffers = input.fallback_buffers;
    Loaded loaded;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    REQUIRE(loader.LoadBinaryFromMemory(&loaded.model, &err, &warn, parsed.data(), unsigned(parsed.size()), ""));
    for (const tinygltf::BufferView& view : loaded.model.bufferViews) {
        for (const char* extension : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
            if (!view.extensions.count(extension)) continue;
            const tinygltf::Value& ext = view.extensions.at(extension);
            if (ext.Has("filter")) loaded.filters.insert(ext.Get("filter").Get<std::string>());
            if (ext.Get("mode").Get<std::string>() != "ATTRIBUTES") continue;
            const int buffer = ext.Get("buffer").GetNumberAsInt();
            const int offset = ext.Has("byteOffset") ? ext.Get("byteOffset").GetNumberAsInt() : 0;
            loaded.attribute_codec_versions.insert(loaded.model.buffers.at(std::size_t(buffer)).data.at(std::size_t(offset)) & 0x0f);
        }
    }
    return loaded;
}

Loaded load_decoded(const std::string& name) {
    std::vector<int> fallback_buffers;
    Loaded loaded = load_parsed(file_bytes(name), fallback_buffers);
    gltf::decode_compressed_geometry(loaded.model, name, fallback_buffers);
    return loaded;
}

std::string decode_error(tinygltf::Model& model, const std::vector<int>& fallback_buffers) {
    try {
        gltf::decode_compressed_geometry(model, "bad.glb", fallback_buffers);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(decoded)";
}

// Accessor `a`'s elements, packed (no stride).
std::vector<std::uint8_t> accessor_bytes(const tinygltf::Model& model, std::size_t a) {
    const tinygltf::Accessor& accessor = model.accessors.at(a);
    const tinygltf::BufferView& view = model.bufferViews.at(std::size_t(accessor.bufferView));
    const std::size_t element = std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType)) *
                                            tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type)));
    const std::size_t stride = view.byteStride ? view.byteStride : element;
    const std::vector<unsigned char>& data = model.buffers.at(std::size_t(view.buffer)).data;
    std::vector<std::uint8_t> bytes;
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const std::size_t at = view.byteOffset + accessor.byteOffset + i * stride;
        REQUIRE(at + element <= data.size());
        bytes.insert(bytes.end(), data.begin() + std::ptrdiff_t(at), data.begin() + std::ptrdiff_t(at + element));
    }
    return bytes;
}

// The accessor of each primitive's COLOR_0.
std::set<std::size_t> color_accessors(const tinygltf::Model& model) {
    std::set<std::size_t> colors;
    for (const tinygltf::Mesh& mesh : model.meshes)
        for (const tinygltf::Primitive& primitive : mesh.primitives)
            if (const auto c = primitive.attributes.find("COLOR_0"); c != primitive.attributes.end()) colors.insert(std::size_t(c->second));
    return colors;
}

}  // namespace

TEST_CASE("gltfpack -ce khr files decode to the accessors of their gltfpack -c twins") {
    struct Pair {
        const char* ext;  // gltfpack -c
        const char* khr;  // gltfpack -ce khr, or -cc -ce khr
        std::set<std::string> khr_filters;
    };
    const Pair pairs[] = {
        {"morph_c.glb", "morph_khr.glb", {}},
        {"texcoord_c.glb", "texcoord_khr.glb", {}},
        // -cc: normals through filter OCTAHEDRAL (exact for this model's axis-aligned ones) and colours through COLOR.
        {"vcolor_c.glb", "vcolor_cc_khr.glb", {"OCTAHEDRAL", "COLOR"}},
    };
    for (const Pair& pair : pairs) {
        CAPTURE(pair.khr);
        const Loaded ext = load_decoded(pair.ext), khr = load_decoded(pair.khr);
        CHECK(ext.attribute_codec_versions == std::set<int>{0});
        CHECK(khr.attribute_codec_versions == std::set<int>{1});  // what this test is about
        CHECK(khr.filters == pair.khr_filters);
        REQUIRE(ext.model.accessors.size() == khr.model.accessors.size());
        const std::set<std::size_t> colors = color_accessors(khr.model);
        CHECK(colors.empty() == !pair.khr_filters.count("COLOR"));
        for (std::size_t a = 0; a < ext.model.accessors.size(); ++a) {
            CAPTURE(a);
            REQUIRE(ext.model.accessors[a].componentType == khr.model.accessors[a].componentType);
            REQUIRE(ext.model.accessors[a].type == khr.model.accessors[a].type);
            const std::vector<std::uint8_t> want = accessor_bytes(ext.model, a), got = accessor_bytes(khr.model, a);
            REQUIRE(want.size() == got.size());
            if (!colors.count(a)) {
                CHECK(got == want);
                continue;
            }
            // COLOR re-quantizes the 8-bit colours through YCoCg: within one step.
            REQUIRE(ext.model.accessors[a].componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
            int worst = 0;
            for (std::size_t i = 0; i < want.size(); ++i) worst = std::max(worst, std::abs(int(got[i]) - int(want[i])));
            CHECK(worst <= 1);
        }
    }
}

TEST_CASE("gltfpack -ce khr files: a damaged stream is refused naming the buffer view, and COLOR is KHR's only") {
    std::vector<int> fallback_buffers;
    SUBCASE("a channel mode byte (the stream's last) that codec version 1 does not have") {
        Loaded loaded = load_parsed(file_bytes("morph_khr.glb"), fallback_buffers);
        const tinygltf::Value& ext = loaded.model.bufferViews.at(0).extensions.at("KHR_meshopt_compression");
        const std::size_t end = std::size_t(ext.Get("byteOffset").GetNumberAsInt() + ext.Get("byteLength").GetNumberAsInt());
        loaded.model.buffers.at(std::size_t(ext.Get("buffer").GetNumberAsInt())).data.at(end - 1) = 0x03;
        CHECK(decode_error(loaded.model, fallback_buffers) ==
              "bad.glb: bufferView 0 KHR_meshopt_compression: the ATTRIBUTES data (" +
                  std::to_string(ext.Get("byteLength").GetNumberAsInt()) +
                  " bytes): channel 0 has mode byte 3 (modes are 0, 1 and 2; only mode 2 has a rotation)");
    }
    SUBCASE("one byte fewer: the tail is not where the blocks end") {
        Loaded loaded = load_parsed(file_bytes("morph_khr.glb"), fallback_buffers);
        tinygltf::Value::Object ext = loaded.model.bufferViews.at(0).extensions.at("KHR_meshopt_compression").Get<tinygltf::Value::Object>();
        ext["byteLength"] = tinygltf::Value(ext["byteLength"].GetNumberAsInt() - 1);
        loaded.model.bufferViews.at(0).extensions["KHR_meshopt_compression"] = tinygltf::Value(ext);
        CHECK(decode_error(loaded.model, fallback_buffers).find("bad.glb: bufferView 0 KHR_meshopt_compression: the ATTRIBUTES data (") == 0);
    }
    SUBCASE("filter COLOR under EXT_meshopt_compression's name (the same length in the JSON)") {
        std::vector<std::uint8_t> bytes = file_bytes("vcolor_cc_khr.glb");
        const std::string khr = "KHR_meshopt_compression";
        for (auto at = std::search(bytes.begin(), bytes.end(), khr.begin(), khr.end()); at != bytes.end();
             at = std::search(at, bytes.end(), khr.begin(), khr.end()))
            std::copy_n("EXT", 3, at);
        Loaded loaded = load_parsed(bytes, fallback_buffers);
        const std::string error = decode_error(loaded.model, fallback_buffers);
        CHECK(error.find("bad.glb: bufferView ") == 0);
        CHECK(error.find(" EXT_meshopt_compression filter is 'COLOR', expected NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL "
                         "(COLOR is KHR_meshopt_compression's)") != std::string::npos);
    }
}
