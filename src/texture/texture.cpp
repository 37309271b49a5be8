// Texture storage (texture.hpp): texels and their colour encodings, allocation against the
// memory budget, images from pixels in memory, texel access. Decoding files is texture_load.cpp,
// the mips mip_chain.cpp, GL's sampling rules texture_sampling.cpp.
#include "texture/texture.hpp"

#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <sys/mman.h>

#include "io/memory_budget.hpp"

#include "texture/texture_internal.hpp"

namespace tessera::texture {

using namespace detail;

namespace detail {

// source: "texture 'path'", "texture from_pixels", or the caller's label for an image in memory.
void fail(const std::string& source, const std::string& what) {
    throw TextureError(source + ": " + what);
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

const SrgbEncoder& srgb_encoder() {
    static const SrgbEncoder encoder;
    return encoder;
}

}  // namespace detail

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

std::uint8_t encode_unorm8(float linear) { return unorm8_from_linear(linear); }

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

TextureView Texture::view() const {
    return {texels_.get(),        color_space_ == ColorSpace::srgb, srgb_decode_table().data(),
            level_count(),         width_table_.data(),              height_table_.data(),
            offset_table_.data(),  width_f_table_.data(),            height_f_table_.data()};
}

}  // namespace tessera::texture
