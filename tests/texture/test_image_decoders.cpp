// The PNG and JPEG decoders (src/texture/image_decoders.hpp) give exactly the
// RGBA8 texels OpenImageIO 2.4 gave: every PNG layout (grey, grey + alpha,
// palette with and without tRNS, RGB, RGBA; 1 to 16 bits; interlaced; sRGB,
// gAMA and unmarked files, alpha kept straight or associated as OpenImageIO
// associates it) and JPEG (grey, YCbCr at two subsamplings, RGB, CMYK, YCCK),
// written here with libpng and libjpeg, plus the sample models' PNG textures.
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <tuple>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>
#include <jpeglib.h>
#include <png.h>

#include "texture/image_decoders.hpp"
#include "texture/texture.hpp"
#include "test_paths.hpp"

namespace {

using namespace tessera::texture;

std::filesystem::path decoder_dir() {
    const std::filesystem::path dir = tessera::test::binary_dir() / "test_output" / "image_decoders";
    std::filesystem::create_directories(dir);
    return dir;
}

std::vector<std::uint8_t> read_all(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What texture.cpp did with OpenImageIO: the first min(channels, 4) channels
// as UINT8, expanded to RGBA8 words (grey → g, g, g; no alpha → 255).
std::vector<std::uint32_t> decode_with_oiio(const std::filesystem::path& path, bool straight_alpha) {
    OIIO::ImageSpec config;
    if (straight_alpha) config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path.string(), &config);
    REQUIRE_MESSAGE(input, OIIO::geterror());
    const OIIO::ImageSpec spec = input->spec();
    const int channels = std::min(spec.nchannels, 4);
    std::vector<std::uint8_t> samples(std::size_t(spec.width) * spec.height * channels);
    REQUIRE(input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, samples.data()));
    std::vector<std::uint32_t> texels(std::size_t(spec.width) * spec.height);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        const std::uint8_t* p = samples.data() + i * channels;
        std::uint32_t r = p[0], g = p[0], b = p[0], a = 255;
        if (channels == 2) a = p[1];
        if (channels >= 3) g = p[1], b = p[2];
        if (channels == 4) a = p[3];
        texels[i] = r | g << 8 | b << 16 | a << 24;
    }
    return texels;
}

std::vector<std::uint32_t> decode_with_ours(const std::filesystem::path& path, bool straight_alpha) {
    const std::vector<std::uint8_t> bytes = read_all(path);
    std::vector<std::uint32_t> texels;
    const Level0Allocator allocate = [&](int width, int height) {
        texels.assign(std::size_t(width) * std::size_t(height), 0xDEADBEEFu);
        return texels.data();
    };
    if (has_png_signature(bytes)) decode_png(bytes, straight_alpha ? PngAlpha::straight : PngAlpha::associated, allocate);
    else decode_jpeg(bytes, allocate);
    return texels;
}

void check_same_texels(const std::filesystem::path& path) {
    for (const bool straight : {true, false}) {
        INFO(path.filename().string() << (straight ? ", straight alpha" : ", associated alpha"));
        const std::vector<std::uint32_t> expected = decode_with_oiio(path, straight);
        const std::vector<std::uint32_t> actual = decode_with_ours(path, straight);
        REQUIRE(actual.size() == expected.size());
        std::size_t differing = 0, first = 0;
        for (std::size_t i = 0; i < actual.size(); ++i)
            if (actual[i] != expected[i] && differing++ == 0) first = i;
        INFO("first differing texel " << first << ": ours " << std::hex << actual[first] << ", OpenImageIO "
                                      << expected[first]);
        CHECK(differing == 0);
    }
}

// A PNG of `width`×`height` with random samples (seeded), every layout libpng writes.
struct PngKind {
    const char* name;
    int color_type;
    int bit_depth;
    bool trns = false;
    bool interlaced = false;
    int gamma_chunk = 0;  // 0 none, 1 sRGB, 2 gAMA 1/2.2, 3 gAMA 1.0
};

std::filesystem::path write_png(const PngKind& kind, int width, int height, unsigned seed) {
    const std::filesystem::path path = decoder_dir() / (std::string(kind.name) + ".png");
    std::FILE* file = std::fopen(path.c_str(), "wb");
    REQUIRE(file);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, file);
    png_set_IHDR(png, info, width, height, kind.bit_depth, kind.color_type,
                 kind.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    std::mt19937 rng(seed);
    const int max = (1 << kind.bit_depth) - 1;
    std::vector<png_color> palette;
    std::vector<png_byte> palette_alpha;
    if (kind.color_type == PNG_COLOR_TYPE_PALETTE) {
        for (int i = 0; i <= max; ++i)
            palette.push_back({png_byte(rng()), png_byte(rng()), png_byte(rng())}), palette_alpha.push_back(png_byte(rng()));
        png_set_PLTE(png, info, palette.data(), int(palette.size()));
        if (kind.trns) png_set_tRNS(png, info, palette_alpha.data(), int(palette_alpha.size()), nullptr);
    } else if (kind.trns) {
        png_color_16 transparent{};
        transparent.gray = transparent.red = png_uint_16(max / 3);
        transparent.green = transparent.blue = png_uint_16(max / 3);
        png_set_tRNS(png, info, nullptr, 0, &transparent);
    }
    if (kind.gamma_chunk == 1) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    if (kind.gamma_chunk == 2) png_set_gAMA(png, info, 1.0 / 2.2);
    if (kind.gamma_chunk == 3) png_set_gAMA(png, info, 1.0);
    png_write_info(png, info);
    if (kind.bit_depth == 16) png_set_swap(png);
    const int channels = png_get_channels(png, info);
    const int samples_per_row = width * channels;
    std::vector<png_byte> row(png_get_rowbytes(png, info));
    std::vector<png_bytep> rows;
    std::vector<std::vector<png_byte>> image(std::size_t(height), row);
    for (int y = 0; y < height; ++y) {
        std::vector<png_byte>& r = image[std::size_t(y)];
        std::fill(r.begin(), r.end(), 0);
        for (int s = 0; s < samples_per_row; ++s) {
            // Some samples at the tRNS key and at the extremes, the rest random.
            const unsigned pick = rng() % 8;
            const int value = pick == 0 ? max / 3 : pick == 1 ? 0 : pick == 2 ? max : int(rng() % unsigned(max + 1));
            if (kind.bit_depth == 16) {
                r[2 * s] = png_byte(value & 0xFF), r[2 * s + 1] = png_byte(value >> 8);
            } else if (kind.bit_depth == 8) {
                r[s] = png_byte(value);
            } else {
                const int per_byte = 8 / kind.bit_depth;
                r[s / per_byte] |= png_byte(value << (8 - kind.bit_depth * (s % per_byte + 1)));
            }
        }
        rows.push_back(r.data());
    }
    png_write_image(png, rows.data());
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    return path;
}

std::filesystem::path write_jpeg(const char* name, J_COLOR_SPACE in_space, int components, J_COLOR_SPACE file_space,
                                 int h_sampling, int width, int height, unsigned seed) {
    const std::filesystem::path path = decoder_dir() / (std::string(name) + ".jpg");
    std::FILE* file = std::fopen(path.c_str(), "wb");
    REQUIRE(file);
    jpeg_compress_struct cinfo{};
    jpeg_error_mgr errors{};
    cinfo.err = jpeg_std_error(&errors);
    jpeg_create_compress(&cinfo);
    jpeg_stdio_dest(&cinfo, file);
    cinfo.image_width = JDIMENSION(width);
    cinfo.image_height = JDIMENSION(height);
    cinfo.input_components = components;
    cinfo.in_color_space = in_space;
    jpeg_set_defaults(&cinfo);
    jpeg_set_colorspace(&cinfo, file_space);
    if (file_space == JCS_YCbCr) cinfo.comp_info[0].h_samp_factor = h_sampling;
    jpeg_set_quality(&cinfo, 85, TRUE);
    jpeg_start_compress(&cinfo, TRUE);
    // Smooth gradients with noise: chroma that subsampling and upsampling change.
    std::mt19937 rng(seed);
    std::vector<JSAMPLE> row(std::size_t(width) * components);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < components; ++c)
                row[std::size_t(x) * components + c] = JSAMPLE((x * (c + 1) * 3 + y * (5 - c) + int(rng() % 24)) & 0xFF);
        JSAMPROW pointer = row.data();
        jpeg_write_scanlines(&cinfo, &pointer, 1);
    }
    jpeg_finish_compress(&cinfo);
    jpeg_destroy_compress(&cinfo);
    std::fclose(file);
    return path;
}

}  // namespace

TEST_CASE("PNG decoding gives OpenImageIO's texels for every layout, bit depth and gamma marking") {
    const std::vector<PngKind> kinds = {
        {"grey1", PNG_COLOR_TYPE_GRAY, 1},
        {"grey2", PNG_COLOR_TYPE_GRAY, 2},
        {"grey4", PNG_COLOR_TYPE_GRAY, 4},
        {"grey8", PNG_COLOR_TYPE_GRAY, 8},
        {"grey8_trns", PNG_COLOR_TYPE_GRAY, 8, true},
        {"grey16", PNG_COLOR_TYPE_GRAY, 16},
        {"grey16_trns", PNG_COLOR_TYPE_GRAY, 16, true},
        {"grey_alpha8", PNG_COLOR_TYPE_GRAY_ALPHA, 8},
        {"grey_alpha16", PNG_COLOR_TYPE_GRAY_ALPHA, 16},
        {"palette1", PNG_COLOR_TYPE_PALETTE, 1},
        {"palette4_trns", PNG_COLOR_TYPE_PALETTE, 4, true},
        {"palette8", PNG_COLOR_TYPE_PALETTE, 8},
        {"palette8_trns", PNG_COLOR_TYPE_PALETTE, 8, true},
        {"rgb8", PNG_COLOR_TYPE_RGB, 8},
        {"rgb8_trns", PNG_COLOR_TYPE_RGB, 8, true},
        {"rgb16", PNG_COLOR_TYPE_RGB, 16},
        {"rgba8", PNG_COLOR_TYPE_RGB_ALPHA, 8},
        {"rgba8_srgb", PNG_COLOR_TYPE_RGB_ALPHA, 8, false, false, 1},
        {"rgba8_gamma22", PNG_COLOR_TYPE_RGB_ALPHA, 8, false, false, 2},
        {"rgba8_gamma10", PNG_COLOR_TYPE_RGB_ALPHA, 8, false, false, 3},
        {"grey_alpha8_gamma22", PNG_COLOR_TYPE_GRAY_ALPHA, 8, false, false, 2},
        {"rgba16", PNG_COLOR_TYPE_RGB_ALPHA, 16},
        {"rgba16_gamma22", PNG_COLOR_TYPE_RGB_ALPHA, 16, false, false, 2},
        {"rgba8_interlaced", PNG_COLOR_TYPE_RGB_ALPHA, 8, false, true},
        {"rgb16_interlaced", PNG_COLOR_TYPE_RGB, 16, false, true},
    };
    unsigned seed = 1;
    for (const PngKind& kind : kinds) check_same_texels(write_png(kind, 67, 45, seed++));
}

TEST_CASE("16-bit PNG samples round to 8 bits as OpenImageIO rounds them, all 65536 values") {
    const std::filesystem::path path = decoder_dir() / "grey16_every_value.png";
    {
        std::FILE* file = std::fopen(path.c_str(), "wb");
        REQUIRE(file);
        png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
        png_infop info = png_create_info_struct(png);
        png_init_io(png, file);
        png_set_IHDR(png, info, 256, 256, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                     PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        for (int y = 0; y < 256; ++y) {
            png_byte row[512];
            for (int x = 0; x < 256; ++x) row[2 * x] = png_byte(y), row[2 * x + 1] = png_byte(x);  // big-endian y·256 + x
            png_write_row(png, row);
        }
        png_write_end(png, info);
        png_destroy_write_struct(&png, &info);
        std::fclose(file);
    }
    check_same_texels(path);
}

TEST_CASE("JPEG decoding gives OpenImageIO's texels: grey, YCbCr, RGB, CMYK, YCCK") {
    check_same_texels(write_jpeg("grey", JCS_GRAYSCALE, 1, JCS_GRAYSCALE, 1, 70, 41, 1));
    check_same_texels(write_jpeg("ycbcr420", JCS_RGB, 3, JCS_YCbCr, 2, 70, 41, 2));
    check_same_texels(write_jpeg("ycbcr444", JCS_RGB, 3, JCS_YCbCr, 1, 70, 41, 3));
    check_same_texels(write_jpeg("rgb", JCS_RGB, 3, JCS_RGB, 1, 70, 41, 4));
    check_same_texels(write_jpeg("cmyk", JCS_CMYK, 4, JCS_CMYK, 1, 70, 41, 5));
    check_same_texels(write_jpeg("ycck", JCS_CMYK, 4, JCS_YCCK, 1, 70, 41, 6));
}

TEST_CASE("The sample models' PNG and JPEG textures decode to OpenImageIO's texels") {
    if (tessera::test::skip_without_assets()) return;
    const std::filesystem::path assets = tessera::test::assets_dir() / "gltf";
    int files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(assets)) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".png" && ext != ".jpg" && ext != ".jpeg") continue;
        if (entry.path().string().find("screenshot") != std::string::npos) continue;
        check_same_texels(entry.path());
        ++files;
    }
    CHECK(files > 0);  // the samples have PNG and JPEG textures
}

TEST_CASE("Damaged PNG and JPEG data is refused with the decoder's reason") {
    const std::filesystem::path png = write_png({"damaged_source", PNG_COLOR_TYPE_RGB, 8}, 64, 64, 9);
    const std::filesystem::path jpeg = write_jpeg("damaged_source", JCS_RGB, 3, JCS_YCbCr, 2, 64, 64, 9);
    for (const std::filesystem::path& path : {png, jpeg}) {
        std::vector<std::uint8_t> bytes = read_all(path);
        bytes.resize(bytes.size() / 2);
        const Level0Allocator allocate = [](int width, int height) {
            static std::vector<std::uint32_t> texels;
            texels.resize(std::size_t(width) * std::size_t(height));
            return texels.data();
        };
        INFO(path.filename().string());
        try {
            if (has_png_signature(bytes)) decode_png(bytes, PngAlpha::straight, allocate);
            else decode_jpeg(bytes, allocate);
            FAIL("a truncated file decoded");
        } catch (const ImageDecodeError& e) {
            CHECK_FALSE(e.header());  // the header read: the pixel data is what is missing
            CHECK(std::string(e.what()).size() > 0);
        }
    }
    // A damaged signature or header is a header error.
    const Level0Allocator never = [](int, int) -> std::uint32_t* { throw std::logic_error("allocated"); };
    std::vector<std::uint8_t> bytes = read_all(png);
    bytes[7] ^= 0xFF;
    try {
        decode_png(bytes, PngAlpha::straight, never);
        FAIL("a PNG with a bad signature decoded");
    } catch (const ImageDecodeError& e) {
        CHECK(e.header());
    }
    bytes = read_all(jpeg);
    bytes.resize(40);  // inside the header
    try {
        decode_jpeg(bytes, never);
        FAIL("a JPEG cut in its header decoded");
    } catch (const ImageDecodeError& e) {
        CHECK(e.header());
    }
}

TEST_CASE("Other formats load through the OpenImageIO module with OpenImageIO's texels") {
    // A TGA with alpha and a 16-bit TIFF, written by OpenImageIO.
    std::mt19937 rng(11);
    for (const auto& [name, channels, format] :
         {std::tuple{"module.tga", 4, OIIO::TypeDesc::UINT8}, std::tuple{"module.tif", 3, OIIO::TypeDesc::UINT16}}) {
        const std::filesystem::path path = decoder_dir() / name;
        const int width = 37, height = 23;
        std::vector<float> pixels(std::size_t(width) * height * channels);
        for (float& p : pixels) p = float(rng() % 1000) / 999.0f;
        auto out = OIIO::ImageOutput::create(path.string());
        REQUIRE(out);
        REQUIRE(out->open(path.string(), OIIO::ImageSpec(width, height, channels, format)));
        REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        REQUIRE(out->close());

        INFO(name);
        const std::vector<std::uint32_t> expected = decode_with_oiio(path, true);
        const Texture texture = Texture::load(path, ColorSpace::linear);
        REQUIRE(texture.width() == width);
        REQUIRE(texture.height() == height);
        std::size_t differing = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const auto b = texture.texel_bytes(0, x, y);
                const std::uint32_t word = b[0] | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
                differing += word != expected[std::size_t(y) * width + x];
            }
        CHECK(differing == 0);
    }
}

TEST_CASE("A .png or .jpg file that is neither is refused without OpenImageIO, naming the file") {
    const std::filesystem::path path = decoder_dir() / "not_really.jpg";
    std::ofstream(path) << "GIF89a, not a JPEG";
    try {
        (void)Texture::load(path, ColorSpace::srgb);
        FAIL("a text file loaded as a texture");
    } catch (const TextureError& e) {
        const std::string message = e.what();
        CHECK(message.find("not_really.jpg") != std::string::npos);
        CHECK(message.find("neither a PNG nor a JPEG") != std::string::npos);
    }
}

TEST_CASE("A damaged file in a format for the module is refused with OpenImageIO's reason and the file's name") {
    const std::filesystem::path path = decoder_dir() / "damaged.tga";
    {
        // A TGA header promising 64x64 RGB, then 10 bytes of pixels.
        const unsigned char header[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 64, 0, 64, 0, 24, 0};
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(header), sizeof header);
        out.write("0123456789", 10);
    }
    try {
        (void)Texture::load(path, ColorSpace::linear);
        FAIL("a truncated TGA loaded");
    } catch (const TextureError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find("damaged.tga") != std::string::npos);
        CHECK((message.find("truncated or corrupt image data: ") != std::string::npos ||
               message.find("cannot read image: ") != std::string::npos));
    }
}
