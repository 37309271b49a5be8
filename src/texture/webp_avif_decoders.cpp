// WebP through libwebp and AVIF through libavif (image_decoders.hpp): the two
// formats glTF files carry with EXT_texture_webp and EXT_texture_avif. Both
// decode straight into level 0 as 8-bit RGBA, alpha straight (unassociated),
// as the files store it. libavif is opened with dlopen on the first AVIF
// image: linked, it and its codecs (aom, dav1d, rav1e, SVT-AV1, libgav1,
// libyuv, abseil: 23 libraries) would load at every start of `tessera`.
#include <dlfcn.h>

#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>

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

namespace {

// The libavif functions decode_avif calls, from the shared library Debian's
// libavif15 installs (the one libavif-dev's headers describe).
struct Libavif {
    decltype(&avifDecoderCreate) decoder_create = nullptr;
    decltype(&avifDecoderDestroy) decoder_destroy = nullptr;
    decltype(&avifDecoderSetIOMemory) set_io_memory = nullptr;
    decltype(&avifDecoderParse) parse = nullptr;
    decltype(&avifDecoderNextImage) next_image = nullptr;
    decltype(&avifRGBImageSetDefaults) rgb_defaults = nullptr;
    decltype(&avifImageYUVToRGB) yuv_to_rgb = nullptr;
    decltype(&avifResultToString) result_string = nullptr;
    std::string error;  // why it could not be opened; empty when it was
};

const Libavif& libavif() {
    static Libavif lib;
    static std::once_flag once;
    std::call_once(once, [] {
        void* handle = dlopen("libavif.so.15", RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
            lib.error = std::string("AVIF needs libavif.so.15 (Debian's libavif15): ") + dlerror();
            return;
        }
        const auto symbol = [&](auto& function, const char* name) {
            function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(dlsym(handle, name));
            if (function == nullptr && lib.error.empty()) lib.error = std::string("libavif.so.15 has no ") + name;
        };
        symbol(lib.decoder_create, "avifDecoderCreate");
        symbol(lib.decoder_destroy, "avifDecoderDestroy");
        symbol(lib.set_io_memory, "avifDecoderSetIOMemory");
        symbol(lib.parse, "avifDecoderParse");
        symbol(lib.next_image, "avifDecoderNextImage");
        symbol(lib.rgb_defaults, "avifRGBImageSetDefaults");
        symbol(lib.yuv_to_rgb, "avifImageYUVToRGB");
        symbol(lib.result_string, "avifResultToString");
    });
    return lib;
}

}  // namespace

void decode_avif(std::span<const std::uint8_t> bytes, const Level0Allocator& allocate) {
    const Libavif& avif = libavif();
    if (!avif.error.empty()) throw ImageDecodeError(true, avif.error);
    const std::unique_ptr<avifDecoder, decltype(avif.decoder_destroy)> decoder(avif.decoder_create(),
                                                                              avif.decoder_destroy);
    if (!decoder) throw ImageDecodeError(false, "out of memory");
    decoder->maxThreads = 1;  // textures are already decoded in parallel, one per thread
    const avifResult parsed = avif.set_io_memory(decoder.get(), bytes.data(), bytes.size());
    if (parsed != AVIF_RESULT_OK) throw ImageDecodeError(true, avif.result_string(parsed));
    if (const avifResult header = avif.parse(decoder.get()); header != AVIF_RESULT_OK)
        throw ImageDecodeError(true, std::string("not a readable AVIF image: ") + avif.result_string(header));
    if (const avifResult frame = avif.next_image(decoder.get()); frame != AVIF_RESULT_OK)
        throw ImageDecodeError(false, std::string("AVIF image data does not decode: ") + avif.result_string(frame));
    const avifImage* decoded = decoder->image;
    avifRGBImage rgb;
    avif.rgb_defaults(&rgb, decoded);
    rgb.format = AVIF_RGB_FORMAT_RGBA;
    rgb.depth = 8;
    rgb.alphaPremultiplied = AVIF_FALSE;  // straight alpha, as glTF means it
    rgb.pixels = reinterpret_cast<std::uint8_t*>(allocate(int(decoded->width), int(decoded->height)));
    rgb.rowBytes = decoded->width * 4;
    if (const avifResult converted = avif.yuv_to_rgb(decoded, &rgb); converted != AVIF_RESULT_OK)
        throw ImageDecodeError(false, std::string("AVIF colour conversion failed: ") + avif.result_string(converted));
}

}  // namespace tessera::texture
