// Texture::load and Texture::decode (texture.hpp): an image file or encoded bytes into level 0,
// then the mips. PNG, JPEG, WebP and AVIF in process (image_decoders.hpp), other formats through
// the OpenImageIO module (oiio_module_loader.hpp).
#include "texture/texture.hpp"

#include <cctype>
#include <cstring>
#include <exception>
#include <initializer_list>
#include <string>
#include <vector>

#include "io/input_file.hpp"
#include "io/memory_budget.hpp"
#include "texture/image_decoders.hpp"
#include "texture/oiio_module_loader.hpp"

#include "texture/texture_internal.hpp"

namespace tessera::texture {

using namespace detail;

namespace {

// Built by appending: g++ 12 warns falsely (-Wrestrict) about "'" + std::string.
std::string quoted(const std::filesystem::path& path) {
    std::string text(1, '\'');
    text += path.string();
    text += '\'';
    return text;
}

// OpenImageIO's messages may span lines; the CLI prints one.
std::string one_line(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return message.empty() ? std::string("unknown error") : message;
}

}  // namespace

// Decodes an image into level 0, then builds the mips. PNG and JPEG by
// image_decoders.hpp, other formats through OpenImageIO's module.
struct ImageDecoder {
    // `header_prefix`: "cannot read image" (a file) or "cannot decode image" (bytes in memory).
    static Texture decode_bytes(std::span<const std::uint8_t> bytes, const std::string& source,
                                ColorSpace color_space, PngAlpha png_alpha, const char* header_prefix);
    static Texture decode_with_module(const std::filesystem::path& path, const std::string& source,
                                      ColorSpace color_space);
};

Texture ImageDecoder::decode_bytes(std::span<const std::uint8_t> bytes, const std::string& source,
                                   ColorSpace color_space, PngAlpha png_alpha, const char* header_prefix) {
    Texture texture;
    const Level0Allocator allocate = [&](int width, int height) {
        check_size(source, width, height);
        try {
            texture.allocate(width, height, color_space);
        } catch (const io::MemoryBudgetError& e) {
            fail(source, e.what());
        }
        return texture.texels_.get();
    };
    // Decoding writes RGBA8 straight into level 0: there is no separate upload.
    const auto start = std::chrono::steady_clock::now();
    try {
        if (has_png_signature(bytes)) decode_png(bytes, png_alpha, allocate);
        else if (has_webp_signature(bytes)) decode_webp(bytes, allocate);
        else if (has_avif_signature(bytes)) decode_avif(bytes, allocate);
        else decode_jpeg(bytes, allocate);
    } catch (const ImageDecodeError& e) {
        fail(source, (e.header() ? std::string(header_prefix) + ": " : "truncated or corrupt image data: ") +
                         one_line(e.what()));
    }
    build_times().decode_ns += nanoseconds_since(start);
    texture.build_mip_chain();
    return texture;
}

namespace {

// The module's sink: level 0 of `texture`, filled band by band; an exception
// thrown here is kept and rethrown once the module has returned.
struct ModuleSink {
    const std::string* source;
    ColorSpace color_space;
    Texture* texture;
    std::uint32_t* level0 = nullptr;
    int width = 0;
    int channels = 0;
    std::exception_ptr failure;
    std::int64_t upload_ns = 0;
    std::uint64_t file_bytes = 0;  // what the header's size must be possible from
};

}  // namespace

Texture ImageDecoder::decode_with_module(const std::filesystem::path& path, const std::string& source,
                                         ColorSpace color_space) {
    const TesseraReadImage read_image = oiio_module_reader(source);
    Texture texture;
    ModuleSink sink_state{&source, color_space, &texture, nullptr, 0, 0, nullptr, 0, 0};
    try {
        sink_state.file_bytes = io::check_input_file(path, io::memory_budget(), "texture");
    } catch (const io::InputFileError& e) {
        fail(source, e.reason());
    }
    const auto begin = [](void* context, int width, int height, int depth, int channels) -> int {
        auto* s = static_cast<ModuleSink*>(context);
        try {
            check_size(*s->source, width, height);
            try {
                io::check_decoded_size(s->file_bytes, std::uint64_t(width) * std::uint64_t(height) *
                                                          std::uint64_t(std::max(channels, 1)),
                                       "a " + std::to_string(width) + "x" + std::to_string(height) + " image");
            } catch (const io::MemoryBudgetError& e) {
                fail(*s->source, e.what());
            }
            if (depth > 1) fail(*s->source, "volume images are not supported (depth " + std::to_string(depth) + ")");
            if (channels < 1) fail(*s->source, "no channels");
            try {
                s->texture->allocate(width, height, s->color_space);
            } catch (const io::MemoryBudgetError& e) {
                fail(*s->source, e.what());
            }
            s->level0 = s->texture->texels_.get();
            s->width = width;
            s->channels = std::min(channels, 4);
            return 1;
        } catch (...) {
            s->failure = std::current_exception();
            return 0;
        }
    };
    const auto rows = [](void* context, int y_begin, int y_end, const std::uint8_t* samples) -> int {
        auto* s = static_cast<ModuleSink*>(context);
        const auto start = std::chrono::steady_clock::now();
        expand_to_rgba8(samples, s->channels, std::size_t(s->width) * std::size_t(y_end - y_begin),
                        s->level0 + std::size_t(y_begin) * std::size_t(s->width));
        s->upload_ns += nanoseconds_since(start);
        return 1;
    };
    const TesseraImageSink sink{&sink_state, begin, rows};
    char error[512] = "";
    int header_failed = 0;
    const auto start = std::chrono::steady_clock::now();
    const int ok = read_image(path.c_str(), &sink, error, sizeof error, &header_failed);
    if (sink_state.failure) std::rethrow_exception(sink_state.failure);
    if (!ok)
        fail(source, (header_failed ? "cannot read image: " : "truncated or corrupt image data: ") + one_line(error));
    build_times().decode_ns += nanoseconds_since(start) - sink_state.upload_ns;
    build_times().upload_ns += sink_state.upload_ns;
    texture.build_mip_chain();
    return texture;
}

namespace {

bool has_extension(const std::filesystem::path& path, std::initializer_list<const char*> extensions) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char* e : extensions)
        if (ext == e) return true;
    return false;
}

// The whole file (at most max_bytes), or its first `prefix` bytes; a FIFO or device is refused by name.
std::vector<std::uint8_t> read_bytes(const std::filesystem::path& path, const std::string& source,
                                     std::uint64_t max_bytes, std::size_t prefix = std::size_t(-1)) {
    try {
        if (prefix != std::size_t(-1)) return io::read_input_prefix(path, prefix, "texture");
        return io::read_input_file(path, max_bytes, "texture");
    } catch (const io::InputFileError& e) {
        fail(source, e.reason());
    }
}

}  // namespace

Texture Texture::load(const std::filesystem::path& path, ColorSpace color_space) {
    const std::string source = "texture " + quoted(path);
    // An encoded image is smaller than the texels it decodes to, which the budget bounds.
    const std::uint64_t max_bytes = io::memory_budget();
    std::uint64_t size = 0;
    try {
        size = io::check_input_file(path, max_bytes, "texture");
    } catch (const io::InputFileError& e) {
        fail(source, e.reason());
    }
    if (size == 0) fail(source, "empty file (0 bytes)");

    // The format is told by the bytes; a .png or .jpg file that is neither is
    // refused here, anything else goes to OpenImageIO.
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::uint8_t> signature = read_bytes(path, source, max_bytes, 12);
    if (!can_decode(signature)) {
        if (has_extension(path, {".png", ".jpg", ".jpeg"}))
            fail(source, "cannot read image: neither a PNG nor a JPEG file (bad signature)");
        return ImageDecoder::decode_with_module(path, source, color_space);
    }
    const std::vector<std::uint8_t> bytes = read_bytes(path, source, max_bytes);
    build_times().decode_ns += nanoseconds_since(start);
    // Straight (unassociated) alpha as stored.
    return ImageDecoder::decode_bytes(bytes, source, color_space, PngAlpha::straight, "cannot read image");
}

bool Texture::can_decode(std::span<const std::uint8_t> encoded) {
    return has_jpeg_signature(encoded) || (encoded.size() >= 4 && std::memcmp(encoded.data(), "\x89PNG", 4) == 0) ||
           has_webp_signature(encoded) || has_avif_signature(encoded);
}

Texture Texture::decode(std::span<const std::uint8_t> encoded, const std::string& source, ColorSpace color_space) {
    if (!can_decode(encoded)) fail(source, "is neither PNG, JPEG, WebP nor AVIF");
    // Straight alpha as stored: glTF's base colour is not premultiplied, and
    // OPAQUE ignores alpha altogether (it used to be associated here, as
    // OpenImageIO does by default, which darkened colour where alpha was low).
    return ImageDecoder::decode_bytes(encoded, source, color_space, PngAlpha::straight, "cannot decode image");
}

}  // namespace tessera::texture
