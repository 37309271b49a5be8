// glTF materials and textures (issue 31): each map's own texCoord and
// KHR_texture_transform, samplers, KHR_materials_unlit, EXT_texture_webp and
// EXT_texture_avif, KHR_texture_basisu refused with advice, and straight
// base-colour alpha, on a small quad of the tests' own (gltf_material_files.hpp).
#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <OpenImageIO/imagebuf.h>

#include "scene/gltf/gltf_import.hpp"
#include "scene/gltf_text_import.hpp"
#include "scene/gltf_material_files.hpp"
#include "test_paths.hpp"
#include "texture/texture.hpp"
#include "texture/webp_avif_test_images.hpp"

using namespace tessera;

namespace {

GltfContent import_text(const std::string& text, const std::filesystem::path& base_dir = "") {
    return test::import_gltf_text(text, "quad.gltf", base_dir);
}

std::string error_of(const std::string& text, const std::filesystem::path& base_dir = "") {
    return test::gltf_import_error(text, "quad.gltf", base_dir);
}

std::vector<glm::vec2> uvs_of(const float (&values)[8]) {
    return {{values[0], values[1]}, {values[2], values[3]}, {values[4], values[5]}, {values[6], values[7]}};
}

const std::string kTwoTextures = R"({"source": 0}, {"source": 0, "sampler": 0})";

}  // namespace

TEST_CASE("glTF texCoord: maps that agree are baked into the uvs, maps on two sets read two") {
    SUBCASE("every map on TEXCOORD_1: baked, one set") {
        const GltfContent c = import_text(test::quad_gltf(
            R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}, "emissiveTexture": {"index": 1, "texCoord": 1}, "emissiveFactor": [1, 1, 1]})",
            kTwoTextures, test::png_image(), R"({})"));
        REQUIRE(c.meshes.size() == 1);
        CHECK(c.meshes[0].uvs == uvs_of(test::kQuadUv1));
        CHECK(c.meshes[0].uvs1.empty());
        CHECK(c.materials[0].albedo_map.plain_uvs());
        CHECK(c.materials[0].emissive_map.plain_uvs());
        CHECK(c.warnings.empty());
    }
    SUBCASE("base colour on TEXCOORD_0, emissive on TEXCOORD_1 (baked AO's layout): each its own") {
        const GltfContent c = import_text(test::quad_gltf(
            R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "occlusionTexture": {"index": 1, "texCoord": 1}})",
            kTwoTextures, test::png_image(), R"({})"));
        CHECK(c.meshes[0].uvs == uvs_of(test::kQuadUv0));
        CHECK(c.meshes[0].uvs1 == uvs_of(test::kQuadUv1));
        CHECK(c.materials[0].albedo_map.uv_set == 0);
        CHECK(c.materials[0].ao_map.uv_set == 1);
        CHECK(c.warnings.empty());  // no longer "all use the first map's"
    }
    SUBCASE("per-map KHR_texture_transform: applied when sampling where maps differ") {
        const GltfContent c = import_text(test::quad_gltf(
            R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.25, 0.5], "scale": [2, 3]}}}}, "emissiveTexture": {"index": 1}, "emissiveFactor": [1, 1, 1]})",
            kTwoTextures, test::png_image(), R"({})", R"("KHR_texture_transform")"));
        CHECK(c.meshes[0].uvs == uvs_of(test::kQuadUv0));  // not baked
        const TextureSlot& base = c.materials[0].albedo_map;
        REQUIRE(base.uv_transformed);
        const glm::vec3 moved = base.uv_transform * glm::vec3(1, 1, 1);
        CHECK(moved.x == doctest::Approx(2.25f));
        CHECK(moved.y == doctest::Approx(3.5f));
        CHECK_FALSE(c.materials[0].emissive_map.uv_transformed);
        // The texCoord override of the extension picks the set.
        const GltfContent o = import_text(test::quad_gltf(
            R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}}}, "emissiveTexture": {"index": 1}, "emissiveFactor": [1, 1, 1]})",
            kTwoTextures, test::png_image(), R"({})", R"("KHR_texture_transform")"));
        // The base colour is the first map: its set (TEXCOORD_1) is Mesh::uvs, the emissive's the second.
        CHECK(o.materials[0].albedo_map.uv_set == 0);
        CHECK(o.materials[0].emissive_map.uv_set == 1);
        CHECK(o.meshes[0].uvs == uvs_of(test::kQuadUv1));
        CHECK(o.meshes[0].uvs1 == uvs_of(test::kQuadUv0));
    }
    SUBCASE("a texCoord naming a set the primitive does not have: one clear error") {
        const std::string message = error_of(test::quad_gltf(
            R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 2}}})", kTwoTextures,
            test::png_image(), R"({})"));
        CHECK(message == "quad.gltf: meshes[0] primitives[0]: material 0 has a map with texCoord 2 but the primitive "
                         "has no TEXCOORD_2");
        const std::string second = error_of(test::quad_gltf(
            R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "emissiveTexture": {"index": 1, "texCoord": 1}})",
            kTwoTextures, test::png_image(), R"({})", "", R"("POSITION": 0, "TEXCOORD_0": 2)"));
        CHECK(second.find("texCoord 1 but the primitive has no TEXCOORD_1") != std::string::npos);
    }
}

TEST_CASE("glTF samplers: wrapS and wrapT apart, MIRRORED_REPEAT, the filters, bad enums refused") {
    const auto material = R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}})";
    const GltfContent c = import_text(test::quad_gltf(
        material, kTwoTextures, test::png_image(),
        R"({"wrapS": 33648, "wrapT": 33071, "magFilter": 9728, "minFilter": 9986})"));
    const TextureSlot& slot = c.materials[0].albedo_map;
    CHECK(slot.wrap_s == TextureWrap::mirrored_repeat);
    CHECK(slot.wrap_t == TextureWrap::clamp_to_edge);
    CHECK(slot.mag_filter == TextureFilter::nearest);
    CHECK(slot.min_filter == TextureFilter::nearest_mipmap_linear);
    // Absent: REPEAT, LINEAR, LINEAR_MIPMAP_LINEAR.
    const TextureSlot defaults = import_text(test::quad_gltf(material, kTwoTextures, test::png_image(), R"({})"))
                                     .materials[0]
                                     .albedo_map;  // a copy: the imported content is a temporary
    CHECK(defaults.wrap_s == TextureWrap::repeat);
    CHECK(defaults.wrap_t == TextureWrap::repeat);
    CHECK(defaults.mag_filter == TextureFilter::linear);
    CHECK(defaults.min_filter == TextureFilter::linear_mipmap_linear);
    CHECK(error_of(test::quad_gltf(material, kTwoTextures, test::png_image(), R"({"wrapT": 1234})")) ==
          "quad.gltf: samplers[0] wrapT is 1234, expected 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT)");
    CHECK(error_of(test::quad_gltf(material, kTwoTextures, test::png_image(), R"({"magFilter": 9987})"))
              .find("samplers[0] magFilter is 9987, expected 9728 (NEAREST) or 9729 (LINEAR)") != std::string::npos);
    CHECK(error_of(test::quad_gltf(material, kTwoTextures, test::png_image(), R"({"minFilter": 1})"))
              .find("samplers[0] minFilter is 1") != std::string::npos);
}

TEST_CASE("glTF KHR_materials_unlit: accepted (also when required), the material unlit") {
    const std::string text = test::replaced(
        test::quad_gltf(R"({"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1]}, "extensions": {"KHR_materials_unlit": {}}})",
                        "", "", "", R"("KHR_materials_unlit")"),
        R"("extensionsUsed": ["KHR_materials_unlit"],)",
        R"("extensionsUsed": ["KHR_materials_unlit"], "extensionsRequired": ["KHR_materials_unlit"],)");
    const GltfContent c = import_text(text);
    CHECK(c.materials[0].unlit);
    CHECK(c.warnings.empty());
    const GltfContent lit = import_text(test::quad_gltf(R"({})", "", ""));
    CHECK_FALSE(lit.materials[0].unlit);
}

TEST_CASE("glTF EXT_texture_webp and EXT_texture_avif: the extension's image is decoded") {
    const std::vector<std::uint8_t> rgba = {10, 20, 30, 255, 200, 100, 50, 128, 0, 255, 0, 64, 255, 255, 255, 255};
    const std::string material = R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})";
    SUBCASE("WebP only (gltf-transform's --texture-compress webp), a data URI") {
        const GltfContent c = import_text(test::quad_gltf(
            material, R"({"extensions": {"EXT_texture_webp": {"source": 0}}})",
            test::data_image(test::encode_webp_lossless(rgba, 2, 2), "application/octet-stream"), "",
            R"("EXT_texture_webp")"));
        REQUIRE(c.textures.size() == 1);
        CHECK(c.textures[0]->width() == 2);
        CHECK(c.textures[0]->texel_bytes(0, 1, 0) == std::array<std::uint8_t, 4>{200, 100, 50, 128});  // straight alpha
        CHECK(c.warnings.empty());
    }
    SUBCASE("WebP with a PNG fallback: the WebP is used") {
        const GltfContent c = import_text(test::quad_gltf(
            material, R"({"source": 1, "extensions": {"EXT_texture_webp": {"source": 0}}})",
            test::data_image(test::encode_webp_lossless(rgba, 2, 2), "application/octet-stream") + ", " +
                test::png_image(),
            "", R"("EXT_texture_webp")"));
        CHECK(c.textures[0]->texel_bytes(0, 0, 0) == std::array<std::uint8_t, 4>{10, 20, 30, 255});
    }
    SUBCASE("an external .webp that does not decode: one line naming the file") {
        const std::filesystem::path dir = test::output_dir("gltf_materials");
        std::vector<std::uint8_t> broken = test::encode_webp_lossless(rgba, 2, 2);
        broken.resize(24);
        test::write_bytes(dir / "broken.webp", broken);
        const std::string message = error_of(
            test::quad_gltf(material, R"({"extensions": {"EXT_texture_webp": {"source": 0}}})",
                            R"({"uri": "broken.webp"})", "", R"("EXT_texture_webp")"),
            dir);
        INFO(message);
        CHECK(message.starts_with("quad.gltf: images[0] ('broken.webp'): "));
        CHECK(message.find('\n') == std::string::npos);
    }
    SUBCASE("AVIF") {
        const std::vector<std::uint8_t> avif = test::encode_avif(rgba, 2, 2);
        if (avif.empty()) return;  // no AV1 encoder in this libavif
        const GltfContent c = import_text(test::quad_gltf(
            material, R"({"extensions": {"EXT_texture_avif": {"source": 0}}})",
            test::data_image(avif, "application/octet-stream"), "", R"("EXT_texture_avif")"));
        REQUIRE(c.textures.size() == 1);
        CHECK(c.textures[0]->height() == 2);
    }
    SUBCASE("a source index out of range") {
        CHECK(error_of(test::quad_gltf(material, R"({"extensions": {"EXT_texture_webp": {"source": 5}}})",
                                       test::png_image(), "", R"("EXT_texture_webp")"))
                  .find("EXT_texture_webp source is not an image index below 1") != std::string::npos);
    }
}

TEST_CASE("glTF KHR_texture_basisu: a texture with only a KTX2 image is refused, saying how to convert") {
    const std::string message = error_of(test::quad_gltf(
        R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})",
        R"({"extensions": {"KHR_texture_basisu": {"source": 0}}})", test::png_image(), "", R"("KHR_texture_basisu")"));
    INFO(message);
    CHECK(message.find("KHR_texture_basisu (KTX2) image, which is not supported") != std::string::npos);
    CHECK(message.find("ktx extract") != std::string::npos);
    // With a PNG fallback it loads, with one warning.
    const GltfContent c = import_text(test::quad_gltf(
        R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})",
        R"({"source": 0, "extensions": {"KHR_texture_basisu": {"source": 0}}})", test::png_image(), "",
        R"("KHR_texture_basisu")"));
    REQUIRE(c.warnings.size() == 1);
    CHECK(c.warnings[0].find("PNG or JPEG fallback") != std::string::npos);
}

TEST_CASE("glTF base colour alpha is straight: a PNG's colour is not darkened by its alpha") {
    const std::filesystem::path path = test::output_dir("gltf_materials") / "straight_alpha.png";
    const float pixels[] = {1.0f, 0.5f, 0.25f, 0.1f};
    OIIO::ImageSpec spec(1, 1, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // the values are straight: written as they are
    OIIO::ImageBuf buffer(spec, const_cast<float*>(pixels));
    REQUIRE(buffer.write(path.string(), OIIO::TypeDesc::UINT8));
    std::ifstream file(path, std::ios::binary);
    const std::vector<std::uint8_t> png((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const GltfContent c = import_text(test::quad_gltf(R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})",
                                                      R"({"source": 0})", test::data_image(png, "image/png")));
    REQUIRE(c.textures.size() == 1);
    const auto texel = c.textures[0]->texel_bytes(0, 0, 0);
    INFO(int(texel[0]) << " " << int(texel[1]) << " " << int(texel[2]) << " " << int(texel[3]));
    CHECK(texel == std::array<std::uint8_t, 4>{255, 128, 64, 26});
}
