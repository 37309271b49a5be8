// Small WebP and AVIF images made in the tests by the same libraries that
// decode them (libwebp's lossless encoder, libavif's AV1 encoder).
#pragma once

#include <cstdint>
#include <vector>

#include <avif/avif.h>
#include <webp/encode.h>

namespace tessera::test {

// width × height straight RGBA bytes, lossless: decoding gives them back exactly
// where alpha is not 0 (the encoder may change the colour of invisible pixels).
inline std::vector<std::uint8_t> encode_webp_lossless(const std::vector<std::uint8_t>& rgba, int width, int height) {
    std::uint8_t* output = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), width, height, width * 4, &output);
    std::vector<std::uint8_t> bytes(output, output + size);
    WebPFree(output);
    return bytes;
}

// The same as AVIF (4:4:4, 8 bits, high quality but lossy: a few steps off).
inline std::vector<std::uint8_t> encode_avif(const std::vector<std::uint8_t>& rgba, int width, int height) {
    avifImage* image = avifImageCreate(std::uint32_t(width), std::uint32_t(height), 8, AVIF_PIXEL_FORMAT_YUV444);
    avifRGBImage rgb;
    avifRGBImageSetDefaults(&rgb, image);
    rgb.format = AVIF_RGB_FORMAT_RGBA;
    rgb.depth = 8;
    rgb.pixels = const_cast<std::uint8_t*>(rgba.data());
    rgb.rowBytes = std::uint32_t(width) * 4;
    std::vector<std::uint8_t> bytes;
    if (avifImageRGBToYUV(image, &rgb) == AVIF_RESULT_OK) {
        avifEncoder* encoder = avifEncoderCreate();
        encoder->minQuantizer = encoder->maxQuantizer = 4;
        encoder->minQuantizerAlpha = encoder->maxQuantizerAlpha = AVIF_QUANTIZER_LOSSLESS;
        encoder->speed = 10;
        avifRWData output = AVIF_DATA_EMPTY;
        if (avifEncoderWrite(encoder, image, &output) == AVIF_RESULT_OK) bytes.assign(output.data, output.data + output.size);
        avifRWDataFree(&output);
        avifEncoderDestroy(encoder);
    }
    avifImageDestroy(image);
    return bytes;
}

}  // namespace tessera::test
