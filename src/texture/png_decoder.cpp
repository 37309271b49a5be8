// PNG through libpng (image_decoders.hpp). libpng reports errors by longjmp:
// every function that calls into it while it may fail sets its jump point and
// holds no C++ object with a destructor between setjmp and the calls.
#include <csetjmp>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <png.h>

#include "texture/image_decoders.hpp"

namespace tessera::texture {

namespace {

// libpng's state for one decode: the input, the last error message.
struct PngStream {
    std::span<const std::uint8_t> bytes;
    std::size_t position = 0;
    char message[256] = "";
};

void on_png_error(png_structp png, png_const_charp message) {
    auto* stream = static_cast<PngStream*>(png_get_error_ptr(png));
    std::snprintf(stream->message, sizeof stream->message, "%s", message ? message : "unknown libpng error");
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}  // as OpenImageIO: warnings are not errors

void read_from_memory(png_structp png, png_bytep out, png_size_t length) {
    auto* stream = static_cast<PngStream*>(png_get_io_ptr(png));
    if (length > stream->bytes.size() - stream->position) png_error(png, "unexpected end of file");
    std::memcpy(out, stream->bytes.data() + stream->position, length);
    stream->position += length;
}

// The file's layout after the transforms OpenImageIO asks for (png_set_expand):
// 1–4 channels of 8 or 16 bits.
struct PngHeader {
    png_uint_32 width = 0, height = 0;
    int bit_depth = 0;
    int channels = 0;
    bool interlaced = false;
    bool has_alpha = false;   // channels 2 or 4 after expansion (alpha or tRNS)
    float gamma = 1.0f;       // OpenImageIO's "oiio:Gamma": 1 unless a gAMA chunk without sRGB says otherwise
};

// Reads the header and sets the transforms: expansion, byte order, and (for
// 8-bit data) grey → RGB and an opaque alpha filler, so rows come out RGBA8.
bool read_png_header(png_structp png, png_infop info, PngHeader* header) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_info(png, info);
    png_set_expand(png);
    const bool sixteen = png_get_bit_depth(png, info) == 16;
    if (sixteen) {
        png_set_swap(png);  // PNG is big-endian
    } else {
        png_set_gray_to_rgb(png);
        png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
    }
    const int color_type = png_get_color_type(png, info);
    header->has_alpha = (color_type & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(png, info, PNG_INFO_tRNS) != 0;
    int srgb_intent = 0;
    double file_gamma = 0.0;
    if (!png_get_sRGB(png, info, &srgb_intent) && png_get_gAMA(png, info, &file_gamma) && file_gamma > 0.0) {
        // OpenImageIO rounds the exponent to hundredths (2.2, not 2.19998).
        const float g = float(1.0 / file_gamma);
        header->gamma = std::round(100.0f * g) / 100.0f;
    }
    header->interlaced = png_get_interlace_type(png, info) != PNG_INTERLACE_NONE;
    if (header->interlaced) png_set_interlace_handling(png);
    png_read_update_info(png, info);
    header->width = png_get_image_width(png, info);
    header->height = png_get_image_height(png, info);
    header->bit_depth = png_get_bit_depth(png, info);
    header->channels = png_get_channels(png, info);
    return true;
}

bool read_png_rows(png_structp png, png_bytep* rows, png_uint_32 count) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_rows(png, rows, nullptr, count);
    return true;
}

bool read_png_image(png_structp png, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    return true;
}

// OpenImageIO 2.4's association of PNG alpha (pnginput.cpp, associateAlpha):
// in integers when the gamma is 1 (also for sRGB files), else colour times
// (alpha/max)^gamma, truncated. T is the sample type, max its largest value.
template <class T>
void associate_alpha(T* pixel, int channels, float gamma) {
    constexpr unsigned max = std::numeric_limits<T>::max();
    const int alpha = channels - 1;
    if (gamma == 1.0f) {
        for (int c = 0; c < alpha; ++c) pixel[c] = static_cast<T>((unsigned(pixel[c]) * pixel[alpha]) / max);
    } else {
        const float inv_max = static_cast<float>(1.0 / max);
        const float alpha_associate = std::pow(pixel[alpha] * inv_max, gamma);
        for (int c = 0; c < alpha; ++c) pixel[c] = static_cast<T>(pixel[c] * alpha_associate);
    }
}

// A 16-bit row of `channels` samples → RGBA8 words.
void expand_row16(const std::uint16_t* row, int width, int channels, bool associate, float gamma, std::uint32_t* out) {
    std::uint16_t pixel[4];
    for (int x = 0; x < width; ++x) {
        std::memcpy(pixel, row + std::size_t(x) * channels, sizeof(std::uint16_t) * std::size_t(channels));
        if (associate) associate_alpha(pixel, channels, gamma);
        std::uint8_t r, g, b, a = 0xFF;
        if (channels <= 2) {
            r = g = b = unorm16_to_unorm8(pixel[0]);
            if (channels == 2) a = unorm16_to_unorm8(pixel[1]);
        } else {
            r = unorm16_to_unorm8(pixel[0]);
            g = unorm16_to_unorm8(pixel[1]);
            b = unorm16_to_unorm8(pixel[2]);
            if (channels == 4) a = unorm16_to_unorm8(pixel[3]);
        }
        out[x] = std::uint32_t(r) | std::uint32_t(g) << 8 | std::uint32_t(b) << 16 | std::uint32_t(a) << 24;
    }
}

// Grey + alpha association on RGBA8 words: the grey value is r = g = b, so
// associating r and copying it gives what OpenImageIO gives for (Y, A).
void associate_row8(std::uint32_t* row, int width, float gamma) {
    for (int x = 0; x < width; ++x) {
        std::uint8_t pixel[4];
        std::memcpy(pixel, row + x, 4);  // r, g, b, a in memory order (little-endian words)
        associate_alpha(pixel, 4, gamma);
        std::memcpy(row + x, pixel, 4);
    }
}

struct PngReadStruct {
    png_structp png = nullptr;
    png_infop info = nullptr;
    ~PngReadStruct() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

// A small file whose header claims a huge image is refused before level 0 is
// allocated: deflate expands at most 1032:1, so the rows (a filter byte each,
// at the file's own bit depth) cannot be more than ~1032 times the file.
void check_png_data_present(std::span<const std::uint8_t> bytes, png_uint_32 width, png_uint_32 height) {
    if (bytes.size() < 26) return;  // libpng read the header, so it is there
    const int bit_depth = bytes[24];
    const int channels = bytes[25] == 2 ? 3 : bytes[25] == 4 ? 2 : bytes[25] == 6 ? 4 : 1;
    const std::uint64_t row_bits = std::uint64_t(width) * std::uint64_t(channels) * std::uint64_t(bit_depth);
    const std::uint64_t rows = std::uint64_t(height) * (1 + (row_bits + 7) / 8);
    constexpr std::uint64_t kMaxDeflateRatio = 1032;
    const std::uint64_t needed = rows / kMaxDeflateRatio;
    if (needed > bytes.size())
        throw ImageDecodeError(true, "the header claims " + std::to_string(width) + "x" + std::to_string(height) +
                                         ", which needs at least " + std::to_string(needed) +
                                         " bytes of compressed data; the file has " + std::to_string(bytes.size()));
}

}  // namespace

std::uint8_t unorm16_to_unorm8(std::uint16_t value) {
    // OpenImageIO: to float as v·(1/65535), then scaled_conversion: v·255 + ½, truncated.
    const float f = static_cast<float>(value) * (1.0f / 65535.0f);
    return static_cast<std::uint8_t>(f * 255.0f + 0.5f);
}

bool has_png_signature(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 8 && png_sig_cmp(bytes.data(), 0, 8) == 0;
}

void decode_png(std::span<const std::uint8_t> bytes, PngAlpha alpha, const Level0Allocator& allocate) {
    if (!has_png_signature(bytes)) throw ImageDecodeError(true, "not a PNG file (bad signature)");
    PngStream stream{bytes, 8};
    PngReadStruct s;
    s.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &stream, on_png_error, on_png_warning);
    if (!s.png) throw ImageDecodeError(true, "libpng: out of memory");
    s.info = png_create_info_struct(s.png);
    if (!s.info) throw ImageDecodeError(true, "libpng: out of memory");
    png_set_read_fn(s.png, &stream, read_from_memory);
    png_set_sig_bytes(s.png, 8);
    // OpenImageIO's PNG reader allows 65536 per side; ours refuses bigger
    // textures after the header (allocate), so libpng's own limit can stay.
    PngHeader header;
    if (!read_png_header(s.png, s.info, &header)) throw ImageDecodeError(true, stream.message);

    const int width = int(header.width), height = int(header.height);
    const std::size_t row_bytes = png_get_rowbytes(s.png, s.info);
    // The transforms promise RGBA8 rows for 8-bit data, 1-4 channels of 16 bits otherwise.
    const std::size_t sample_bytes = header.bit_depth == 16 ? 2 : 1;
    if ((header.bit_depth != 8 && header.bit_depth != 16) || (header.bit_depth == 8 && header.channels != 4) ||
        header.channels < 1 || header.channels > 4 ||
        row_bytes != std::size_t(header.width) * std::size_t(header.channels) * sample_bytes)
        throw ImageDecodeError(true, "unsupported PNG layout (" + std::to_string(header.channels) + " channels of " +
                                         std::to_string(header.bit_depth) + " bits)");
    check_png_data_present(bytes, header.width, header.height);
    std::uint32_t* const level0 = allocate(width, height);
    const bool associate = alpha == PngAlpha::associated && header.has_alpha;

    if (header.bit_depth == 8) {
        // RGBA8 straight into level 0 (the transforms made the rows that shape).
        std::vector<png_bytep> rows(static_cast<std::size_t>(height));
        for (int y = 0; y < height; ++y) rows[std::size_t(y)] = reinterpret_cast<png_bytep>(level0 + std::size_t(y) * width);
        const bool ok = header.interlaced ? read_png_image(s.png, rows.data())
                                          : read_png_rows(s.png, rows.data(), png_uint_32(height));
        if (!ok) throw ImageDecodeError(false, stream.message);
        if (associate)
            for (int y = 0; y < height; ++y) associate_row8(level0 + std::size_t(y) * width, width, header.gamma);
        return;
    }
    // 16 bits: a band of rows (the whole image when interlaced), converted as OpenImageIO converts.
    const int band_rows = header.interlaced ? height : std::max(1, std::min(height, int((1u << 20) / row_bytes) + 1));
    std::vector<std::uint16_t> band(row_bytes / 2 * std::size_t(band_rows));
    std::vector<png_bytep> rows(static_cast<std::size_t>(band_rows));
    for (int y = 0; y < band_rows; ++y)
        rows[std::size_t(y)] = reinterpret_cast<png_bytep>(band.data()) + std::size_t(y) * row_bytes;
    for (int y = 0; y < height; y += band_rows) {
        const int count = std::min(band_rows, height - y);
        const bool ok = header.interlaced ? read_png_image(s.png, rows.data())
                                          : read_png_rows(s.png, rows.data(), png_uint_32(count));
        if (!ok) throw ImageDecodeError(false, stream.message);
        for (int r = 0; r < count; ++r)
            expand_row16(band.data() + std::size_t(r) * (row_bytes / 2), width, header.channels, associate,
                         header.gamma, level0 + std::size_t(y + r) * width);
    }
}

}  // namespace tessera::texture
