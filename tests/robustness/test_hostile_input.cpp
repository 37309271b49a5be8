// Hostile glTF files and images in process (issue 35): URIs out of the model's
// folder, node cycles, GLB versions, nesting depth, negative offsets,
// amplification past the memory budget, image headers claiming more than the
// data holds. tests/robustness/hostile/ runs the same kinds through the binary.
#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "io/memory_budget.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "tessera/scene.hpp"
#include "test_paths.hpp"
#include "texture/texture.hpp"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

// A triangle whose buffer is `buffer_uri`, plus what `more` adds to the top-level object.
std::string triangle_gltf(const std::string& buffer_uri, const std::string& more = "",
                          const std::string& accessor_extra = "", const std::string& nodes = R"([{"mesh": 0}])",
                          bool scenes = true) {
    return R"({"asset": {"version": "2.0"},)" + std::string(scenes ? R"("scenes": [{"nodes": [0]}],)" : "") +
           R"("nodes": )" + nodes + R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "buffers": [{"byteLength": 36, "uri": ")" + buffer_uri + R"("}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, )" + accessor_extra + R"("componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}])" + more + "}";
}

const char* kTriangleData = "data:application/octet-stream;base64,"
                            "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";

// The folder layout of the URI cases: <root>/model/ holds the model, <root>/secret.bin is outside it.
fs::path uri_root() {
    const fs::path root = test::output_dir("hostile_uris");
    fs::create_directories(root / "model");
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::ofstream(root / "secret.bin", std::ios::binary).write(reinterpret_cast<const char*>(triangle), 36);
    std::ofstream(root / "model" / "inside.bin", std::ios::binary).write(reinterpret_cast<const char*>(triangle), 36);
    return root;
}

std::string import_error(const std::string& json, const fs::path& base_dir, const GltfReadOptions& options = {}) {
    const std::vector<std::uint8_t> bytes(json.begin(), json.end());
    try {
        import_gltf(bytes, "m.gltf", base_dir, options);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

std::vector<std::uint8_t> glb_of(const std::string& json, std::uint32_t version) {
    std::string body = json;
    while (body.size() % 4) body += ' ';
    std::vector<std::uint8_t> bytes(20 + body.size());
    const std::uint32_t header[5] = {0x46546C67u, version, std::uint32_t(bytes.size()), std::uint32_t(body.size()),
                                     0x4E4F534Au};
    std::memcpy(bytes.data(), header, 20);
    std::memcpy(bytes.data() + 20, body.data(), body.size());
    return bytes;
}

struct BudgetScope {
    explicit BudgetScope(std::uint64_t bytes) : saved(io::memory_budget()) { io::set_memory_budget(bytes); }
    ~BudgetScope() { io::set_memory_budget(saved); }
    std::uint64_t saved;
};

}  // namespace

TEST_CASE("hostile glTF: a URI inside the model's folder is read, one leaving it is refused, however spelled") {
    const fs::path root = uri_root();
    const fs::path model = root / "model";
    CHECK(import_error(triangle_gltf("inside.bin"), model) == "");
    CHECK(import_error(triangle_gltf("./inside.bin"), model) == "");
    for (const std::string uri : {"../secret.bin", "%2e%2e/secret.bin", "%2E%2E%2Fsecret.bin", "sub/../../secret.bin"}) {
        CAPTURE(uri);
        CHECK(import_error(triangle_gltf(uri), model).find("leaves the model's folder") != std::string::npos);
    }
    const std::string absolute = import_error(triangle_gltf((root / "secret.bin").string()), model);
    CHECK(absolute.find("is an absolute path; only files inside the model's folder") != std::string::npos);
    CHECK(absolute.find("--allow-external-uris") != std::string::npos);
    CHECK(import_error(triangle_gltf("file:///etc/hostname"), model).find("has a scheme (file:)") !=
          std::string::npos);
    CHECK(import_error(triangle_gltf("http://example.com/b.bin"), model).find("has a scheme (http:)") !=
          std::string::npos);
    // A data: URI is always read.
    CHECK(import_error(triangle_gltf(kTriangleData), model) == "");
}

TEST_CASE("hostile glTF: a symbolic link out of the model's folder is refused, allowing external URIs reads it") {
    const fs::path root = uri_root();
    const fs::path link = root / "model" / "link.bin";
    fs::remove(link);
    fs::create_symlink("../secret.bin", link);
    CHECK(import_error(triangle_gltf("link.bin"), root / "model").find("through a symbolic link") !=
          std::string::npos);
    GltfReadOptions allow;
    allow.allow_external_uris = true;
    CHECK(import_error(triangle_gltf("link.bin"), root / "model", allow) == "");
    CHECK(import_error(triangle_gltf("../secret.bin"), root / "model", allow) == "");
    // The fuzzer's setting still reads nothing at all.
    GltfReadOptions no_files;
    no_files.read_external_files = false;
    CHECK(import_error(triangle_gltf("inside.bin"), root / "model", no_files) != "");
}

TEST_CASE("hostile glTF: nodes in a cycle, or with two parents, are refused though no scene reaches them") {
    const fs::path dir = test::output_dir("hostile_gltf");
    const std::string cycle = import_error(
        triangle_gltf(kTriangleData, "", "", R"([{"mesh": 0, "children": [1]}, {"children": [0]}])", false), dir);
    CHECK(cycle.find("is its own ancestor (a cycle of children)") != std::string::npos);
    const std::string two_parents = import_error(
        triangle_gltf(kTriangleData, "", "", R"([{"children": [2]}, {"children": [2]}, {"mesh": 0}])"), dir);
    CHECK(two_parents.find("is a child of both nodes 0 and 1") != std::string::npos);
    CHECK(import_error(triangle_gltf(kTriangleData, "", "", R"([{"children": [1]}, {"mesh": 0}])"), dir) == "");
}

TEST_CASE("hostile glTF: GLB version 2 only, deep JSON and negative offsets are refused before parsing") {
    const fs::path dir = test::output_dir("hostile_gltf");
    const auto glb_error = [&](const std::vector<std::uint8_t>& bytes) -> std::string {
        try {
            import_gltf(bytes, "m.glb", dir);
        } catch (const std::exception& e) {
            return e.what();
        }
        return "";
    };
    CHECK(glb_error(glb_of(triangle_gltf(kTriangleData), 2)) == "");
    CHECK(glb_error(glb_of(triangle_gltf(kTriangleData), 1)) ==
          "m.glb: invalid glTF binary (.glb): version 1, expected 2");
    const std::string deep = triangle_gltf(kTriangleData, ",\n\"extras\": " + std::string(20000, '[') +
                                                              std::string(20000, ']'));
    CHECK(import_error(deep, dir) ==
          "m.gltf: line 6: JSON nested deeper than 256 levels (arrays and objects, e.g. in extras); refused before "
          "parsing");
    CHECK(glb_error(glb_of(deep, 2)).find("m.glb: the JSON chunk's line 6: JSON nested deeper than 256") == 0);
    CHECK(import_error(triangle_gltf(kTriangleData, "", R"("byteOffset": -4, )"), dir) ==
          "m.gltf: accessors[0]: \"byteOffset\" is negative (-4); offsets, lengths and strides are >= 0");
    // Found by where it is in the document, not by its text: in extras it is the user's, and the
    // same words inside a string are no key at all.
    CHECK(import_error(triangle_gltf(kTriangleData, R"(, "extras": {"byteOffset": -1, "note": "\"byteLength\": -2"})"),
                       dir) == "");
    std::string stride = triangle_gltf(kTriangleData);
    const std::string view = R"("bufferViews": [{"buffer": 0, "byteLength": 36})";
    stride.replace(stride.find(view), view.size(), R"("bufferViews": [{"buffer": 0, "byteLength": 36, "byteStride": -12})");
    CHECK(import_error(stride, dir) ==
          "m.gltf: bufferViews[0]: \"byteStride\" is negative (-12); offsets, lengths and strides are >= 0");
    std::string weights = triangle_gltf(kTriangleData, "", "", R"([{"mesh": 0, "weights": [0.5, "NaN"]}])");
    CHECK(import_error(weights, dir) == "m.gltf: nodes[0]: \"weights\" holds something other than numbers "
                                        "([0.5,\"NaN\"]); morph weights are finite numbers");
}

TEST_CASE("hostile glTF: one accessor behind 10^5 primitives is refused against the budget, before it expands") {
    const BudgetScope budget(16ull << 20);
    std::string primitives;
    for (int i = 0; i < 100000; ++i) primitives += std::string(i ? "," : "") + R"({"attributes": {"POSITION": 0}})";
    std::string json = triangle_gltf(kTriangleData);
    const std::string one = R"("primitives": [{"attributes": {"POSITION": 0}}])";
    json.replace(json.find(one), one.size(), "\"primitives\": [" + primitives + "]");
    // 3 vertices a primitive is little; the objects and meshes of 10^5 of them are what grows.
    const std::string error = import_error(json, test::output_dir("hostile_gltf"));
    CHECK(error.find("more than the memory budget of 16.0 MB (--max-memory)") != std::string::npos);
    CHECK(error.find("m.gltf: ") == 0);
}

TEST_CASE("hostile images: a header claiming more pixels than the data can hold is refused before decoding") {
    // A greyscale baseline JPEG of flat 8x8 blocks, its size patched (tests/robustness/hostile/make_cases.py).
    const auto jpeg = [](int width, int height) {
        std::vector<std::uint8_t> b = {0xFF, 0xD8, 0xFF, 0xDB, 0x00, 0x43, 0x00};
        b.insert(b.end(), 64, 1);
        const std::uint8_t sof[] = {0xFF, 0xC0, 0x00, 0x0B, 0x08, std::uint8_t(height >> 8), std::uint8_t(height),
                                    std::uint8_t(width >> 8), std::uint8_t(width), 0x01, 0x01, 0x11, 0x00};
        b.insert(b.end(), sof, sof + sizeof sof);
        const std::uint8_t dht_head[] = {0xFF, 0xC4, 0x00, 0x26};
        b.insert(b.end(), dht_head, dht_head + 4);
        for (const std::uint8_t table : {0x00, 0x10}) {
            b.push_back(table);
            b.push_back(1);
            b.insert(b.end(), 15, 0);
            b.push_back(0);
        }
        const std::uint8_t sos[] = {0xFF, 0xDA, 0x00, 0x08, 0x01, 0x01, 0x00, 0x00, 0x3F, 0x00, 0x3F, 0xFF, 0xD9};
        b.insert(b.end(), sos, sos + sizeof sos);
        return b;
    };
    const texture::Texture small = texture::Texture::decode(jpeg(8, 8), "t.jpg", texture::ColorSpace::srgb);
    CHECK(small.width() == 8);
    CHECK_THROWS_WITH_AS(texture::Texture::decode(jpeg(16384, 16384), "t.jpg", texture::ColorSpace::srgb),
                         doctest::Contains("the header claims 16384x16384, which needs at least 524288 bytes of JPEG "
                                           "data (a bit per 8x8 block); the file has"),
                         texture::TextureError);
}
