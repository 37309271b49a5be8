// Decoders for the two image formats glTF allows and most texture files use:
// PNG through libpng, JPEG through libjpeg-turbo, straight into a texture's
// level 0 (RGBA8 words, r in the low byte). They give exactly the texels
// OpenImageIO 2.4 gave before (the same libraries with the same settings, its
// 16→8-bit rounding and its PNG alpha association; tests/texture/
// test_image_decoders.cpp decodes the same files both ways). Other formats go
// through the OpenImageIO module (oiio_module_loader.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>

namespace tessera::texture {

// Why a decode failed, without the source's name (the caller adds it).
// `header` failures mean the bytes are not a readable image of that format at
// all; the others are damaged or truncated pixel data.
class ImageDecodeError : public std::runtime_error {
public:
    ImageDecodeError(bool header, const std::string& reason) : std::runtime_error(reason), header_(header) {}
    bool header() const { return header_; }

private:
    bool header_;
};

// Called once the header is read, with the image's size: checks it (throwing
// to refuse) and returns where level 0's width·height RGBA8 words go.
using Level0Allocator = std::function<std::uint32_t*(int width, int height)>;

// PNG colour with alpha: kept straight as the file stores it, or associated
// (premultiplied) as OpenImageIO 2.4 does by default, in the file's encoded
// values — with the file's gAMA exponent when it has one.
enum class PngAlpha { straight, associated };

bool has_png_signature(std::span<const std::uint8_t> bytes);
bool has_jpeg_signature(std::span<const std::uint8_t> bytes);
bool has_webp_signature(std::span<const std::uint8_t> bytes);  // RIFF....WEBP
bool has_avif_signature(std::span<const std::uint8_t> bytes);  // ....ftypavif (or avis)

// Grey → (g, g, g, 255), grey + alpha → (g, g, g, a), palette and tRNS
// expanded, 1/2/4-bit grey scaled to 8 bits (libpng), 16-bit samples rounded
// to 8 bits. Throws ImageDecodeError, or whatever `allocate` throws.
void decode_png(std::span<const std::uint8_t> bytes, PngAlpha alpha, const Level0Allocator& allocate);

// Greyscale → (g, g, g, 255); YCbCr and RGB → (r, g, b, 255); CMYK and YCCK
// → RGB as OpenImageIO converts them (R = C·K with Adobe's inverted values).
void decode_jpeg(std::span<const std::uint8_t> bytes, const Level0Allocator& allocate);

// WebP (lossy or lossless, with or without alpha; not animated) by libwebp,
// and AVIF (its first image, any bit depth, converted to 8-bit RGBA by libavif
// with its default YUV coefficients) by libavif (webp_avif_decoders.cpp).
void decode_webp(std::span<const std::uint8_t> bytes, const Level0Allocator& allocate);
void decode_avif(std::span<const std::uint8_t> bytes, const Level0Allocator& allocate);

// A 16-bit sample → 8 bits as OpenImageIO converts it: through float,
// round-half-up: uint8(v/65535·255 + ½).
std::uint8_t unorm16_to_unorm8(std::uint16_t value);

}  // namespace tessera::texture
