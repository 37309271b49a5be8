// The mip chain (Texture::build_mip_chain, texture.hpp): what glGenerateMipmap leaves to the
// implementation, done as an area-weighted box filter in linear light.
#include "texture/texture.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <vector>

#include "texture/texture_internal.hpp"

namespace tessera::texture {

using namespace detail;

namespace {

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

}  // namespace tessera::texture
