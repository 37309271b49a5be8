// JPEG through libjpeg-turbo (image_decoders.hpp), with the decompressor's
// defaults as OpenImageIO uses them (islow DCT, fancy upsampling). libjpeg
// reports errors by longjmp: the functions that call into it while it may fail
// set their jump point and hold no C++ object with a destructor.
#include <csetjmp>
#include <cstdio>
#include <string>
#include <vector>

#include <jpeglib.h>
#include <jerror.h>  // after jpeglib.h: the message codes

#include "texture/image_decoders.hpp"

namespace tessera::texture {

namespace {

struct JpegErrorManager {
    jpeg_error_mgr pub;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX] = "";
};

void on_jpeg_error(j_common_ptr cinfo) {
    auto* errors = reinterpret_cast<JpegErrorManager*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, errors->message);
    std::longjmp(errors->jump, 1);
}

// Warnings about data libjpeg recovers from are not printed; a file that ends
// early is an error (libjpeg would fill the rest grey), as for PNG.
void on_jpeg_warning(j_common_ptr cinfo, int level) {
    if (level < 0 && cinfo->err->msg_code == JWRN_JPEG_EOF) on_jpeg_error(cinfo);
}

// How libjpeg hands out the rows and how they become RGBA8.
enum class JpegLayout { rgba, grey, cmyk };

bool read_jpeg_header(jpeg_decompress_struct* cinfo, JpegErrorManager* errors, JpegLayout* layout) {
    if (setjmp(errors->jump)) return false;
    jpeg_read_header(cinfo, TRUE);
    switch (cinfo->jpeg_color_space) {
        case JCS_GRAYSCALE: *layout = JpegLayout::grey; break;
        case JCS_CMYK:
        case JCS_YCCK:
            cinfo->out_color_space = JCS_CMYK;  // YCCK → CMYK by libjpeg; CMYK → RGB below
            *layout = JpegLayout::cmyk;
            break;
        default:
            // YCbCr or RGB: libjpeg-turbo writes RGBA8 itself (the same RGB as
            // JCS_RGB, alpha 255), so level 0 needs no second pass.
            cinfo->out_color_space = JCS_EXT_RGBA;
            *layout = JpegLayout::rgba;
    }
    jpeg_start_decompress(cinfo);
    return true;
}

bool read_jpeg_rows(jpeg_decompress_struct* cinfo, JpegErrorManager* errors, JSAMPARRAY rows, int count) {
    if (setjmp(errors->jump)) return false;
    int done = 0;
    while (done < count) {
        const JDIMENSION read = jpeg_read_scanlines(cinfo, rows + done, JDIMENSION(count - done));
        if (read == 0) {
            std::snprintf(errors->message, sizeof errors->message, "no more scanlines");
            return false;
        }
        done += int(read);
    }
    return true;
}

bool finish_jpeg(jpeg_decompress_struct* cinfo, JpegErrorManager* errors) {
    if (setjmp(errors->jump)) return false;
    jpeg_finish_decompress(cinfo);
    return true;
}

struct JpegDecompress {
    jpeg_decompress_struct cinfo{};
    JpegErrorManager errors;
    JpegDecompress() {
        cinfo.err = jpeg_std_error(&errors.pub);
        errors.pub.error_exit = on_jpeg_error;
        errors.pub.emit_message = on_jpeg_warning;
        jpeg_create_decompress(&cinfo);
    }
    ~JpegDecompress() { jpeg_destroy_decompress(&cinfo); }
};

// OpenImageIO's CMYK → RGB (jpeginput.cpp): JPEG stores CMYK inverted, so
// R = C·K in [0, 1], rounded back to 8 bits.
std::uint8_t cmyk_channel(std::uint8_t ink, std::uint8_t black) {
    const float value = (static_cast<float>(ink) * (1.0f / 255.0f)) * (static_cast<float>(black) * (1.0f / 255.0f));
    return static_cast<std::uint8_t>(value * 255.0f + 0.5f);
}

}  // namespace

bool has_jpeg_signature(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 2 && bytes[0] == 0xFF && bytes[1] == 0xD8;
}

void decode_jpeg(std::span<const std::uint8_t> bytes, const Level0Allocator& allocate) {
    if (!has_jpeg_signature(bytes)) throw ImageDecodeError(true, "not a JPEG file (bad signature)");
    JpegDecompress d;
    jpeg_mem_src(&d.cinfo, bytes.data(), static_cast<unsigned long>(bytes.size()));
    JpegLayout layout = JpegLayout::rgba;
    if (!read_jpeg_header(&d.cinfo, &d.errors, &layout)) throw ImageDecodeError(true, d.errors.message);
    const int width = int(d.cinfo.output_width), height = int(d.cinfo.output_height);
    const int components = d.cinfo.output_components;
    if ((layout == JpegLayout::grey && components != 1) || (layout == JpegLayout::cmyk && components != 4) ||
        (layout == JpegLayout::rgba && components != 4))
        throw ImageDecodeError(true, "unsupported JPEG colour space (" + std::to_string(d.cinfo.num_components) +
                                         " components)");
    // Every 8x8 block of the first component costs at least one bit even in a
    // progressive file (its DC scan); fewer bytes mean the data is missing and
    // libjpeg would pad it out (a 32x32 file claiming 16384^2 decoded to 1 GB).
    const std::uint64_t blocks = (std::uint64_t(width) + 7) / 8 * ((std::uint64_t(height) + 7) / 8);
    if (blocks / 8 > bytes.size())
        throw ImageDecodeError(true, "the header claims " + std::to_string(width) + "x" + std::to_string(height) +
                                         ", which needs at least " + std::to_string(blocks / 8) +
                                         " bytes of JPEG data (a bit per 8x8 block); the file has " +
                                         std::to_string(bytes.size()));
    std::uint32_t* const level0 = allocate(width, height);

    if (layout == JpegLayout::rgba) {
        std::vector<JSAMPROW> rows(static_cast<std::size_t>(height));
        for (int y = 0; y < height; ++y) rows[std::size_t(y)] = reinterpret_cast<JSAMPROW>(level0 + std::size_t(y) * width);
        if (!read_jpeg_rows(&d.cinfo, &d.errors, rows.data(), height)) throw ImageDecodeError(false, d.errors.message);
    } else {
        // One row at a time through a small buffer, expanded into level 0.
        std::vector<JSAMPLE> row(static_cast<std::size_t>(width) * static_cast<std::size_t>(components));
        JSAMPROW row_pointer = row.data();
        for (int y = 0; y < height; ++y) {
            if (!read_jpeg_rows(&d.cinfo, &d.errors, &row_pointer, 1)) throw ImageDecodeError(false, d.errors.message);
            std::uint32_t* out = level0 + std::size_t(y) * width;
            for (int x = 0; x < width; ++x) {
                std::uint32_t r, g, b;
                if (layout == JpegLayout::grey) {
                    r = g = b = row[std::size_t(x)];
                } else {
                    const JSAMPLE* cmyk = row.data() + std::size_t(x) * 4;
                    r = cmyk_channel(cmyk[0], cmyk[3]);
                    g = cmyk_channel(cmyk[1], cmyk[3]);
                    b = cmyk_channel(cmyk[2], cmyk[3]);
                }
                out[x] = r | g << 8 | b << 16 | 0xFF000000u;
            }
        }
    }
    if (!finish_jpeg(&d.cinfo, &d.errors)) throw ImageDecodeError(false, d.errors.message);
}

}  // namespace tessera::texture
