// Textures for the textured PBR variant (docs/reference/pbr_lighting.md, "Textured
// variant"): an image with its full mip chain and OpenGL's sampling rules,
// GL_LINEAR magnification and GL_LINEAR_MIPMAP_LINEAR minification, with
// GL_REPEAT or GL_CLAMP_TO_EDGE wrapping. The scalar samplers are the reference
// (texture_sampling.cpp); sample_trilinear(Isa, ...) runs the same arithmetic over
// batches of fragments (texture_sampling_simd.cpp, one copy per ISA).
//
// Storage: 8 bits per channel, RGBA interleaved in one 32-bit word per texel
// (r in the low byte), all levels in one array: GL_RGBA8, or GL_SRGB8_ALPHA8
// for sRGB maps. A 2048² map with its mips is 22 MB (it was 90 MB as float
// RGBA), and a bilinear tap is one 4-byte load for all four channels. The
// stored values are the file's: for 8-bit PNG/JPEG sources level 0 is exactly
// the image; mip levels are filtered in linear light and rounded to 8 bits.
// Sampling decodes each texel to linear light before filtering, as GL does:
// sRGB colour through a 256-entry table of the exact transfer function,
// everything else (linear colour, alpha) as byte/255.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "simd/isa.hpp"
#include "simd/lane_padding.hpp"

namespace tessera::texture {

using simd::Isa;
using simd::kLanePadding;
using simd::padded_count;

// How the stored values relate to light. sRGB data (albedo/base colour, 8-bit
// images authored for display) is decoded to linear with the exact sRGB transfer
// function, as GL does for GL_SRGB8_ALPHA8 textures: alpha stays linear. Linear
// data (metallic, roughness, ao, normal maps) is kept as read. Both are stored
// as 8-bit values in [0, 1]: float or 16-bit sources (EXR, 16-bit PNG) are
// clamped and rounded.
enum class ColorSpace { srgb, linear };

// What happens outside [0, 1]: GL_REPEAT (the pattern tiles),
// GL_CLAMP_TO_EDGE (the edge texels extend) or GL_MIRRORED_REPEAT (the
// pattern tiles, every other copy mirrored).
enum class Wrap { repeat, clamp_to_edge, mirrored_repeat };

// GL's texture filters (§8.14): NEAREST and LINEAR for magnification;
// all six for minification.
enum class Filter { nearest, linear, nearest_mipmap_nearest, linear_mipmap_nearest, nearest_mipmap_linear,
                    linear_mipmap_linear };

// A GL sampler object's state: wrap per axis (s = u, t = v) and the two
// filters. The default is what the sampler did before samplers were
// configurable, and glTF's default where a file gives none.
struct Sampler {
    Wrap wrap_s = Wrap::repeat;
    Wrap wrap_t = Wrap::repeat;
    Filter mag = Filter::linear;
    Filter min = Filter::linear_mipmap_linear;
    bool operator==(const Sampler&) const = default;
    // GL_LINEAR / GL_LINEAR_MIPMAP_LINEAR with one wrap (repeat or clamp) on both
    // axes: what sample_trilinear() does, on its fast kernels.
    bool trilinear() const {
        return mag == Filter::linear && min == Filter::linear_mipmap_linear && wrap_s == wrap_t &&
               wrap_s != Wrap::mirrored_repeat;
    }
};

// Loading or building a texture failed; the message names the file (or
// "from_pixels") and what was wrong.
class TextureError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The exact sRGB decode (IEC 61966-2-1): c/12.92 up to 0.04045, else ((c + 0.055)/1.055)^2.4.
float srgb_to_linear(float encoded);

// 8-bit value → linear light, by table (the sampler's decode, texture.hpp header):
// srgb_decode_table()[k] = srgb_to_linear(k/255), unorm8_table()[k] = k/255.
const std::array<float, 256>& srgb_decode_table();
const std::array<float, 256>& unorm8_table();
// Linear light → the nearest 8-bit value (mip levels are stored this way):
// round(255·x) for linear data, round(255·sRGB_encode(x)) for sRGB, x clamped to [0, 1].
std::uint8_t encode_unorm8(float linear);
std::uint8_t encode_srgb8(float linear);

// One mip level: its size in texels and where its first texel is in Texture::texels().
struct MipLevel {
    int width = 0;
    int height = 0;
    std::size_t offset = 0;  // in texels (one 32-bit RGBA8 word each)
};

// Up to 16384 per side: 15 levels.
inline constexpr int kMaxTextureSize = 16384;
inline constexpr int kMaxMipLevels = 15;

// What the SIMD kernels read: plain pointers and per-level tables, no std::vector
// (kernels compiled for a wider ISA must not instantiate code shared with the
// baseline). Tables hold level_count entries.
struct TextureView {
    const std::uint32_t* texels = nullptr;  // RGBA8 words (r in the low byte), all levels
    bool srgb = false;                      // colour through srgb_decode_table(), else byte/255
    const float* srgb_table = nullptr;      // srgb_decode_table().data()
    int level_count = 0;
    const std::int32_t* width = nullptr;
    const std::int32_t* height = nullptr;
    const std::int32_t* offset = nullptr;  // in texels
    const float* width_f = nullptr;
    const float* height_f = nullptr;
};

// An image with a full mip chain, RGBA8 (see the storage note above).
//
// Level 0 is the source. Level n+1 has size max(1, floor(w/2)) × max(1, floor(h/2))
// of level n (GL's rule), down to 1×1: floor(log2(max(w, h))) + 1 levels. Each
// texel of level n+1 is the area-weighted box filter of the level-n texels its
// footprint covers: with an even side that is the plain 2×2 average; with an odd
// side (w = 2k+1 → k) a texel covers w/k > 2 parent texels, the partially covered
// one weighted by its covered fraction (5 → 2: (t0 + t1 + ½·t2)/2.5). The filter
// is separable, preserves the mean exactly (up to rounding), and is one of the
// box filters glGenerateMipmap permits. Filtering happens on linear values
// (the decoded texels of level n), the result rounded to 8 bits in the
// texture's colour space. Rows of a level are built in parallel (TBB); each
// texel's arithmetic is fixed, so the chain is the same with any thread count.
//
// Channels: 1 = grey → (g, g, g, 1); 2 = grey + alpha → (g, g, g, a);
// 3 = RGB → (r, g, b, 1); 4 = RGBA; more than 4: the first 4, the rest ignored.
class Texture {
public:
    // Reads PNG, JPEG, WebP and AVIF itself (libpng, libjpeg-turbo, libwebp, libavif), any other format
    // OpenImageIO reads (TGA, TIFF, EXR, HDR, ...) through its module
    // (oiio_module_loader.hpp), the first subimage. Throws TextureError for a
    // missing or unreadable file, a truncated image, a zero size, a side above
    // kMaxTextureSize, or another format when the module is not installed.
    static Texture load(const std::filesystem::path& path, ColorSpace color_space);
    // The same from an encoded PNG, JPEG, WebP or AVIF image in memory (a glTF
    // image); messages read "<source>: what is wrong".
    static Texture decode(std::span<const std::uint8_t> encoded, const std::string& source, ColorSpace color_space);
    // Whether decode() knows the bytes' format (by its signature).
    static bool can_decode(std::span<const std::uint8_t> encoded);
    // `pixels` holds width·height·channels floats, row-major, top row first,
    // channels interleaved, in color_space's encoding (sRGB values are the
    // encoded ones), rounded to 8 bits: round(255·clamp(value, 0, 1)).
    static Texture from_pixels(int width, int height, int channels, const float* pixels, ColorSpace color_space);
    // The same from 8-bit values, stored as they are.
    static Texture from_pixels(int width, int height, int channels, const std::uint8_t* pixels,
                               ColorSpace color_space);

    int width() const { return levels_.front().width; }
    int height() const { return levels_.front().height; }
    int level_count() const { return static_cast<int>(levels_.size()); }
    const MipLevel& level(int index) const { return levels_.at(static_cast<std::size_t>(index)); }
    ColorSpace color_space() const { return color_space_; }
    std::span<const std::uint32_t> texels() const { return {texels_.get(), texel_count_}; }
    // Bytes held by the texels of every level.
    std::size_t memory_bytes() const { return texel_count_ * sizeof(std::uint32_t); }

    // Texel (x, y) of a level, no wrapping: 0 <= x < width, 0 <= y < height of
    // that level. Decoded to linear light (the values the sampler filters).
    glm::vec4 texel(int level, int x, int y) const;
    // The stored 8-bit values of that texel: r, g, b, a.
    std::array<std::uint8_t, 4> texel_bytes(int level, int x, int y) const;

    // GL_LINEAR on one level. (u, v) in texture space: (0, 0) is the top-left
    // corner of the image (its first row), (1, 1) the bottom-right; texel (i, j)
    // has its centre at ((i + 0.5)/width, (j + 0.5)/height). NaN coordinates
    // sample like -∞ (no out-of-range reads).
    glm::vec4 sample_bilinear(int level, float u, float v, Wrap wrap) const;

    // GL_LINEAR_MIPMAP_LINEAR for lod > 0, GL_LINEAR on level 0 for lod <= 0
    // (magnification). lod is clamped to [0, level_count − 1] (NaN → 0); the
    // result blends levels floor(lod) and floor(lod) + 1 by frac(lod).
    glm::vec4 sample_trilinear(glm::vec2 uv, float lod, Wrap wrap) const;

    // GL_NEAREST on one level: the texel whose square holds (u, v), wrapped per axis.
    glm::vec4 sample_nearest(int level, float u, float v, Wrap wrap_s, Wrap wrap_t) const;
    // GL_LINEAR on one level, wrapped per axis.
    glm::vec4 sample_bilinear(int level, float u, float v, Wrap wrap_s, Wrap wrap_t) const;

    // The GL sampler (§8.14, §8.14.2): magnification where lod <= c (c = 0.5
    // for mag LINEAR with min NEAREST_MIPMAP_*, else 0; NaN magnifies), with
    // sampler.mag on level 0; otherwise sampler.min: NEAREST/LINEAR on level 0;
    // *_MIPMAP_NEAREST on level ⌈lod + ½⌉ − 1 (0 up to lod ½), clamped to the
    // last; *_MIPMAP_LINEAR blends levels ⌊lod⌋ and ⌊lod⌋ + 1 (lod clamped to the
    // last level) by frac(lod). With the default sampler it equals sample_trilinear.
    glm::vec4 sample(glm::vec2 uv, float lod, const Sampler& sampler) const;

    // The kernels' view of this texture; valid while the texture lives and is not moved.
    TextureView view() const;

private:
    Texture() = default;
    friend struct ImageDecoder;  // texture_load.cpp: decodes an image file into level 0
    // Sizes every level and allocates the texels; level 0 is then filled. Throws
    // io::MemoryBudgetError when every live texture with this one would pass the budget.
    void allocate(int width, int height, ColorSpace color_space);
    void build_mip_chain();  // from level 0 in texels_

    std::vector<MipLevel> levels_;
    ColorSpace color_space_ = ColorSpace::linear;
    // All levels, RGBA8. Not a std::vector: its zero fill cost a memset of
    // 22 MB per 2048² map before the decoder and the mip filter wrote every
    // texel. Maps of 2 MiB and more are in transparent huge pages (texture.cpp: allocate).
    // It gives the bytes back to the process's count of live texels, which
    // allocate checks against the memory budget (io/memory_budget.hpp).
    struct FreeTexels {
        std::size_t bytes;  // no initializer: a nested class's one would make it not default-constructible here
        void operator()(std::uint32_t* texels) const;
    };
    std::unique_ptr<std::uint32_t[], FreeTexels> texels_;
    std::size_t texel_count_ = 0;
    // The per-level tables of TextureView.
    std::array<std::int32_t, kMaxMipLevels> width_table_{};
    std::array<std::int32_t, kMaxMipLevels> height_table_{};
    std::array<std::int32_t, kMaxMipLevels> offset_table_{};
    std::array<float, kMaxMipLevels> width_f_table_{};
    std::array<float, kMaxMipLevels> height_f_table_{};
};

// Time spent making textures in this process, summed over the threads that
// did it (so it can exceed wall time), for `tessera render --stats`:
// decoding PNG/JPEG to 8-bit rows, expanding them into RGBA8 level 0 (the
// sampler's layout), and filtering the mip levels. Never reset by the library.
struct TextureBuildTimes {
    std::atomic<std::int64_t> decode_ns{0};
    std::atomic<std::int64_t> upload_ns{0};
    std::atomic<std::int64_t> mips_ns{0};
    std::atomic<std::int64_t> textures{0};  // textures built
    std::atomic<std::int64_t> bytes{0};     // their memory_bytes()
};
TextureBuildTimes& build_times();

// The level of detail λ = log2(ρ) of the GL spec (§8.14.1, the non-approximated
// scale factor): ρ = max(|∂(uv·size)/∂x|, |∂(uv·size)/∂y|), the longer of the
// two screen-space steps measured in level-0 texels. Derivatives are of (u, v)
// per pixel; width, height of level 0. ρ = 0 gives -∞ (magnification).
float lod_from_derivatives(float dudx, float dvdx, float dudy, float dvdy, int width, int height);

// Screen-space derivatives of (u, v) for a batch of fragments, SoA, each array
// padded as TexCoordInputs' are.
struct DerivativeInputs {
    std::size_t count = 0;
    const float* dudx = nullptr;
    const float* dvdx = nullptr;
    const float* dudy = nullptr;
    const float* dvdy = nullptr;
};

// lod[i] = lod_from_derivatives(...[i], width, height) for i < in.count; `lod`
// holds padded_count(in.count) floats. The SIMD ISAs compute ½·log2(max(ρx², ρy²)),
// within a few ulps of the scalar hypot and log2.
void lod_from_derivatives(Isa isa, const DerivativeInputs& in, int width, int height, float* lod);

// Fragments to sample in SoA form. All pointers address at least
// padded_count(count) floats (simd/lane_padding.hpp: kernels run whole vectors past
// count). Any values in those extra lanes are safe: indices are clamped.
struct TexCoordInputs {
    std::size_t count = 0;
    const float* u = nullptr;
    const float* v = nullptr;
    const float* lod = nullptr;  // as for Texture::sample_trilinear
};

// Sampled linear RGBA, one array per channel, padded like the inputs. Only
// the channels asked for are sampled: r alone (g, b, a null), r, g, b (a
// null), or all four.
struct TexelOutputs {
    float* r = nullptr;
    float* g = nullptr;
    float* b = nullptr;
    float* a = nullptr;
};

// out[i] = texture.sample_trilinear({u[i], v[i]}, lod[i], wrap) for i < in.count.
// The SIMD ISAs decode texels as the scalar sampler does (the same table, or
// the same division by 255) and run its operations in the same order, without
// FMA contraction, so they return the same floats (tests/texture/test_texture.cpp
// checks |simd − scalar| <= 1e-5; it measures 0).
void sample_trilinear(simd::Isa isa, const Texture& texture, Wrap wrap, const TexCoordInputs& in,
                      const TexelOutputs& out);

// out[i] = texture.sample({u[i], v[i]}, lod[i], sampler) for i < in.count, the
// same floats from every ISA (the same arithmetic in the same order). A
// trilinear() sampler runs sample_trilinear's kernels; any other the general
// kernel, whose filter and wrap choices are made once per call.
void sample(simd::Isa isa, const Texture& texture, const Sampler& sampler, const TexCoordInputs& in,
            const TexelOutputs& out);

}  // namespace tessera::texture
