// The vertex stage over vectors of vertices (vertex_kernels.hpp), compiled once
// per ISA. Vertices are stored one after another (xyz, xyz, ...); a run is moved
// through small per-lane arrays so that the arithmetic — two matrix products, the
// normal matrix, outcodes and the viewport transform — runs a vector at a time.
#include <algorithm>
#include <bit>
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "simd/prefetch.hpp"
#include "simd/transpose.hpp"

#include "geometry/clipper.hpp"
#include "geometry/vertex_kernels.hpp"
#include "geometry/viewport.hpp"

namespace tessera::geometry {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Float = xsimd::batch<float, Arch>;
using Int = xsimd::batch<std::int32_t, Arch>;
constexpr std::size_t kLanes = Float::size;
// How far ahead of its stores the kernel prefetches its output, in vertices.
constexpr std::size_t kAhead = 4 * kLanes;

struct Vec4 {
    Float x, y, z, w;
};

// Row r of glm's mat4 · vec4(p, 1): (m0·x + m1·y) + (m2·z + m3·1), glm's order.
Float affine_row(const float* m, int r, const Float& x, const Float& y, const Float& z) {
    return (Float(m[r]) * x + Float(m[4 + r]) * y) + (Float(m[8 + r]) * z + Float(m[12 + r]));
}
// Row r of glm's mat3 · vec3: m0·x + m1·y + m2·z, left to right.
Float linear_row(const float* m, int r, const Float& x, const Float& y, const Float& z) {
    return Float(m[r]) * x + Float(m[3 + r]) * y + Float(m[6 + r]) * z;
}

// An outcode bit where `outside` holds, as float bits so every mask stays a float mask.
Float bit_if(const xsimd::batch_bool<float, Arch>& outside, std::uint32_t bit) {
    return xsimd::select(outside, xsimd::bitwise_cast<Float>(Int(std::int32_t(bit))), Float(0.0f));
}

// outcode() of clipper.cpp, lane by lane; a non-finite normal or position gives kNotFinite alone.
Int outcodes(const Vec4& p, const Float& nx, const Float& ny, const Float& nz, const Float& guard_x,
             const Float& guard_y) {
    const auto finite = xsimd::isfinite(p.x) & xsimd::isfinite(p.y) & xsimd::isfinite(p.z) & xsimd::isfinite(p.w) &
                        xsimd::isfinite(nx) & xsimd::isfinite(ny) & xsimd::isfinite(nz);
    const Float gx = guard_x * p.w, gy = guard_y * p.w;
    const Float code = bit_if(p.z < -p.w, kOutsideNear) | bit_if(p.z > p.w, kOutsideFar) |
                       bit_if(p.x > gx, kOutsideGuardRight) | bit_if(p.x < -gx, kOutsideGuardLeft) |
                       bit_if(p.y > gy, kOutsideGuardTop) | bit_if(p.y < -gy, kOutsideGuardBottom) |
                       bit_if(p.x > p.w, kOutsideViewRight) | bit_if(p.x < -p.w, kOutsideViewLeft) |
                       bit_if(p.y > p.w, kOutsideViewTop) | bit_if(p.y < -p.w, kOutsideViewBottom);
    return xsimd::bitwise_cast<Int>(
        xsimd::select(finite, code, xsimd::bitwise_cast<Float>(Int(std::int32_t(kNotFinite)))));
}

#if defined(__AVX2__)
// Lanes first .. first + 8 of a run's records (stride floats apart; 16 bytes are
// read from each, so the last must not be the run's last): their first three
// words as three vectors.
void load_records8(const float* base, std::size_t stride, std::size_t first, __m256 (&abc)[3]) {
    __m256 r[4];
    for (std::size_t j = 0; j < 4; ++j)
        r[j] = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(base + stride * (first + j))),
                                    _mm_loadu_ps(base + stride * (first + j + 4)), 1);
    simd::transpose4x4_halves(r);
    abc[0] = r[0], abc[1] = r[1], abc[2] = r[2];
}

// Vertices first .. first + 8 out, from one vector per word: the 12 words of
// each ShadedVertex (clip xyzw, world xyz, normal xyz, uv) and its screen
// words (x, y, depth bits, outcode).
void store_records8(const VertexRunOutput& out, std::size_t first, __m256 (&words)[8], __m256 (&tail)[4],
                    __m256 (&screen)[4]) {
    simd::transpose8x8(words);
    simd::transpose4x4_halves(tail);
    simd::transpose4x4_halves(screen);
    for (std::size_t j = 0; j < 8; ++j) {
        float* vertex = out.vertices + 12 * (first + j);
        _mm256_storeu_ps(vertex, words[j]);
        const __m128 rest = j < 4 ? _mm256_castps256_ps128(tail[j]) : _mm256_extractf128_ps(tail[j - 4], 1);
        _mm_storeu_ps(vertex + 8, rest);
        const __m128 on_screen = j < 4 ? _mm256_castps256_ps128(screen[j]) : _mm256_extractf128_ps(screen[j - 4], 1);
        _mm_storeu_ps(reinterpret_cast<float*>(out.screen + 4 * (first + j)), on_screen);
    }
}

// Lanes 8h .. 8h + 8 of a vector (simd::half_of, or the AVX2 vector itself).
__m256 half_of(const Float& x, std::size_t h) {
#if defined(__AVX512F__)
    return simd::half_of(x, int(h));
#else
    (void)h;
    return x;
#endif
}
#endif

void shade_vertex_run(const VertexRunInput& in, const VertexRunOutput& out) {
    // Per-lane staging: object-space inputs in, results out.
    alignas(64) float position[3][kLanes], normal[3][kLanes], uv[2][kLanes];
    alignas(64) float clip[4][kLanes], world[3][kLanes], world_normal[3][kLanes], depth_lanes[kLanes];
    const Float guard_x(in.guard_x_ndc), guard_y(in.guard_y_ndc), width(in.width), height(in.height);
    const Float half(0.5f), one(1.0f), subpixel(static_cast<float>(kSubpixelScale));

    for (std::size_t first = 0; first < in.count; first += kLanes) {
        const std::size_t n = std::min(kLanes, in.count - first);
        Float px, py, pz, nx0, ny0, nz0, u, v;
#if defined(__AVX2__)
        // Lanes whose 16-byte loads (xyz + 1 float, uv + 2) stay inside the run: records in, transposed
        // 8 lanes at a time (AVX-512: two such halves joined).
        const bool transposed = first + kLanes < in.count;
        if (transposed) {
            const auto load = [&](const float* base, std::size_t stride, Float& a, Float& b, Float& c) {
                __m256 h[kLanes / 8][3];
                for (std::size_t part = 0; part < kLanes / 8; ++part)
                    load_records8(base, stride, first + 8 * part, h[part]);
#if defined(__AVX512F__)
                a = simd::join_halves(h[0][0], h[1][0]), b = simd::join_halves(h[0][1], h[1][1]);
                c = simd::join_halves(h[0][2], h[1][2]);
#else
                a = h[0][0], b = h[0][1], c = h[0][2];
#endif
            };
            load(in.positions, 3, px, py, pz);
            load(in.normals, 3, nx0, ny0, nz0);
            Float unused;
            if (in.uvs) load(in.uvs, 2, u, v, unused);
            else u = v = Float(0.0f);
        }
#else
        constexpr bool transposed = false;
#endif
        if (!transposed) {
            for (std::size_t i = 0; i < kLanes; ++i) {
                // Lanes past the run compute on zeros and are never written back.
                const bool live = i < n;
                for (int c = 0; c < 3; ++c) {
                    position[c][i] = live ? in.positions[3 * (first + i) + c] : 0.0f;
                    normal[c][i] = live ? in.normals[3 * (first + i) + c] : 0.0f;
                }
                for (int c = 0; c < 2; ++c) uv[c][i] = live && in.uvs ? in.uvs[2 * (first + i) + c] : 0.0f;
            }
            px = Float::load_aligned(position[0]), py = Float::load_aligned(position[1]);
            pz = Float::load_aligned(position[2]);
            nx0 = Float::load_aligned(normal[0]), ny0 = Float::load_aligned(normal[1]);
            nz0 = Float::load_aligned(normal[2]);
            u = Float::load_aligned(uv[0]), v = Float::load_aligned(uv[1]);
        }
        const Float wx = affine_row(in.model, 0, px, py, pz), wy = affine_row(in.model, 1, px, py, pz),
                    wz = affine_row(in.model, 2, px, py, pz);
        const Vec4 p{affine_row(in.view_projection, 0, wx, wy, wz), affine_row(in.view_projection, 1, wx, wy, wz),
                     affine_row(in.view_projection, 2, wx, wy, wz), affine_row(in.view_projection, 3, wx, wy, wz)};
        const Float nx = linear_row(in.normal_matrix, 0, nx0, ny0, nz0),
                    ny = linear_row(in.normal_matrix, 1, nx0, ny0, nz0),
                    nz = linear_row(in.normal_matrix, 2, nx0, ny0, nz0);
        const Int codes = outcodes(p, nx, ny, nz, guard_x, guard_y);
        // to_screen(): the viewport transform, snapped to 24.8 fixed point
        // (round to nearest even, as lrintf).
        const Float w_inv = one / p.w;
        const Float sx = (p.x * w_inv * half + half) * width, sy = (half - p.y * w_inv * half) * height;
        const Int screen_x = xsimd::nearbyint_as_int(sx * subpixel), screen_y = xsimd::nearbyint_as_int(sy * subpixel);
        const Float depth = p.z * w_inv * half + half;
#if defined(__AVX2__)
        if (n == kLanes) {  // whole records out, transposed 8 lanes at a time
            // The output lines of the vector kAhead vertices on, asked for
            // exclusive now (simd/prefetch.hpp): a frame on several threads
            // read them on every core last frame, and a store to a line the
            // other core holds waits for that copy to go (on one thread the
            // vertex pass measured 1.15-1.20x faster with it too). Only lines
            // of this run's vertices: the next run may be another thread's.
            if (first + kAhead + kLanes <= in.count) {
                const auto* vertices = reinterpret_cast<const char*>(out.vertices + 12 * (first + kAhead));
                for (std::size_t b = 0; b < sizeof(float) * 12 * kLanes; b += 64) simd::prefetch_for_write(vertices + b);
                const auto* screen = reinterpret_cast<const char*>(out.screen + 4 * (first + kAhead));
                for (std::size_t b = 0; b < sizeof(std::int32_t) * 4 * kLanes; b += 64) simd::prefetch_for_write(screen + b);
                simd::prefetch_for_write(out.outcodes + first + kAhead);
            }
            for (std::size_t h = 0; h < kLanes / 8; ++h) {
                __m256 words[8] = {half_of(p.x, h), half_of(p.y, h), half_of(p.z, h), half_of(p.w, h),
                                   half_of(wx, h),  half_of(wy, h),  half_of(wz, h),  half_of(nx, h)};
                __m256 tail[4] = {half_of(ny, h), half_of(nz, h), half_of(u, h), half_of(v, h)};
                __m256 screen[4] = {half_of(xsimd::bitwise_cast<Float>(screen_x), h),
                                    half_of(xsimd::bitwise_cast<Float>(screen_y), h), half_of(depth, h),
                                    half_of(xsimd::bitwise_cast<Float>(codes), h)};
                store_records8(out, first + 8 * h, words, tail, screen);
            }
            codes.store_unaligned(reinterpret_cast<std::int32_t*>(out.outcodes + first));
            continue;
        }
#endif
        alignas(64) std::int32_t code[kLanes], screen_x_lanes[kLanes], screen_y_lanes[kLanes];
        codes.store_aligned(code);
        screen_x.store_aligned(screen_x_lanes), screen_y.store_aligned(screen_y_lanes);
        depth.store_aligned(depth_lanes);
        u.store_aligned(uv[0]), v.store_aligned(uv[1]);
        p.x.store_aligned(clip[0]), p.y.store_aligned(clip[1]), p.z.store_aligned(clip[2]), p.w.store_aligned(clip[3]);
        wx.store_aligned(world[0]), wy.store_aligned(world[1]), wz.store_aligned(world[2]);
        nx.store_aligned(world_normal[0]), ny.store_aligned(world_normal[1]), nz.store_aligned(world_normal[2]);

        for (std::size_t i = 0; i < n; ++i) {
            float* vertex = out.vertices + 12 * (first + i);
            vertex[0] = clip[0][i], vertex[1] = clip[1][i], vertex[2] = clip[2][i], vertex[3] = clip[3][i];
            vertex[4] = world[0][i], vertex[5] = world[1][i], vertex[6] = world[2][i];
            vertex[7] = world_normal[0][i], vertex[8] = world_normal[1][i], vertex[9] = world_normal[2][i];
            vertex[10] = uv[0][i], vertex[11] = uv[1][i];
            out.outcodes[first + i] = std::uint32_t(code[i]);
            std::int32_t* s = out.screen + 4 * (first + i);
            s[0] = screen_x_lanes[i], s[1] = screen_y_lanes[i];
            s[2] = std::bit_cast<std::int32_t>(depth_lanes[i]), s[3] = code[i];
        }
    }
}

}  // namespace

void TESSERA_SIMD_ENTRY(shade_vertex_run)(const VertexRunInput& in, const VertexRunOutput& out) {
    shade_vertex_run(in, out);
}

}  // namespace tessera::geometry
