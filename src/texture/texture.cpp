// Texture loading, mip chain and the scalar reference samplers (texture.hpp).
// The sampling follows the GL 4.6 spec, §8.14 "Texture Minification" and
// §8.14.2 "Coordinate Wrapping and Texel Selection", term for term.
#include "texture/texture.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>
#include <utility>

#include <OpenImageIO/imageio.h>

#include "simd/lane_padding.hpp"

namespace tessera::texture {

namespace {

// Built by appending: g++ 12 warns falsely (-Wrestrict) about "'" + std::string.
std::string quoted(const std::filesystem::path& path) {
    std::string text(1, '\'');
    text += path.string();
    text += '\'';
    return text;
}

[[noreturn]] void fail(const std::string& source, const std::string& what) {
    throw TextureError("texture " + source + ": " + what);
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

AxisTaps axis_taps(float coord, int size, float size_f, Wrap wrap) {
    if (wrap == Wrap::repeat) coord -= std::floor(coord);
    const float x = clamp_nan_low(coord * size_f - 0.5f, -1.0f, size_f);
    const float x_floor = std::floor(x);
    AxisTaps taps{static_cast<int>(x_floor), static_cast<int>(x_floor) + 1, x - x_floor};
    if (wrap == Wrap::repeat) {
        // With coord in [0, 1], x is in [−1, size − ½]: one step of wrapping suffices.
        if (taps.i0 < 0) taps.i0 += size;
        if (taps.i1 >= size) taps.i1 -= size;
    } else {
        taps.i0 = std::clamp(taps.i0, 0, size - 1);
        taps.i1 = std::clamp(taps.i1, 0, size - 1);
    }
    return taps;
}

// Weights of the area-weighted box filter from `from` texels down to `to`
// along one axis: output texel i covers [i·r, (i+1)·r) of the input, r = from/to.
struct FilterTap {
    int source;
    double weight;
};

std::vector<std::vector<FilterTap>> box_filter_taps(int from, int to) {
    const double ratio = static_cast<double>(from) / to;
    std::vector<std::vector<FilterTap>> taps(static_cast<std::size_t>(to));
    for (int i = 0; i < to; ++i) {
        const double begin = i * ratio;
        const double end = (i + 1) * ratio;
        for (int j = static_cast<int>(std::floor(begin)); j < from && j < end; ++j) {
            const double covered = std::min(end, j + 1.0) - std::max(begin, static_cast<double>(j));
            if (covered > 0.0) taps[static_cast<std::size_t>(i)].push_back({j, covered / ratio});
        }
    }
    return taps;
}

}  // namespace

float srgb_to_linear(float encoded) {
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return static_cast<float>(std::pow((static_cast<double>(encoded) + 0.055) / 1.055, 2.4));
}

Texture Texture::from_pixels(int width, int height, int channels, const float* pixels, ColorSpace color_space) {
    check_size("from_pixels", width, height);
    if (channels < 1) fail("from_pixels", "no channels (" + std::to_string(channels) + ")");
    if (pixels == nullptr) fail("from_pixels", "no pixel data");

    Texture texture;
    const std::size_t texel_count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    texture.levels_.push_back({width, height, 0});
    texture.texels_.resize(texel_count * 4);
    const auto decode = [color_space](float value) {
        return color_space == ColorSpace::srgb ? srgb_to_linear(value) : value;
    };
    const std::size_t stride = static_cast<std::size_t>(channels);
    for (std::size_t t = 0; t < texel_count; ++t) {
        const float* in = pixels + t * stride;
        float* out = texture.texels_.data() + t * 4;
        if (channels <= 2) {
            out[0] = out[1] = out[2] = decode(in[0]);
        } else {
            out[0] = decode(in[0]);
            out[1] = decode(in[1]);
            out[2] = decode(in[2]);
        }
        // Alpha is coverage, linear in every colour space.
        out[3] = channels == 2 ? in[1] : channels >= 4 ? in[3] : 1.0f;
    }
    texture.build_mip_chain();
    return texture;
}

Texture Texture::load(const std::filesystem::path& path, ColorSpace color_space) {
    const std::string source = quoted(path);
    std::error_code error;
    if (!std::filesystem::exists(path, error)) fail(source, "file not found");
    if (!std::filesystem::is_regular_file(path, error)) fail(source, "not a regular file");
    if (std::filesystem::file_size(path, error) == 0 && !error) fail(source, "empty file (0 bytes)");

    // Straight (unassociated) alpha as stored: OpenImageIO would otherwise
    // premultiply PNG colour by alpha, in the encoded (sRGB) values.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path.string(), &config);
    if (!input) fail(source, "cannot read image: " + one_line(OIIO::geterror()));

    const OIIO::ImageSpec& spec = input->spec();
    check_size(source, spec.width, spec.height);
    if (spec.depth > 1) fail(source, "volume images are not supported (depth " + std::to_string(spec.depth) + ")");
    if (spec.nchannels < 1) fail(source, "no channels");

    const int channels = std::min(spec.nchannels, 4);
    std::vector<float> pixels(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                              static_cast<std::size_t>(channels));
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
        fail(source, "truncated or corrupt image data: " + one_line(input->geterror()));
    input->close();

    try {
        return from_pixels(spec.width, spec.height, channels, pixels.data(), color_space);
    } catch (const TextureError& e) {
        fail(source, e.what());
    }
}

void Texture::build_mip_chain() {
    MipLevel parent = levels_.front();
    // Every level's room at once: growing the array level by level moved it
    // and faulted in fresh pages each time (2 s for a 2048² texture, half of it that).
    std::size_t total = 0;
    for (int w = parent.width, h = parent.height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        total += static_cast<std::size_t>(w) * h;
        if (w == 1 && h == 1) break;
    }
    texels_.reserve(total * 4);
    while (parent.width > 1 || parent.height > 1) {
        const MipLevel child{std::max(1, parent.width / 2), std::max(1, parent.height / 2),
                             parent.offset + static_cast<std::size_t>(parent.width) * parent.height};
        const auto x_taps = box_filter_taps(parent.width, child.width);
        const auto y_taps = box_filter_taps(parent.height, child.height);

        // Rows first (parent.height rows of child.width texels), in double, then columns.
        std::vector<double> rows(static_cast<std::size_t>(child.width) * parent.height * 4, 0.0);
        for (int y = 0; y < parent.height; ++y) {
            const float* parent_row = texels_.data() + (parent.offset + static_cast<std::size_t>(y) * parent.width) * 4;
            for (int x = 0; x < child.width; ++x) {
                double* out = rows.data() + (static_cast<std::size_t>(y) * child.width + x) * 4;
                for (const FilterTap& tap : x_taps[static_cast<std::size_t>(x)])
                    for (int c = 0; c < 4; ++c) out[c] += tap.weight * parent_row[tap.source * 4 + c];
            }
        }
        texels_.resize((child.offset + static_cast<std::size_t>(child.width) * child.height) * 4);
        for (int y = 0; y < child.height; ++y) {
            for (int x = 0; x < child.width; ++x) {
                double sum[4] = {0.0, 0.0, 0.0, 0.0};
                for (const FilterTap& tap : y_taps[static_cast<std::size_t>(y)]) {
                    const double* in = rows.data() + (static_cast<std::size_t>(tap.source) * child.width + x) * 4;
                    for (int c = 0; c < 4; ++c) sum[c] += tap.weight * in[c];
                }
                float* out = texels_.data() + (child.offset + static_cast<std::size_t>(y) * child.width + x) * 4;
                for (int c = 0; c < 4; ++c) out[c] = static_cast<float>(sum[c]);
            }
        }
        levels_.push_back(child);
        parent = child;
    }

    for (std::size_t i = 0; i < levels_.size(); ++i) {
        width_table_[i] = levels_[i].width;
        height_table_[i] = levels_[i].height;
        offset_table_[i] = static_cast<std::int32_t>(levels_[i].offset);
        width_f_table_[i] = static_cast<float>(levels_[i].width);
        height_f_table_[i] = static_cast<float>(levels_[i].height);
    }
}

glm::vec4 Texture::texel(int level_index, int x, int y) const {
    const MipLevel& l = level(level_index);
    const float* t = texels_.data() + (l.offset + static_cast<std::size_t>(y) * l.width + x) * 4;
    return {t[0], t[1], t[2], t[3]};
}

glm::vec4 Texture::sample_bilinear(int level_index, float u, float v, Wrap wrap) const {
    const MipLevel& l = level(level_index);
    const AxisTaps x = axis_taps(u, l.width, static_cast<float>(l.width), wrap);
    const AxisTaps y = axis_taps(v, l.height, static_cast<float>(l.height), wrap);
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

TextureView Texture::view() const {
    return {texels_.data(),        level_count(),         width_table_.data(), height_table_.data(),
            offset_table_.data(),  width_f_table_.data(), height_f_table_.data()};
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
    void lod_from_derivatives_##suffix(const DerivativeInputs& in, int width, int height, float* lod);
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
