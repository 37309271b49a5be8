// The scalar reference samplers and the SIMD kernels' dispatch (texture.hpp). The sampling
// follows the GL 4.6 spec, §8.14 "Texture Minification" and §8.14.2 "Coordinate Wrapping and
// Texel Selection", term for term.
#include "texture/texture.hpp"

#include <cmath>

#include "texture/texture_internal.hpp"

namespace tessera::texture {

using namespace detail;

namespace {

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

}  // namespace

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
