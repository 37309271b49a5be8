#include "image/blend.hpp"

#include "image/display_encoding.hpp"

namespace tessera::image {

void TileRadiance::reserve(int tile_side, int samples_per_pixel) {
    side = tile_side, samples = samples_per_pixel;
    const std::size_t n = shade::padded_count(std::size_t(tile_side) * tile_side * samples_per_pixel);
    r.assign(n, 0.0f), g.assign(n, 0.0f), b.assign(n, 0.0f);
}

namespace {

void set(TileRadiance& tile, std::size_t i, float r, float g, float b) { tile.r[i] = r, tile.g[i] = g, tile.b[i] = b; }

}  // namespace

void fill_opaque(const raster::TileBuffers& coverage, const raster::TileRect& rect, const shade::RadianceOutputs& shaded,
                 const ClearValues& clear, TileRadiance& tile) {
    std::size_t k = 0;  // covered pixels come in the gather's row-major order
    for (int y = 0; y < rect.height(); ++y) {
        for (int x = 0; x < rect.width(); ++x) {
            const std::size_t pixel = std::size_t(y) * tile.side + x;
            if (coverage.covered(std::size_t(y) * coverage.side + x)) set(tile, pixel, shaded.r[k], shaded.g[k], shaded.b[k]), ++k;
            else set(tile, pixel, clear.radiance.r, clear.radiance.g, clear.radiance.b);
        }
    }
}

void fill_opaque(const raster::TileSamples& samples, const raster::TileRect& rect, const shade::RadianceOutputs& shaded,
                 const ClearValues& clear, TileRadiance& tile) {
    constexpr int n = raster::kMsaaSamples;
    for (int y = 0; y < rect.height(); ++y) {
        for (int x = 0; x < rect.width(); ++x) {
            const std::int32_t* fragment = &samples.fragment[std::size_t(n) * (std::size_t(y) * samples.side + x)];
            const std::size_t first = std::size_t(n) * (std::size_t(y) * tile.side + x);
            for (int s = 0; s < n; ++s) {
                const std::int32_t k = fragment[s];
                if (k >= 0) set(tile, first + s, shaded.r[k], shaded.g[k], shaded.b[k]);
                else set(tile, first + s, clear.radiance.r, clear.radiance.g, clear.radiance.b);
            }
        }
    }
}

void fill_background(const raster::TileRect& rect, const ClearValues& clear, TileRadiance& tile) {
    for (int y = 0; y < rect.height(); ++y)
        for (int x = 0; x < rect.width(); ++x)
            for (int s = 0; s < tile.samples; ++s)
                set(tile, std::size_t(tile.samples) * (std::size_t(y) * tile.side + x) + s, clear.radiance.r,
                    clear.radiance.g, clear.radiance.b);
}

void blend_over(const raster::BlendFragments& fragments, std::size_t count, const shade::RadianceOutputs& shaded,
                const float* alpha, TileRadiance& tile) {
    const raster::TileFragments& f = fragments.fragments;
    for (std::size_t k = 0; k < count; ++k) {
        const float a = alpha[k], keep = 1.0f - a;
        const float src_r = shaded.r[k] * a, src_g = shaded.g[k] * a, src_b = shaded.b[k] * a;
        const std::size_t first = std::size_t(tile.samples) * (std::size_t(f.y[k]) * tile.side + f.x[k]);
        for (int s = 0; s < tile.samples; ++s) {
            if (!(fragments.sample_mask[k] >> s & 1u)) continue;
            const std::size_t i = first + s;
            tile.r[i] = src_r + tile.r[i] * keep;
            tile.g[i] = src_g + tile.g[i] * keep;
            tile.b[i] = src_b + tile.b[i] * keep;
        }
    }
}

void resolve_blended_tile(TileRadiance& tile, const raster::TileRect& rect, simd::Isa isa, RenderedImage& image) {
    const int n = tile.samples;
    if (!image.radiance.empty()) {
        for (int y = 0; y < rect.height(); ++y) {
            for (int x = 0; x < rect.width(); ++x) {
                const std::size_t first = std::size_t(n) * (std::size_t(y) * tile.side + x);
                float* radiance = &image.radiance[3 * (std::size_t(rect.y0 + y) * image.width + rect.x0 + x)];
                const std::vector<float>* planes[3] = {&tile.r, &tile.g, &tile.b};
                for (int c = 0; c < 3; ++c) {
                    const float* v = planes[c]->data() + first;
                    // As resolve_tile_msaa sums them: in pairs, so equal samples give exactly their value.
                    radiance[c] = n == 1 ? v[0] : ((v[0] + v[1]) + (v[2] + v[3])) * 0.25f;
                }
            }
        }
    }
    // The display values as resolve_tile encodes them (exact, any ISA): r becomes packed RGB8.
    encode_display_unorm8(isa, std::size_t(tile.side) * tile.side * n, tile.r.data(), tile.g.data(), tile.b.data());
    for (int y = 0; y < rect.height(); ++y) {
        for (int x = 0; x < rect.width(); ++x) {
            const float* encoded = tile.r.data() + std::size_t(n) * (std::size_t(y) * tile.side + x);
            std::uint8_t* display = &image.display[3 * (std::size_t(rect.y0 + y) * image.width + rect.x0 + x)];
            for (int c = 0; c < 3; ++c) {
                unsigned sum = 0;
                for (int s = 0; s < n; ++s) sum += (packed_unorm8(encoded[s]) >> (8 * c)) & 0xFFu;
                display[c] = std::uint8_t((sum + unsigned(n) / 2) / unsigned(n));  // n = 1: the value itself
            }
        }
    }
}

}  // namespace tessera::image
