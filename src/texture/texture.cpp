// Texture loading, mip chain and the scalar reference samplers (texture.hpp).
// The sampling follows the GL 4.6 spec, §8.14 "Texture Minification" and
// §8.14.2 "Coordinate Wrapping and Texel Selection", term for term.
#include "texture/texture.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <initializer_list>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <system_error>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <sys/mman.h>

#include "io/input_file.hpp"
#include "io/memory_budget.hpp"
#include "simd/lane_padding.hpp"
#include "texture/image_decoders.hpp"
#include "texture/oiio_module_loader.hpp"

namespace tessera::texture {

namespace {

// Built by appending: g++ 12 warns falsely (-Wrestrict) about "'" + std::string.
std::string quoted(const std::filesystem::path& path) {
    std::string text(1, '\'');
    text += path.string();
    text += '\'';
    return text;
}

// source: "texture 'path'", "texture from_pixels", or the caller's label for an image in memory.
[[noreturn]] void fail(const std::string& source, const std::string& what) {
    throw TextureError(source + ": " + what);
}

// OpenImageIO's messages may span lines; the CLI prints one.
std::string one_line(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return message.empty() ? std::string("unknown error") : message;
}

void check_size(const std::string& source, long long width, long long height) {
    if (width <= 0 || height <= 0)
        fail(source, "zero size (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    if (width > kMaxTextureSize || height > kMaxTextureSize)
        fail(source, "size " + std::to_string(width) + "x" + std::to_string(height) + " is above the limit of " +
                         std::to_string(kMaxTextureSize) + " per side");
    // Level 0 and its mips (4/3 of it), RGBA8, before any is allocated.
    try {
        io::check_memory(std::uint64_t(width) * std::uint64_t(height) * 4 * 4 / 3,
                         "a " + std::to_string(width) + "x" + std::to_string(height) + " texture with its mips");
    } catch (const io::MemoryBudgetError& e) {
        fail(source, e.what());
    }
}

// min(hi, max(lo, x)) in this operand order: std::max returns its first
// argument when the comparison fails, so NaN becomes lo (as xsimd::max(x, lo)
// does in the kernels, by the hardware rule).
float clamp_nan_low(float x, float lo, float hi) { return std::min(hi, std::max(lo, x)); }

// GL_LINEAR along one axis: the two texel indices and the weight of the second.
//   x = coord·size − ½, i0 = wrap(⌊x⌋), i1 = wrap(⌊x⌋ + 1), α = frac(x)
// For repeat, coord is first reduced to [0, 1] (coord − ⌊coord⌋): the same
// texels (the pattern has period 1), without ⌊x⌋ overflowing an int. Clamping x
// to [−1, size] changes no result (beyond the edges both taps are the edge
// texel) and keeps the integer conversion defined.
struct AxisTaps {
    int i0, i1;
    float alpha;
};

// GL_MIRRORED_REPEAT has period 2: coord is reduced to [0, 2) (coord −
// 2⌊coord/2⌋), indices run over a 2·size pattern (one step of wrapping), and
// index m of it is texel m below size, else 2·size − 1 − m: GL's
// (size − 1) − mirror((i mod 2·size) − size), mirror(a) = a ≥ 0 ? a : −(1 + a).
int mirror_fold(int i, int size) {
    const int period = 2 * size;
    if (i < 0) i += period;
    if (i >= period) i -= period;
    return i < size ? i : period - 1 - i;
}

AxisTaps axis_taps(float coord, int size, float size_f, Wrap wrap) {
    if (wrap == Wrap::repeat) coord -= std::floor(coord);
    if (wrap == Wrap::mirrored_repeat) coord -= 2.0f * std::floor(coord * 0.5f);
    const float period_f = wrap == Wrap::mirrored_repeat ? 2.0f * size_f : size_f;
    const float x = clamp_nan_low(coord * size_f - 0.5f, -1.0f, period_f);
    const float x_floor = std::floor(x);
    AxisTaps taps{static_cast<int>(x_floor), static_cast<int>(x_floor) + 1, x - x_floor};
    if (wrap == Wrap::repeat) {
        // With coord in [0, 1], x is in [−1, size − ½]: one step of wrapping suffices.
        if (taps.i0 < 0) taps.i0 += size;
        if (taps.i1 >= size) taps.i1 -= size;
    } else if (wrap == Wrap::mirrored_repeat) {
        taps.i0 = mirror_fold(taps.i0, size);
        taps.i1 = mirror_fold(taps.i1, size);
    } else {
        taps.i0 = std::clamp(taps.i0, 0, size - 1);
        taps.i1 = std::clamp(taps.i1, 0, size - 1);
    }
    return taps;
}

// GL_NEAREST along one axis: i = wrap(⌊coord·size⌋), coords reduced as for axis_taps.
int nearest_tap(float coord, int size, float size_f, Wrap wrap) {
    if (wrap == Wrap::repeat) coord -= std::floor(coord);
    if (wrap == Wrap::mirrored_repeat) coord -= 2.0f * std::floor(coord * 0.5f);
    const float period_f = wrap == Wrap::mirrored_repeat ? 2.0f * size_f : size_f;
    const int i = static_cast<int>(std::floor(clamp_nan_low(coord * size_f, -1.0f, period_f)));
    if (wrap == Wrap::repeat) return i >= size ? i - size : i < 0 ? i + size : i;  // size: rounded up; −1: NaN
    if (wrap == Wrap::mirrored_repeat) return mirror_fold(i, size);
    return std::clamp(i, 0, size - 1);
}

// Weights of the area-weighted box filter from `from` texels down to `to`
// along one axis: output texel i covers [i·r, (i+1)·r) of the input, r = from/to.
struct FilterTap {
    int source;
    float weight;
};

std::vector<std::vector<FilterTap>> box_filter_taps(int from, int to) {
    const double ratio = static_cast<double>(from) / to;
    std::vector<std::vector<FilterTap>> taps(static_cast<std::size_t>(to));
    for (int i = 0; i < to; ++i) {
        const double begin = i * ratio;
        const double end = (i + 1) * ratio;
        for (int j = static_cast<int>(std::floor(begin)); j < from && j < end; ++j) {
            const double covered = std::min(end, j + 1.0) - std::max(begin, static_cast<double>(j));
            if (covered > 0.0) taps[static_cast<std::size_t>(i)].push_back({j, static_cast<float>(covered / ratio)});
        }
    }
    return taps;
}

}  // namespace

float srgb_to_linear(float encoded) {
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return static_cast<float>(std::pow((static_cast<double>(encoded) + 0.055) / 1.055, 2.4));
}

const std::array<float, 256>& srgb_decode_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int k = 0; k < 256; ++k) t[static_cast<std::size_t>(k)] = srgb_to_linear(static_cast<float>(k) / 255.0f);
        return t;
    }();
    return table;
}

const std::array<float, 256>& unorm8_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        // k / 255.0f, the same IEEE division the SIMD sampler does.
        for (int k = 0; k < 256; ++k) t[static_cast<std::size_t>(k)] = static_cast<float>(k) / 255.0f;
        return t;
    }();
    return table;
}

namespace {

// round(255·x) for x clamped to [0, 1]: floor(255·x + ½), and floor is the
// integer conversion for these non-negative values (no libm call).
inline std::uint8_t unorm8_from_linear(float linear) {
    return static_cast<std::uint8_t>(static_cast<int>(clamp_nan_low(linear, 0.0f, 1.0f) * 255.0f + 0.5f));
}

}  // namespace

std::uint8_t encode_unorm8(float linear) { return unorm8_from_linear(linear); }

namespace {

// round(255·encode(x)) steps from k to k+1 where encode(x) = (k + ½)/255,
// that is at x = decode((k + ½)/255): 255 thresholds in linear light.
// first_code[i] is the code of x = i/kBins; the code of x in [i/kBins,
// (i+1)/kBins) is then at most a step or two above (the steepest part of the
// curve, slope 12.92·255 near 0, puts 0.8 steps in a bin): exact, no pow.
struct SrgbEncoder {
    static constexpr int kBins = 4096;
    std::array<float, 256> thresholds{};  // [255] = +∞, a sentinel
    std::array<std::uint8_t, kBins> first_code{};

    SrgbEncoder() {
        for (int k = 0; k < 255; ++k) {
            const double c = (k + 0.5) / 255.0;
            thresholds[static_cast<std::size_t>(k)] =
                static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        thresholds[255] = INFINITY;
        for (int i = 0; i < kBins; ++i) first_code[static_cast<std::size_t>(i)] = search(static_cast<float>(i) / kBins);
    }
    std::uint8_t search(float x) const {
        return static_cast<std::uint8_t>(std::upper_bound(thresholds.begin(), thresholds.end() - 1, x) - thresholds.begin());
    }
    std::uint8_t encode(float x) const {
        x = clamp_nan_low(x, 0.0f, 1.0f);
        const int bin = std::min(kBins - 1, static_cast<int>(x * kBins));
        // x >= bin/kBins up to float rounding of x·kBins: start one bin lower to be safe.
        unsigned code = first_code[static_cast<std::size_t>(std::max(0, bin - 1))];
        while (x >= thresholds[code]) ++code;
        return static_cast<std::uint8_t>(code);
    }
};

const SrgbEncoder& srgb_encoder() {
    static const SrgbEncoder encoder;
    return encoder;
}

}  // namespace

std::uint8_t encode_srgb8(float linear) { return srgb_encoder().encode(linear); }

TextureBuildTimes& build_times() {
    static TextureBuildTimes times;
    return times;
}

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

// Room for `count` texels. From 2 MiB up, 2 MiB-aligned and advised into
// transparent huge pages before the first touch: on our VMs a 4 KiB page
// fault is expensive, and a 2048² map with its mips is 5,500 of them.
std::uint32_t* allocate_texels(std::size_t count) {
    const std::size_t bytes = count * sizeof(std::uint32_t);
    if (bytes < kHugePage) {
        void* memory = std::malloc(bytes);
        if (memory == nullptr) throw std::bad_alloc();
        return static_cast<std::uint32_t*>(memory);
    }
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* memory = std::aligned_alloc(kHugePage, rounded);
    if (memory == nullptr) throw std::bad_alloc();
    madvise(memory, rounded, MADV_HUGEPAGE);  // a hint: harmless where huge pages are off
    return static_cast<std::uint32_t*>(memory);
}

}  // namespace

// Bytes of texels in every live texture of the process (six 16384² maps are 8.6 GB).
std::atomic<std::uint64_t> g_live_texel_bytes{0};

void Texture::FreeTexels::operator()(std::uint32_t* texels) const {
    std::free(texels);
    g_live_texel_bytes.fetch_sub(bytes, std::memory_order_relaxed);
}

void Texture::allocate(int width, int height, ColorSpace color_space) {
    color_space_ = color_space;
    levels_.clear();
    std::size_t offset = 0;
    for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        levels_.push_back({w, h, offset});
        offset += static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
        if (w == 1 && h == 1) break;
    }
    // Every level's room at once, uninitialised (every texel is written next);
    // the pages are touched by the threads that fill them.
    const std::uint64_t bytes = std::uint64_t(offset) * sizeof(std::uint32_t);
    const std::uint64_t live = g_live_texel_bytes.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    if (live > io::memory_budget()) {
        g_live_texel_bytes.fetch_sub(bytes, std::memory_order_relaxed);
        io::check_memory(live, "this " + std::to_string(width) + "x" + std::to_string(height) +
                                   " texture with every other one loaded");
    }
    texels_.reset();
    try {
        texels_ = std::unique_ptr<std::uint32_t[], FreeTexels>(allocate_texels(offset), FreeTexels{bytes});
    } catch (...) {
        g_live_texel_bytes.fetch_sub(bytes, std::memory_order_relaxed);
        throw;
    }
    texel_count_ = offset;
    for (std::size_t i = 0; i < levels_.size(); ++i) {
        width_table_[i] = levels_[i].width;
        height_table_[i] = levels_[i].height;
        offset_table_[i] = static_cast<std::int32_t>(levels_[i].offset);
        width_f_table_[i] = static_cast<float>(levels_[i].width);
        height_f_table_[i] = static_cast<float>(levels_[i].height);
    }
}

Texture Texture::from_pixels(int width, int height, int channels, const float* pixels, ColorSpace color_space) {
    check_size("texture from_pixels", width, height);
    if (channels < 1) fail("texture from_pixels", "no channels (" + std::to_string(channels) + ")");
    if (pixels == nullptr) fail("texture from_pixels", "no pixel data");
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                              static_cast<std::size_t>(channels);
    std::vector<std::uint8_t> bytes(count);
    // The values are already in color_space's encoding: rounded as they are.
    for (std::size_t i = 0; i < count; ++i) bytes[i] = encode_unorm8(pixels[i]);
    return from_pixels(width, height, channels, bytes.data(), color_space);
}

namespace {

// `count` texels of `channels` bytes each → RGBA8 words: grey → (g, g, g, 1),
// grey + alpha → (g, g, g, a), RGB → (r, g, b, 1), RGBA and more: the first four.
void expand_to_rgba8(const std::uint8_t* in, int channels, std::size_t count, std::uint32_t* out) {
    const auto word = [](std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a) {
        return r | g << 8 | b << 16 | a << 24;
    };
    const std::size_t stride = static_cast<std::size_t>(channels);
    for (std::size_t t = 0; t < count; ++t, in += stride) {
        switch (channels) {
            case 1: out[t] = word(in[0], in[0], in[0], 255); break;
            case 2: out[t] = word(in[0], in[0], in[0], in[1]); break;
            case 3: out[t] = word(in[0], in[1], in[2], 255); break;
            default: out[t] = word(in[0], in[1], in[2], in[3]); break;
        }
    }
}

std::int64_t nanoseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Texture Texture::from_pixels(int width, int height, int channels, const std::uint8_t* pixels,
                             ColorSpace color_space) {
    check_size("texture from_pixels", width, height);
    if (channels < 1) fail("texture from_pixels", "no channels (" + std::to_string(channels) + ")");
    if (pixels == nullptr) fail("texture from_pixels", "no pixel data");
    Texture texture;
    texture.allocate(width, height, color_space);
    expand_to_rgba8(pixels, channels, static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                    texture.texels_.get());
    texture.build_mip_chain();
    return texture;
}

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

// Level n+1 from level n: decode the parent's texels to linear light, box
// filter (separable taps), round to 8 bits in the texture's colour space.
void Texture::build_mip_chain() {
    const auto start = std::chrono::steady_clock::now();
    const float* const rgb_decode = (color_space_ == ColorSpace::srgb ? srgb_decode_table() : unorm8_table()).data();
    const float* const alpha_decode = unorm8_table().data();
    // One copy of the filter per colour space, so that the encoder is inlined
    // (it was an indirect call per channel and texel).
    const SrgbEncoder& srgb = srgb_encoder();
    const auto build_levels = [&](auto rgb_encode) {
    for (std::size_t l = 1; l < levels_.size(); ++l) {
        const MipLevel parent = levels_[l - 1];
        const MipLevel child = levels_[l];
        const auto x_taps = box_filter_taps(parent.width, child.width);
        const auto y_taps = box_filter_taps(parent.height, child.height);
        const std::uint32_t* const parent_texels = texels_.get() + parent.offset;
        std::uint32_t* const child_texels = texels_.get() + child.offset;
        const auto encode = [&](float r, float g, float b, float a) {
            return std::uint32_t(rgb_encode(r)) | std::uint32_t(rgb_encode(g)) << 8 |
                   std::uint32_t(rgb_encode(b)) << 16 | std::uint32_t(unorm8_from_linear(a)) << 24;
        };
        // Both sides even: every texel is the plain 2×2 average. The same floats
        // as the general taps give (weights ¼ = ½·½, summed in the same order;
        // scaling by ¼ is exact), without their bookkeeping.
        const bool halves = parent.width == 2 * child.width && parent.height == 2 * child.height;
        const auto build_half_rows = [&](int row_begin, int row_end) {
            for (int y = row_begin; y < row_end; ++y) {
                const std::uint32_t* row0 = parent_texels + static_cast<std::size_t>(2 * y) * parent.width;
                const std::uint32_t* row1 = row0 + parent.width;
                std::uint32_t* out = child_texels + static_cast<std::size_t>(y) * child.width;
                for (int x = 0; x < child.width; ++x) {
                    const std::uint32_t t[4] = {row0[2 * x], row0[2 * x + 1], row1[2 * x], row1[2 * x + 1]};
                    float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
                    for (const std::uint32_t texel : t) {
                        sum[0] += rgb_decode[texel & 0xFF];
                        sum[1] += rgb_decode[(texel >> 8) & 0xFF];
                        sum[2] += rgb_decode[(texel >> 16) & 0xFF];
                        sum[3] += alpha_decode[texel >> 24];
                    }
                    out[x] = encode(0.25f * sum[0], 0.25f * sum[1], 0.25f * sum[2], 0.25f * sum[3]);
                }
            }
        };
        const auto build_rows = [&](int row_begin, int row_end) {
            if (halves) return build_half_rows(row_begin, row_end);
            std::vector<float> sum(static_cast<std::size_t>(child.width) * 4);
            for (int y = row_begin; y < row_end; ++y) {
                std::fill(sum.begin(), sum.end(), 0.0f);
                for (const FilterTap& y_tap : y_taps[static_cast<std::size_t>(y)]) {
                    const std::uint32_t* row = parent_texels + static_cast<std::size_t>(y_tap.source) * parent.width;
                    for (int x = 0; x < child.width; ++x) {
                        float* out = sum.data() + static_cast<std::size_t>(x) * 4;
                        for (const FilterTap& x_tap : x_taps[static_cast<std::size_t>(x)]) {
                            const std::uint32_t t = row[x_tap.source];
                            const float w = y_tap.weight * x_tap.weight;
                            out[0] += w * rgb_decode[t & 0xFF];
                            out[1] += w * rgb_decode[(t >> 8) & 0xFF];
                            out[2] += w * rgb_decode[(t >> 16) & 0xFF];
                            out[3] += w * alpha_decode[t >> 24];
                        }
                    }
                }
                std::uint32_t* out = child_texels + static_cast<std::size_t>(y) * child.width;
                for (int x = 0; x < child.width; ++x) {
                    const float* s = sum.data() + static_cast<std::size_t>(x) * 4;
                    out[x] = encode(s[0], s[1], s[2], s[3]);
                }
            }
        };
        // Bands of rows in parallel, for the large levels only (the small ones cost less than a task).
        const std::size_t child_texels_count = static_cast<std::size_t>(child.width) * child.height;
        if (child_texels_count >= 16384) {
            const int grain = std::max(1, 8192 / child.width);
            tbb::parallel_for(tbb::blocked_range<int>(0, child.height, grain),
                              [&](const tbb::blocked_range<int>& rows) { build_rows(rows.begin(), rows.end()); });
        } else {
            build_rows(0, child.height);
        }
    }
    };
    if (color_space_ == ColorSpace::srgb) build_levels([&srgb](float x) { return srgb.encode(x); });
    else build_levels([](float x) { return unorm8_from_linear(x); });
    build_times().mips_ns += nanoseconds_since(start);
    build_times().textures += 1;
    build_times().bytes += static_cast<std::int64_t>(memory_bytes());
}

glm::vec4 Texture::texel(int level_index, int x, int y) const {
    const MipLevel& l = level(level_index);
    const std::uint32_t t = texels_[l.offset + static_cast<std::size_t>(y) * l.width + static_cast<std::size_t>(x)];
    const float* rgb = (color_space_ == ColorSpace::srgb ? srgb_decode_table() : unorm8_table()).data();
    const float* alpha = unorm8_table().data();
    return {rgb[t & 0xFF], rgb[(t >> 8) & 0xFF], rgb[(t >> 16) & 0xFF], alpha[t >> 24]};
}

std::array<std::uint8_t, 4> Texture::texel_bytes(int level_index, int x, int y) const {
    const MipLevel& l = level(level_index);
    const std::uint32_t t = texels_[l.offset + static_cast<std::size_t>(y) * l.width + static_cast<std::size_t>(x)];
    return {std::uint8_t(t), std::uint8_t(t >> 8), std::uint8_t(t >> 16), std::uint8_t(t >> 24)};
}

glm::vec4 Texture::sample_bilinear(int level_index, float u, float v, Wrap wrap) const {
    return sample_bilinear(level_index, u, v, wrap, wrap);
}

glm::vec4 Texture::sample_nearest(int level_index, float u, float v, Wrap wrap_s, Wrap wrap_t) const {
    const MipLevel& l = level(level_index);
    return texel(level_index, nearest_tap(u, l.width, static_cast<float>(l.width), wrap_s),
                 nearest_tap(v, l.height, static_cast<float>(l.height), wrap_t));
}

glm::vec4 Texture::sample_bilinear(int level_index, float u, float v, Wrap wrap_s, Wrap wrap_t) const {
    const MipLevel& l = level(level_index);
    const AxisTaps x = axis_taps(u, l.width, static_cast<float>(l.width), wrap_s);
    const AxisTaps y = axis_taps(v, l.height, static_cast<float>(l.height), wrap_t);
    // (1−α)(1−β)·τ00 + α(1−β)·τ10 + (1−α)β·τ01 + αβ·τ11, as two lerps along x then one along y.
    const glm::vec4 top = (1.0f - x.alpha) * texel(level_index, x.i0, y.i0) + x.alpha * texel(level_index, x.i1, y.i0);
    const glm::vec4 bottom =
        (1.0f - x.alpha) * texel(level_index, x.i0, y.i1) + x.alpha * texel(level_index, x.i1, y.i1);
    return (1.0f - y.alpha) * top + y.alpha * bottom;
}

glm::vec4 Texture::sample_trilinear(glm::vec2 uv, float lod, Wrap wrap) const {
    const float max_level = static_cast<float>(level_count() - 1);
    const float clamped = clamp_nan_low(lod, 0.0f, max_level);
    const float level_floor = std::floor(clamped);
    const float blend = clamped - level_floor;  // 0 when magnifying: level 0 alone
    const int level0 = static_cast<int>(level_floor);
    const int level1 = std::min(level0 + 1, level_count() - 1);
    const glm::vec4 s0 = sample_bilinear(level0, uv.x, uv.y, wrap);
    if (blend == 0.0f) return s0;
    const glm::vec4 s1 = sample_bilinear(level1, uv.x, uv.y, wrap);
    return (1.0f - blend) * s0 + blend * s1;
}

glm::vec4 Texture::sample(glm::vec2 uv, float lod, const Sampler& sampler) const {
    const auto on_level = [&](int level_index, bool linear) {
        return linear ? sample_bilinear(level_index, uv.x, uv.y, sampler.wrap_s, sampler.wrap_t)
                      : sample_nearest(level_index, uv.x, uv.y, sampler.wrap_s, sampler.wrap_t);
    };
    const Filter min = sampler.min;
    const bool nearest_mips = min == Filter::nearest_mipmap_nearest || min == Filter::nearest_mipmap_linear;
    const float c = sampler.mag == Filter::linear && nearest_mips ? 0.5f : 0.0f;
    if (!(lod > c)) return on_level(0, sampler.mag == Filter::linear);  // magnification (NaN too)
    const bool linear = min == Filter::linear || min == Filter::linear_mipmap_nearest ||
                        min == Filter::linear_mipmap_linear;
    if (min == Filter::nearest || min == Filter::linear) return on_level(0, linear);
    const float max_level = static_cast<float>(level_count() - 1);
    if (min == Filter::nearest_mipmap_nearest || min == Filter::linear_mipmap_nearest) {
        const float d = lod <= 0.5f ? 0.0f : std::min(std::ceil(lod + 0.5f) - 1.0f, max_level);
        return on_level(static_cast<int>(d), linear);
    }
    // *_MIPMAP_LINEAR, as sample_trilinear (lod > 0 here).
    const float clamped = std::min(lod, max_level);
    const float level_floor = std::floor(clamped);
    const float blend = clamped - level_floor;
    const int level0 = static_cast<int>(level_floor);
    const int level1 = std::min(level0 + 1, level_count() - 1);
    const glm::vec4 s0 = on_level(level0, linear);
    if (blend == 0.0f) return s0;
    const glm::vec4 s1 = on_level(level1, linear);
    return (1.0f - blend) * s0 + blend * s1;
}

TextureView Texture::view() const {
    return {texels_.get(),        color_space_ == ColorSpace::srgb, srgb_decode_table().data(),
            level_count(),         width_table_.data(),              height_table_.data(),
            offset_table_.data(),  width_f_table_.data(),            height_f_table_.data()};
}

float lod_from_derivatives(float dudx, float dvdx, float dudy, float dvdy, int width, int height) {
    const float w = static_cast<float>(width);
    const float h = static_cast<float>(height);
    const float rho_x = std::hypot(dudx * w, dvdx * h);
    const float rho_y = std::hypot(dudy * w, dvdy * h);
    return std::log2(std::max(rho_x, rho_y));
}

// Defined in texture_sampling_simd.cpp, once per ISA.
#define TESSERA_DECLARE_TEXTURE_ENTRIES(suffix)                                                        \
    void sample_trilinear_##suffix(const TextureView& texture, Wrap wrap, const TexCoordInputs& in, \
                                   const TexelOutputs& out);                                       \
    void lod_from_derivatives_##suffix(const DerivativeInputs& in, int width, int height, float* lod);        \
    void sample_general_##suffix(const TextureView& texture, const Sampler& sampler, const TexCoordInputs& in, \
                                 const TexelOutputs& out);
TESSERA_DECLARE_TEXTURE_ENTRIES(sse4)
TESSERA_DECLARE_TEXTURE_ENTRIES(avx2)
TESSERA_DECLARE_TEXTURE_ENTRIES(avx512)
#undef TESSERA_DECLARE_TEXTURE_ENTRIES

void sample_trilinear(simd::Isa isa, const Texture& texture, Wrap wrap, const TexCoordInputs& in,
                      const TexelOutputs& out) {
    simd::require_supported(isa);
    switch (isa) {
        case Isa::scalar:
            for (std::size_t i = 0; i < in.count; ++i) {
                const glm::vec4 s = texture.sample_trilinear({in.u[i], in.v[i]}, in.lod[i], wrap);
                out.r[i] = s.r;
                if (out.g) out.g[i] = s.g, out.b[i] = s.b;
                if (out.a) out.a[i] = s.a;
            }
            return;
        case Isa::sse4: return sample_trilinear_sse4(texture.view(), wrap, in, out);
        case Isa::avx2: return sample_trilinear_avx2(texture.view(), wrap, in, out);
        case Isa::avx512: return sample_trilinear_avx512(texture.view(), wrap, in, out);
    }
}

void sample(simd::Isa isa, const Texture& texture, const Sampler& sampler, const TexCoordInputs& in,
            const TexelOutputs& out) {
    simd::require_supported(isa);
    if (sampler.trilinear()) return sample_trilinear(isa, texture, sampler.wrap_s, in, out);
    switch (isa) {
        case Isa::scalar:
            for (std::size_t i = 0; i < in.count; ++i) {
                const glm::vec4 s = texture.sample({in.u[i], in.v[i]}, in.lod[i], sampler);
                out.r[i] = s.r;
                if (out.g) out.g[i] = s.g, out.b[i] = s.b;
                if (out.a) out.a[i] = s.a;
            }
            return;
        case Isa::sse4: return sample_general_sse4(texture.view(), sampler, in, out);
        case Isa::avx2: return sample_general_avx2(texture.view(), sampler, in, out);
        case Isa::avx512: return sample_general_avx512(texture.view(), sampler, in, out);
    }
}

void lod_from_derivatives(Isa isa, const DerivativeInputs& in, int width, int height, float* lod) {
    simd::require_supported(isa);
    switch (isa) {
        case Isa::scalar:
            for (std::size_t i = 0; i < in.count; ++i)
                lod[i] = lod_from_derivatives(in.dudx[i], in.dvdx[i], in.dudy[i], in.dvdy[i], width, height);
            return;
        case Isa::sse4: return lod_from_derivatives_sse4(in, width, height, lod);
        case Isa::avx2: return lod_from_derivatives_avx2(in, width, height, lod);
        case Isa::avx512: return lod_from_derivatives_avx512(in, width, height, lod);
    }
}

}  // namespace tessera::texture
