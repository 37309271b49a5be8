// The interface between tessera and its OpenImageIO module (a plugin the
// renderer opens with dlopen only for texture files that are neither PNG nor
// JPEG, so that rendering common assets does not load OpenImageIO's ~260
// libraries). Plain C types: the module and the program agree on nothing else.
#pragma once

#include <cstddef>
#include <cstdint>

extern "C" {

// What the module hands back while it decodes, in bands of rows.
struct TesseraImageSink {
    void* context;
    // The image's size and channel count (the first min(channels, 4) are
    // delivered). Returns 0 to stop (the sink keeps its own reason).
    int (*begin)(void* context, int width, int height, int depth, int channels);
    // Rows [y_begin, y_end) of 8-bit samples, min(channels, 4) a pixel,
    // converted by OpenImageIO (16-bit and float data rounded). Returns 0 to stop.
    int (*rows)(void* context, int y_begin, int y_end, const std::uint8_t* samples);
};

// Reads the first subimage of `path`, colour kept as stored (unassociated
// alpha). Returns 1 on success; 0 with a one-line reason in `error` (empty
// when the sink stopped it), and in *header_failed whether the file could not
// be opened as an image at all.
typedef int (*TesseraReadImage)(const char* path, const TesseraImageSink* sink, char* error,
                                std::size_t error_size, int* header_failed);

// The same for scene-linear float images (environment maps): rows of 32-bit
// floats, min(channels, 4) a pixel, as OpenImageIO converts the stored data.
struct TesseraFloatImageSink {
    void* context;
    int (*begin)(void* context, int width, int height, int depth, int channels);
    int (*rows)(void* context, int y_begin, int y_end, const float* samples);
};
typedef int (*TesseraReadFloatImage)(const char* path, const TesseraFloatImageSink* sink, char* error,
                                     std::size_t error_size, int* header_failed);

}  // extern "C"

// The module's file name (beside the tessera binary) and its entry point.
inline constexpr const char* kTesseraOiioModuleFile = "tessera-oiio-module.so";
inline constexpr const char* kTesseraOiioModuleEntry = "tessera_oiio_read_image_v1";
inline constexpr const char* kTesseraOiioModuleFloatEntry = "tessera_oiio_read_float_image_v1";
