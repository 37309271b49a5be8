// Texture::sample_trilinear (texture_sampling.cpp) over xsimd batches: one fragment per
// lane, each lane with its own level pair, so the per-level sizes and offsets
// are gathered from the TextureView tables, and the RGBA8 texel words by
// simd::hardware_gather (vpgatherdd on AVX2/AVX-512, lane by lane on SSE4.2).
// Each channel byte is decoded before filtering as the scalar texel() does:
// sRGB colour by gathering from the same 256-entry table, the rest as
// float(byte) / 255, the division that built unorm8_table().
// Compiled once per ISA like shade_kernels_simd.cpp; entry points carry
// TESSERA_SIMD_SUFFIX, everything else is in an anonymous namespace.
//
// Same steps, same order and same names as the scalar reference, and built with
// -ffp-contract=off (src/texture/CMakeLists.txt): an FMA in x = u·size − ½ would
// move the bilinear weight by up to half an ulp of u·size (3e-5 on a 512-texel
// side). So the results equal the scalar sampler's; the test allows 1e-5.
#include <array>
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"
#include "simd/hardware_gather.hpp"

#include "simd/lane_padding.hpp"
#include "texture/texture.hpp"

namespace tessera::texture {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Batch = xsimd::batch<float, Arch>;
using IntBatch = xsimd::batch<std::int32_t, Arch>;
static_assert(kLanePadding % Batch::size == 0, "padding must hold whole vectors");
static_assert(IntBatch::size == Batch::size, "one int32 index per float lane");

// The first N channels of a texel per lane: N = 1 (grey data), 3 (RGB) or 4.
template <int N>
struct Texels {
    std::array<Batch, N> c;
};

template <int N>
Texels<N> lerp(const Texels<N>& t0, const Texels<N>& t1, const Batch& weight) {
    const Batch keep = Batch(1.0f) - weight;
    Texels<N> result;
    for (int k = 0; k < N; ++k) result.c[k] = keep * t0.c[k] + weight * t1.c[k];
    return result;
}

// min(max(x, lo), hi): the hardware max returns its second operand for NaN, so NaN → lo.
Batch clamp_nan_low(const Batch& x, const Batch& lo, const Batch& hi) { return xsimd::min(xsimd::max(x, lo), hi); }

// Per-lane level parameters, gathered from the TextureView tables.
struct LevelLanes {
    IntBatch width, height, offset;
    Batch width_f, height_f;
};

// Usually every lane of a batch is on the same level (lod varies slowly over a
// tile): then the parameters are broadcast, saving five gathers.
LevelLanes level_lanes(const TextureView& texture, const IntBatch& level) {
    const std::int32_t first = level.get(0);
    if (xsimd::all(level == IntBatch(first)))
        return {IntBatch(texture.width[first]), IntBatch(texture.height[first]), IntBatch(texture.offset[first]),
                Batch(texture.width_f[first]), Batch(texture.height_f[first])};
    return {IntBatch::gather(texture.width, level), IntBatch::gather(texture.height, level),
            IntBatch::gather(texture.offset, level), Batch::gather(texture.width_f, level),
            Batch::gather(texture.height_f, level)};
}

struct AxisTaps {
    IntBatch i0, i1;
    Batch alpha;
};

// axis_taps of texture_sampling.cpp: x = coord·size − ½, i0 = wrap(⌊x⌋), i1 = wrap(⌊x⌋ + 1), α = frac(x).
AxisTaps axis_taps(Batch coord, const IntBatch& size, const Batch& size_f, Wrap wrap) {
    if (wrap == Wrap::repeat) coord -= xsimd::floor(coord);
    const Batch x = clamp_nan_low(coord * size_f - Batch(0.5f), Batch(-1.0f), size_f);
    const Batch x_floor = xsimd::floor(x);
    const IntBatch i0 = xsimd::to_int(x_floor);  // exact: x_floor is a small integer
    const IntBatch i1 = i0 + IntBatch(1);
    const IntBatch zero(0);
    const IntBatch last = size - IntBatch(1);
    if (wrap == Wrap::repeat)
        return {xsimd::select(i0 < zero, i0 + size, i0), xsimd::select(i1 > last, i1 - size, i1), x - x_floor};
    return {xsimd::select(i0 < zero, zero, xsimd::select(i0 > last, last, i0)),
            xsimd::select(i1 < zero, zero, xsimd::select(i1 > last, last, i1)), x - x_floor};
}

// The texel at texel index `index`, its first N channels decoded to linear light.
template <int N>
Texels<N> fetch(const TextureView& texture, const IntBatch& index) {
    const IntBatch word = simd::hardware_gather(reinterpret_cast<const std::int32_t*>(texture.texels), index);
    Texels<N> result;
    for (int k = 0; k < N; ++k) {
        const IntBatch byte = (word >> (8 * k)) & IntBatch(0xFF);
        if (k < 3 && texture.srgb) result.c[k] = simd::hardware_gather(texture.srgb_table, byte);
        else result.c[k] = xsimd::to_float(byte) / Batch(255.0f);
    }
    return result;
}

// The four taps' texels of one level, weighted as GL_LINEAR weights them (x first, then y).
template <int N>
Texels<N> bilinear_from_taps(const TextureView& texture, const LevelLanes& l, const AxisTaps& x, const AxisTaps& y) {
    const IntBatch row0 = l.offset + y.i0 * l.width;
    const IntBatch row1 = l.offset + y.i1 * l.width;
    const Texels<N> top = lerp(fetch<N>(texture, row0 + x.i0), fetch<N>(texture, row0 + x.i1), x.alpha);
    const Texels<N> bottom = lerp(fetch<N>(texture, row1 + x.i0), fetch<N>(texture, row1 + x.i1), x.alpha);
    return lerp(top, bottom, y.alpha);
}

template <int N>
Texels<N> sample_bilinear(const TextureView& texture, const IntBatch& level, const Batch& u, const Batch& v, Wrap wrap) {
    const LevelLanes l = level_lanes(texture, level);
    return bilinear_from_taps<N>(texture, l, axis_taps(u, l.width, l.width_f, wrap), axis_taps(v, l.height, l.height_f, wrap));
}

template <int N>
void sample_trilinear_batch(const TextureView& texture, Wrap wrap, const TexCoordInputs& in, std::size_t i,
                            const TexelOutputs& out) {
    const Batch u = xsimd::load_unaligned(in.u + i);
    const Batch v = xsimd::load_unaligned(in.v + i);
    const Batch max_level(static_cast<float>(texture.level_count - 1));
    const Batch clamped = clamp_nan_low(xsimd::load_unaligned(in.lod + i), Batch(0.0f), max_level);
    const Batch level_floor = xsimd::floor(clamped);
    const Batch blend = clamped - level_floor;  // 0 when magnifying: level 0 alone
    const IntBatch level0 = xsimd::to_int(level_floor);
    const IntBatch level1 = xsimd::min(level0 + IntBatch(1), IntBatch(texture.level_count - 1));

    const Texels<N> s0 = sample_bilinear<N>(texture, level0, u, v, wrap);
    Texels<N> result = s0;
    // The scalar sampler skips level1 when blend is 0 for a lane; skip it here only when it is 0 for all.
    if (xsimd::any(blend != Batch(0.0f))) result = lerp(s0, sample_bilinear<N>(texture, level1, u, v, wrap), blend);
    float* const channels[] = {out.r, out.g, out.b, out.a};
    for (int k = 0; k < N; ++k) result.c[k].store_unaligned(channels[k] + i);
}

// ---- The general sampler (Texture::sample): wrap per axis, GL_MIRRORED_REPEAT,
// every filter. The same steps as texture_sampling.cpp's axis_taps, nearest_tap and
// Texture::sample; the choices are uniform over a call, so they branch once
// per vector, not per lane.

// mirror_fold of texture_sampling.cpp: i in [−1, 2·size] onto the mirrored pattern's texel.
IntBatch mirror_fold(IntBatch i, const IntBatch& size) {
    const IntBatch period = size + size;
    i = xsimd::select(i < IntBatch(0), i + period, i);
    i = xsimd::select(i >= period, i - period, i);
    return xsimd::select(i < size, i, period - IntBatch(1) - i);
}

Batch reduce_coord(Batch coord, Wrap wrap) {
    if (wrap == Wrap::repeat) return coord - xsimd::floor(coord);
    if (wrap == Wrap::mirrored_repeat) return coord - Batch(2.0f) * xsimd::floor(coord * Batch(0.5f));
    return coord;
}

AxisTaps general_axis_taps(Batch coord, const IntBatch& size, const Batch& size_f, Wrap wrap) {
    if (wrap != Wrap::mirrored_repeat) return axis_taps(coord, size, size_f, wrap);
    coord = reduce_coord(coord, wrap);
    const Batch x = clamp_nan_low(coord * size_f - Batch(0.5f), Batch(-1.0f), Batch(2.0f) * size_f);
    const Batch x_floor = xsimd::floor(x);
    const IntBatch i0 = xsimd::to_int(x_floor);
    return {mirror_fold(i0, size), mirror_fold(i0 + IntBatch(1), size), x - x_floor};
}

IntBatch nearest_tap(Batch coord, const IntBatch& size, const Batch& size_f, Wrap wrap) {
    coord = reduce_coord(coord, wrap);
    const Batch period_f = wrap == Wrap::mirrored_repeat ? Batch(2.0f) * size_f : size_f;
    const IntBatch i = xsimd::to_int(xsimd::floor(clamp_nan_low(coord * size_f, Batch(-1.0f), period_f)));
    if (wrap == Wrap::repeat)
        return xsimd::select(i >= size, i - size, xsimd::select(i < IntBatch(0), i + size, i));
    if (wrap == Wrap::mirrored_repeat) return mirror_fold(i, size);
    return xsimd::select(i < IntBatch(0), IntBatch(0), xsimd::select(i > size - IntBatch(1), size - IntBatch(1), i));
}

template <int N>
Texels<N> sample_level(const TextureView& texture, const Sampler& sampler, const IntBatch& level, const Batch& u,
                       const Batch& v, bool linear) {
    const LevelLanes l = level_lanes(texture, level);
    if (!linear) {
        const IntBatch x = nearest_tap(u, l.width, l.width_f, sampler.wrap_s);
        const IntBatch y = nearest_tap(v, l.height, l.height_f, sampler.wrap_t);
        return fetch<N>(texture, l.offset + y * l.width + x);
    }
    return bilinear_from_taps<N>(texture, l, general_axis_taps(u, l.width, l.width_f, sampler.wrap_s),
                                 general_axis_taps(v, l.height, l.height_f, sampler.wrap_t));
}

// Lanes are magnified or minified each on their own (Texture::sample's
// branches as selects): both results are computed where a vector holds both.
template <int N>
void sample_general_batch(const TextureView& texture, const Sampler& sampler, const TexCoordInputs& in, std::size_t i,
                          const TexelOutputs& out) {
    const Batch u = xsimd::load_unaligned(in.u + i);
    const Batch v = xsimd::load_unaligned(in.v + i);
    const Batch lod = xsimd::load_unaligned(in.lod + i);
    const Filter min = sampler.min;
    const bool nearest_mips = min == Filter::nearest_mipmap_nearest || min == Filter::nearest_mipmap_linear;
    const float c = sampler.mag == Filter::linear && nearest_mips ? 0.5f : 0.0f;
    const auto minified = lod > Batch(c);  // false for NaN
    const IntBatch zero(0);
    Texels<N> result{};
    if (!xsimd::all(minified)) result = sample_level<N>(texture, sampler, zero, u, v, sampler.mag == Filter::linear);
    if (xsimd::any(minified)) {
        const bool linear = min == Filter::linear || min == Filter::linear_mipmap_nearest ||
                            min == Filter::linear_mipmap_linear;
        const float max_level_f = static_cast<float>(texture.level_count - 1);
        Texels<N> minified_result;
        if (min == Filter::nearest || min == Filter::linear) {
            minified_result = sample_level<N>(texture, sampler, zero, u, v, linear);
        } else if (min == Filter::nearest_mipmap_nearest || min == Filter::linear_mipmap_nearest) {
            // Lanes not minified may hold any lod: NaN and the like end on level 0 through the clamp.
            const Batch d = xsimd::select(lod <= Batch(0.5f), Batch(0.0f),
                                          xsimd::min(xsimd::ceil(lod + Batch(0.5f)) - Batch(1.0f), Batch(max_level_f)));
            const IntBatch level = xsimd::to_int(clamp_nan_low(d, Batch(0.0f), Batch(max_level_f)));
            minified_result = sample_level<N>(texture, sampler, level, u, v, linear);
        } else {
            const Batch clamped = clamp_nan_low(lod, Batch(0.0f), Batch(max_level_f));
            const Batch level_floor = xsimd::floor(clamped);
            const Batch blend = clamped - level_floor;
            const IntBatch level0 = xsimd::to_int(level_floor);
            const IntBatch level1 = xsimd::min(level0 + IntBatch(1), IntBatch(texture.level_count - 1));
            minified_result = sample_level<N>(texture, sampler, level0, u, v, linear);
            // As the scalar sampler: level1 only where blend is not 0 (the lerp by 0 gives s0's bits anyway).
            if (xsimd::any(blend != Batch(0.0f))) {
                const Texels<N> s1 = sample_level<N>(texture, sampler, level1, u, v, linear);
                const Texels<N> mixed = lerp(minified_result, s1, blend);
                for (int k = 0; k < N; ++k)
                    minified_result.c[k] = xsimd::select(blend != Batch(0.0f), mixed.c[k], minified_result.c[k]);
            }
        }
        for (int k = 0; k < N; ++k) result.c[k] = xsimd::select(minified, minified_result.c[k], result.c[k]);
    }
    float* const channels[] = {out.r, out.g, out.b, out.a};
    for (int k = 0; k < N; ++k) result.c[k].store_unaligned(channels[k] + i);
}

}  // namespace

// Entry points, declared in texture_sampling.cpp.
void TESSERA_SIMD_ENTRY(lod_from_derivatives)(const DerivativeInputs& in, int width, int height, float* lod) {
    const Batch w(static_cast<float>(width)), h(static_cast<float>(height));
    const std::size_t end = padded_count(in.count);
    for (std::size_t i = 0; i < end; i += Batch::size) {
        const Batch ux = xsimd::load_unaligned(in.dudx + i) * w, vx = xsimd::load_unaligned(in.dvdx + i) * h;
        const Batch uy = xsimd::load_unaligned(in.dudy + i) * w, vy = xsimd::load_unaligned(in.dvdy + i) * h;
        // log2(max(ρx, ρy)) = ½·log2(max(ρx², ρy²)): one square root fewer.
        const Batch rho2 = xsimd::max(ux * ux + vx * vx, uy * uy + vy * vy);
        (Batch(0.5f) * xsimd::log2(rho2)).store_unaligned(lod + i);
    }
}

void TESSERA_SIMD_ENTRY(sample_general)(const TextureView& texture, const Sampler& sampler, const TexCoordInputs& in,
                                        const TexelOutputs& out) {
    const std::size_t end = padded_count(in.count);
    if (out.a != nullptr) {
        for (std::size_t i = 0; i < end; i += Batch::size) sample_general_batch<4>(texture, sampler, in, i, out);
    } else if (out.g != nullptr) {
        for (std::size_t i = 0; i < end; i += Batch::size) sample_general_batch<3>(texture, sampler, in, i, out);
    } else {
        for (std::size_t i = 0; i < end; i += Batch::size) sample_general_batch<1>(texture, sampler, in, i, out);
    }
}

void TESSERA_SIMD_ENTRY(sample_trilinear)(const TextureView& texture, Wrap wrap, const TexCoordInputs& in,
                                          const TexelOutputs& out) {
    const std::size_t end = padded_count(in.count);
    // Only the channels asked for are fetched: a grey map costs a quarter of an RGBA one.
    if (out.a != nullptr) {
        for (std::size_t i = 0; i < end; i += Batch::size) sample_trilinear_batch<4>(texture, wrap, in, i, out);
    } else if (out.g != nullptr) {
        for (std::size_t i = 0; i < end; i += Batch::size) sample_trilinear_batch<3>(texture, wrap, in, i, out);
    } else {
        for (std::size_t i = 0; i < end; i += Batch::size) sample_trilinear_batch<1>(texture, wrap, in, i, out);
    }
}

}  // namespace tessera::texture
