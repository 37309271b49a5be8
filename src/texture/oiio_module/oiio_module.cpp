// The OpenImageIO module (oiio_module_abi.hpp): texture files in the formats
// tessera does not decode itself (TGA, TIFF, EXR, HDR, BMP, ...), read with
// OpenImageIO exactly as texture_load.cpp read every file before.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "texture/oiio_module/oiio_module_abi.hpp"

namespace {

void set_error(char* error, std::size_t error_size, std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');  // the CLI prints one line
    while (!message.empty() && message.back() == ' ') message.pop_back();
    if (message.empty()) message = "unknown error";
    std::snprintf(error, error_size, "%s", message.c_str());
}

// Decodes `path` in bands of rows of Sample (UINT8 or FLOAT) into sink.
template <class Sample, class Sink>
int read_image(const char* path, const Sink* sink, OIIO::TypeDesc type, char* error, std::size_t error_size,
               int* header_failed) {
    *header_failed = 0;
    if (error_size > 0) error[0] = '\0';
    try {
        // Straight (unassociated) alpha as stored: OpenImageIO would otherwise
        // premultiply PNG colour by alpha, in the encoded (sRGB) values.
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        auto input = OIIO::ImageInput::open(path, &config);
        if (!input) {
            *header_failed = 1;
            set_error(error, error_size, OIIO::geterror());
            return 0;
        }
        const OIIO::ImageSpec& spec = input->spec();
        if (!sink->begin(sink->context, spec.width, spec.height, spec.depth, spec.nchannels)) return 0;
        // Decoded in bands of rows straight to 8 bits (OpenImageIO rounds 16-bit and float data).
        const int channels = std::min(spec.nchannels, 4);
        const std::size_t row_samples = std::size_t(spec.width) * std::size_t(channels);
        const int band_rows = std::max(1, std::min(spec.height, int((1 << 20) / (std::size_t(spec.width) * 4) + 1)));
        std::vector<Sample> band(row_samples * std::size_t(band_rows));
        for (int y = 0; y < spec.height; y += band_rows) {
            const int y_end = std::min(spec.height, y + band_rows);
            if (!input->read_scanlines(0, 0, spec.y + y, spec.y + y_end, 0, 0, channels, type,
                                       band.data())) {
                set_error(error, error_size, input->geterror());
                return 0;
            }
            if (!sink->rows(sink->context, y, y_end, band.data())) return 0;
        }
        return 1;
    } catch (const std::exception& e) {
        set_error(error, error_size, e.what());
        return 0;
    }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int tessera_oiio_read_image_v1(
    const char* path, const TesseraImageSink* sink, char* error, std::size_t error_size, int* header_failed) {
    return read_image<std::uint8_t>(path, sink, OIIO::TypeDesc::UINT8, error, error_size, header_failed);
}

extern "C" __attribute__((visibility("default"))) int tessera_oiio_read_float_image_v1(
    const char* path, const TesseraFloatImageSink* sink, char* error, std::size_t error_size, int* header_failed) {
    return read_image<float>(path, sink, OIIO::TypeDesc::FLOAT, error, error_size, header_failed);
}
