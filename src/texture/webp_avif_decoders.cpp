// WebP through libwebp and AVIF through libavif (image_decoders.hpp): the two
// formats glTF files carry with EXT_texture_webp and EXT_texture_avif. Both
// decode straight into level 0 as 8-bit RGBA, alpha straight (unassociated),
// as the files store it.
#include <cstring>
#include <memory>
#include <string>

#include <avif/avif.h>
#include <webp/decode.h>

#include "texture/image_decoders.hpp"

namespace tessera::texture {

bool has_webp_signature(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0;
}

// An ISO-BMFF 'ftyp' box whose major brand is 'avif' (a still image) or 'avis' (a sequence).
bool has_avif_signature(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 12 && std::memcmp(bytes.data() + 4, "ftyp", 4) == 0 &&
           (std::memcmp(bytes.data() + 8, "avif", 4) == 0 || std::memcmp(bytes.data() + 8, "avis", 4) == 0);
}

void decode_webp(std::span<const std::uint8_t> bytes, const Level0Allocator& allocate) {
    WebPBitstreamFeatures features;
    if (WebPGetFeatures(bytes.data(), bytes.size(), &features) != VP8_STATUS_OK)
        throw ImageDecodeError(true, "not a readable WebP image (bad RIFF/VP8 header)");
    if (features.has_animation) throw ImageDecodeError(true, "animated WebP is not supported (a texture is one image)");
    std::uint32_t* level0 = allocate(features.width, features.height);
    const std::size_t row_bytes = std::size_t(features.width) * 4;
    // RGBA bytes in memory order are the texel word with r in its low byte.
    if (WebPDecodeRGBAInto(bytes.data(), bytes.size(), reinterpret_cast<std::uint8_t*>(level0),
                           row_bytes * std::size_t(features.height), int(row_bytes)) == nullptr)
        throw ImageDecodeError(false, "WebP image data does not decode");
}

void decode_avif(std::span<const std::uint8_t> bytes, const Level0Allocator& allocate) {
    const std::unique_ptr<avifDecoder, decltype(&avifDecoderDestroy)> decoder(avifDecoderCreate(), avifDecoderDestroy);
    const std::unique_ptr<avifImage, decltype(&avifImageDestroy)> image(avifImageCreateEmpty(), avifImageDestroy);
    if (!decoder || !image) throw ImageDecodeError(false, "out of memory");
    decoder->maxThreads = 1;  // textures are already decoded in parallel, one per thread
    const avifResult parsed = avifDecoderSetIOMemory(decoder.get(), bytes.data(), bytes.size());
    if (parsed != AVIF_RESULT_OK) throw ImageDecodeError(true, avifResultToString(parsed));
    if (const avifResult header = avifDecoderParse(decoder.get()); header != AVIF_RESULT_OK)
        throw ImageDecodeError(true, std::string("not a readable AVIF image: ") + avifResultToString(header));
    if (const avifResult frame = avifDecoderNextImage(decoder.get()); frame != AVIF_RESULT_OK)
        throw ImageDecodeError(false, std::string("AVIF image data does not decode: ") + avifResultToString(frame));
    const avifImage* decoded = decoder->image;
    avifRGBImage rgb;
    avifRGBImageSetDefaults(&rgb, decoded);
    rgb.format = AVIF_RGB_FORMAT_RGBA;
    rgb.depth = 8;
    rgb.alphaPremultiplied = AVIF_FALSE;  // straight alpha, as glTF means it
    rgb.pixels = reinterpret_cast<std::uint8_t*>(allocate(int(decoded->width), int(decoded->height)));
    rgb.rowBytes = decoded->width * 4;
    if (const avifResult converted = avifImageYUVToRGB(decoded, &rgb); converted != AVIF_RESULT_OK)
        throw ImageDecodeError(false, std::string("AVIF colour conversion failed: ") + avifResultToString(converted));
}

}  // namespace tessera::texture
