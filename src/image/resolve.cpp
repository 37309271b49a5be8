#include "image/resolve.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "image/resolve_kernels.hpp"
#include "image/resolve_msaa_kernels.hpp"
#include "raster/raster_limits.hpp"

namespace tessera::image {

glm::vec3 radiance_for_display(const glm::vec3& display) {
    glm::vec3 radiance;
    for (int c = 0; c < 3; ++c) {
        const float linear = std::pow(std::clamp(display[c], 0.0f, 1.0f), 2.2f);  // undo gamma
        // Undo Reinhard x/(x+1); white would need infinity, so stop at half's largest value.
        radiance[c] = linear < 1.0f ? std::min(linear / (1.0f - linear), 65504.0f) : 65504.0f;
    }
    return radiance;
}

namespace {

// Calls write(image_index, covered, k) for each pixel of the tile in row-major
// order, k counting the covered pixels met so far.
template <class Write>
void for_each_pixel(const raster::TileBuffers& coverage, const raster::TileRect& rect, int image_width, Write&& write) {
    std::size_t k = 0;
    for (int y = 0; y < rect.height(); ++y) {
        const std::size_t tile_row = std::size_t(y) * coverage.side;
        const std::size_t first = 3 * (std::size_t(rect.y0 + y) * image_width + rect.x0);
        for (int x = 0; x < rect.width(); ++x) {
            const bool covered = coverage.covered(tile_row + x);
            write(first + 3 * std::size_t(x), covered, k);
            k += covered;
        }
    }
}

// Background values of the AOV planes (documented at AovPlanes).
constexpr float kBackgroundDepth = std::numeric_limits<float>::infinity();

void write_aov_background(AovPlanes& aov, std::size_t pixel) {
    if (!aov.depth.empty()) aov.depth[pixel] = kBackgroundDepth;
    if (!aov.normal.empty()) std::fill_n(&aov.normal[3 * pixel], 3, 0.0f);
    if (!aov.albedo.empty()) std::fill_n(&aov.albedo[3 * pixel], 3, 0.0f);
    if (!aov.roughness.empty()) aov.roughness[pixel] = 0.0f;
    if (!aov.metallic.empty()) aov.metallic[pixel] = 0.0f;
    if (!aov.position.empty()) std::fill_n(&aov.position[3 * pixel], 3, 0.0f);
    if (!aov.object_id.empty()) aov.object_id[pixel] = 0;
    if (!aov.material_id.empty()) aov.material_id[pixel] = 0;
    if (!aov.shadow.empty()) aov.shadow[pixel] = 1.0f;
}

// Fragment k of `s`, showing triangle `triangle`.
void write_aov_fragment(AovPlanes& aov, std::size_t pixel, const shade::FragmentInputs& s, std::size_t k,
                        const ViewDepth& view_depth, const SurfaceIds& ids, std::uint32_t triangle) {
    if (!aov.object_id.empty()) aov.object_id[pixel] = ids.object_id(triangle);
    if (!aov.material_id.empty()) aov.material_id[pixel] = ids.material_id(triangle);
    if (!aov.shadow.empty()) {  // the mean of the shadowed lights' visibility, summed in slot order
        float sum = 0.0f;
        for (std::size_t p = 0; p < s.visibility_planes; ++p) sum += s.visibility[p * s.visibility_stride + k];
        aov.shadow[pixel] = s.visibility_planes > 0 ? sum / float(s.visibility_planes) : 1.0f;
    }
    const float x = s.world_x[k], y = s.world_y[k], z = s.world_z[k];
    if (!aov.depth.empty()) aov.depth[pixel] = view_depth(x, y, z);
    if (!aov.normal.empty()) {
        // The shader normalizes its input too; a degenerate normal becomes 0 rather than NaN.
        const float nx = s.normal_x[k], ny = s.normal_y[k], nz = s.normal_z[k];
        const float length = std::sqrt(nx * nx + ny * ny + nz * nz);
        const float scale = length > 0.0f && std::isfinite(length) ? 1.0f / length : 0.0f;
        float* n = &aov.normal[3 * pixel];
        n[0] = nx * scale, n[1] = ny * scale, n[2] = nz * scale;
    }
    if (!aov.albedo.empty()) {
        float* a = &aov.albedo[3 * pixel];
        a[0] = s.albedo_r[k], a[1] = s.albedo_g[k], a[2] = s.albedo_b[k];
    }
    if (!aov.roughness.empty()) aov.roughness[pixel] = s.roughness[k];
    if (!aov.metallic.empty()) aov.metallic[pixel] = s.metallic[k];
    if (!aov.position.empty()) {
        float* p = &aov.position[3 * pixel];
        p[0] = x, p[1] = y, p[2] = z;
    }
}

std::uint32_t packed_clear(const ClearValues& clear) {
    return std::uint32_t(clear.display[0]) | std::uint32_t(clear.display[1]) << 8 | std::uint32_t(clear.display[2]) << 16;
}

void clear_tile_display(const raster::TileRect& rect, const ClearValues& clear, RenderedImage& image) {
    // One row of the clear colour, copied to each row of the tile.
    std::uint8_t row[3 * raster::kMaxTileSize];
    const std::size_t row_bytes = 3 * std::size_t(rect.width());
    for (std::size_t i = 0; i < row_bytes; i += 3) std::memcpy(row + i, clear.display, 3);
    for (int y = rect.y0; y < rect.y1; ++y)
        std::memcpy(&image.display[3 * (std::size_t(y) * image.width + rect.x0)], row, row_bytes);
}

// The display rows of a tile: covered pixels take the next encoded fragment,
// the others the clear colour.
void write_display(simd::Isa isa, const raster::TileBuffers& coverage, const raster::TileRect& rect,
                   std::size_t count, const float* encoded, std::uint32_t clear_packed, RenderedImage& image) {
    if (isa == simd::Isa::scalar) {
        return for_each_pixel(coverage, rect, image.width, [&](std::size_t i, bool covered, std::size_t k) {
            const std::uint32_t value = covered ? packed_unorm8(encoded[k]) : clear_packed;
            for (int c = 0; c < 3; ++c) image.display[i + c] = std::uint8_t(value >> (8 * c));
        });
    }
    const DisplayRows rows{coverage.depth.data(), coverage.side, rect.width(), rect.height(), encoded, count, clear_packed,
                           &image.display[3 * (std::size_t(rect.y0) * image.width + rect.x0)],
                           3 * std::size_t(image.width)};
    switch (isa) {
        case simd::Isa::sse4: return write_display_rows_sse4(rows);
        case simd::Isa::avx2: return write_display_rows_avx2(rows);
        case simd::Isa::avx512: return write_display_rows_avx512(rows);
        case simd::Isa::scalar: break;
    }
}

// The radiance rows of a tile: covered pixels take the next shaded value, the
// others the background's.
void write_radiance(simd::Isa isa, const raster::TileBuffers& coverage, const raster::TileRect& rect,
                    const shade::RadianceOutputs& shaded, const ClearValues& clear, RenderedImage& image) {
    if (isa == simd::Isa::scalar) {
        const glm::vec3& clear_radiance = clear.radiance;
        return for_each_pixel(coverage, rect, image.width, [&](std::size_t i, bool covered, std::size_t k) {
            float* radiance = &image.radiance[i];
            if (covered) radiance[0] = shaded.r[k], radiance[1] = shaded.g[k], radiance[2] = shaded.b[k];
            else radiance[0] = clear_radiance.r, radiance[1] = clear_radiance.g, radiance[2] = clear_radiance.b;
        });
    }
    const RadianceRows rows{coverage.depth.data(), coverage.side, rect.width(), rect.height(),
                            {shaded.r, shaded.g, shaded.b}, {clear.radiance.r, clear.radiance.g, clear.radiance.b},
                            &image.radiance[3 * (std::size_t(rect.y0) * image.width + rect.x0)],
                            3 * std::size_t(image.width)};
    switch (isa) {
        case simd::Isa::sse4: return write_radiance_rows_sse4(rows);
        case simd::Isa::avx2: return write_radiance_rows_avx2(rows);
        case simd::Isa::avx512: return write_radiance_rows_avx512(rows);
        case simd::Isa::scalar: break;
    }
}

}  // namespace

ClearValues clear_values(const glm::vec3& clear_color) {
    return {radiance_for_display(clear_color),
            {quantize_unorm8(clear_color.r), quantize_unorm8(clear_color.g), quantize_unorm8(clear_color.b)}};
}

namespace {

// Prefetches for writing every cache line of `rows` rows of `row_bytes` bytes, `stride` apart.
void prefetch_rows_for_write(const std::uint8_t* first, std::size_t row_bytes, std::size_t stride, int rows) {
    for (int y = 0; y < rows; ++y) {
        const std::uint8_t* row = first + std::size_t(y) * stride;
        // Probes at most a line apart, and the last byte: every line the row touches.
        for (std::size_t b = 0; b < row_bytes; b += 64) __builtin_prefetch(row + b, 1);
        __builtin_prefetch(row + row_bytes - 1, 1);
    }
}

}  // namespace

void prefetch_tile_output(const raster::TileRect& rect, const RenderedImage& image) {
    const std::size_t pixels = std::size_t(rect.width()) * std::size_t(rect.height());
    const std::size_t bytes = (image.display.empty() ? 0 : 3) + (image.radiance.empty() ? 0 : 3 * sizeof(float));
    if (pixels == 0 || pixels * bytes > kPrefetchTileOutputBytes) return;
    const std::size_t first = std::size_t(rect.y0) * std::size_t(image.width) + std::size_t(rect.x0);
    if (!image.display.empty())
        prefetch_rows_for_write(&image.display[3 * first], 3 * std::size_t(rect.width()), 3 * std::size_t(image.width),
                                rect.height());
    if (!image.radiance.empty())
        prefetch_rows_for_write(reinterpret_cast<const std::uint8_t*>(&image.radiance[3 * first]),
                                3 * sizeof(float) * std::size_t(rect.width()),
                                3 * sizeof(float) * std::size_t(image.width), rect.height());
}

void clear_tile(const raster::TileRect& rect, const ClearValues& clear, RenderedImage& image) {
    clear_tile_display(rect, clear, image);
    const glm::vec3& clear_radiance = clear.radiance;
    if (!image.radiance.empty()) for (int y = rect.y0; y < rect.y1; ++y) {
        const std::size_t first = 3 * (std::size_t(y) * image.width + rect.x0);
        const std::size_t end = first + 3 * std::size_t(rect.width());
        for (std::size_t i = first; i < end; i += 3)
            image.radiance[i] = clear_radiance.r, image.radiance[i + 1] = clear_radiance.g,
            image.radiance[i + 2] = clear_radiance.b;
    }
    if (image.aov.empty()) return;
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; ++x) write_aov_background(image.aov, std::size_t(y) * image.width + x);
}

void resolve_aov_tile(const raster::TileBuffers& coverage, const raster::TileRect& rect,
                      const shade::FragmentInputs& surface, const ViewDepth& view_depth, const SurfaceIds& ids,
                      RenderedImage& image) {
    const bool wants_ids = ids.object_of_chunk != nullptr;
    std::size_t k = 0;
    for (int y = 0; y < rect.height(); ++y) {
        const std::size_t tile_row = std::size_t(y) * coverage.side;
        const std::size_t first = std::size_t(rect.y0 + y) * image.width + rect.x0;
        for (int x = 0; x < rect.width(); ++x) {
            // A pixel holds its triangle's position in the tile's list (TileBuffers::triangles),
            // looked up only for the id AOVs.
            if (coverage.covered(tile_row + x))
                write_aov_fragment(image.aov, first + x, surface, k++, view_depth, ids,
                                   wants_ids ? coverage.triangles.ids[coverage.triangle[tile_row + x]] : 0);
            else write_aov_background(image.aov, first + x);
        }
    }
}

void resolve_tile(const raster::TileBuffers& coverage, const raster::TileRect& rect, std::size_t count,
                  const shade::RadianceOutputs& shaded, const ClearValues& clear, simd::Isa isa,
                  RenderedImage& image) {
    if (!image.radiance.empty()) write_radiance(isa, coverage, rect, shaded, clear, image);
    if (count == 0) return clear_tile_display(rect, clear, image);
    encode_display_unorm8(isa, count, shaded.r, shaded.g, shaded.b);
    write_display(isa, coverage, rect, count, shaded.r, packed_clear(clear), image);
}

namespace {

// The vector loops of resolve_tile_msaa (resolve_msaa_kernels.hpp).
MsaaResolveRows msaa_rows(const raster::TileSamples& samples, const raster::TileRect& rect,
                          const shade::RadianceOutputs& shaded, const ClearValues& clear, RenderedImage& image) {
    MsaaResolveRows rows{};
    rows.fragment = samples.fragment.data(), rows.side = samples.side;
    rows.width = rect.width(), rows.height = rect.height();
    rows.plane[0] = shaded.r, rows.plane[1] = shaded.g, rows.plane[2] = shaded.b;
    for (int c = 0; c < 3; ++c) rows.clear_radiance[c] = clear.radiance[c];
    if (!image.radiance.empty()) rows.radiance = &image.radiance[3 * (std::size_t(rect.y0) * image.width + rect.x0)];
    rows.radiance_stride = 3 * std::size_t(image.width);
    rows.encoded = shaded.r, rows.clear_display = packed_clear(clear);
    rows.display = &image.display[3 * (std::size_t(rect.y0) * image.width + rect.x0)];
    rows.display_stride = 3 * std::size_t(image.width);
    return rows;
}

void resolve_msaa_radiance(simd::Isa isa, const MsaaResolveRows& rows) {
    switch (isa) {
        case simd::Isa::sse4: return resolve_msaa_radiance_rows_sse4(rows);
        case simd::Isa::avx2: return resolve_msaa_radiance_rows_avx2(rows);
        case simd::Isa::avx512: return resolve_msaa_radiance_rows_avx512(rows);
        case simd::Isa::scalar: break;
    }
}

void resolve_msaa_display(simd::Isa isa, const MsaaResolveRows& rows) {
    switch (isa) {
        case simd::Isa::sse4: return resolve_msaa_display_rows_sse4(rows);
        case simd::Isa::avx2: return resolve_msaa_display_rows_avx2(rows);
        case simd::Isa::avx512: return resolve_msaa_display_rows_avx512(rows);
        case simd::Isa::scalar: break;
    }
}

}  // namespace

void resolve_tile_msaa(const raster::TileSamples& samples, const raster::TileRect& rect, std::size_t count,
                       const shade::RadianceOutputs& shaded, const ClearValues& clear, simd::Isa isa,
                       RenderedImage& image) {
    constexpr int n = raster::kMsaaSamples;
    static_assert(n == 4, "the averages below add four samples in pairs");
    if (isa != simd::Isa::scalar) {
        const MsaaResolveRows rows = msaa_rows(samples, rect, shaded, clear, image);
        if (!image.radiance.empty()) resolve_msaa_radiance(isa, rows);
        if (count == 0) return clear_tile_display(rect, clear, image);
        encode_display_unorm8(isa, count, shaded.r, shaded.g, shaded.b);  // shaded.r becomes `encoded`
        return resolve_msaa_display(isa, rows);
    }
    if (!image.radiance.empty()) for (int y = 0; y < rect.height(); ++y) {
        for (int x = 0; x < rect.width(); ++x) {
            const std::int32_t* fragment = &samples.fragment[std::size_t(n) * (std::size_t(y) * samples.side + x)];
            const std::size_t i = 3 * (std::size_t(rect.y0 + y) * image.width + rect.x0 + x);
            const float* planes[3] = {shaded.r, shaded.g, shaded.b};
            for (int c = 0; c < 3; ++c) {
                float v[n];
                for (int s = 0; s < n; ++s) v[s] = fragment[s] >= 0 ? planes[c][fragment[s]] : clear.radiance[c];
                image.radiance[i + c] = ((v[0] + v[1]) + (v[2] + v[3])) * 0.25f;
            }
        }
    }
    if (count == 0) return clear_tile_display(rect, clear, image);
    encode_display_unorm8(isa, count, shaded.r, shaded.g, shaded.b);
    const std::uint32_t clear_packed = packed_clear(clear);
    for (int y = 0; y < rect.height(); ++y) {
        for (int x = 0; x < rect.width(); ++x) {
            const std::int32_t* fragment = &samples.fragment[std::size_t(n) * (std::size_t(y) * samples.side + x)];
            std::uint8_t* display = &image.display[3 * (std::size_t(rect.y0 + y) * image.width + rect.x0 + x)];
            std::uint32_t value[n];
            for (int s = 0; s < n; ++s) value[s] = fragment[s] >= 0 ? packed_unorm8(shaded.r[fragment[s]]) : clear_packed;
            for (int c = 0; c < 3; ++c) {
                unsigned sum = 0;
                for (int s = 0; s < n; ++s) sum += (value[s] >> (8 * c)) & 0xFFu;
                display[c] = std::uint8_t((sum + n / 2) / n);
            }
        }
    }
}

void resolve_aov_tile_msaa(const raster::TileSamples& samples, const raster::TileRect& rect,
                           const shade::FragmentInputs& surface, const ViewDepth& view_depth, const FragmentIds& ids,
                           RenderedImage& image) {
    for (int y = 0; y < rect.height(); ++y) {
        const std::size_t first = std::size_t(rect.y0 + y) * image.width + rect.x0;
        for (int x = 0; x < rect.width(); ++x) {
            const std::int32_t k = samples.fragment[std::size_t(raster::kMsaaSamples) * (std::size_t(y) * samples.side + x)];
            if (k >= 0)
                write_aov_fragment(image.aov, first + x, surface, std::size_t(k), view_depth, ids.ids,
                                   ids.ids.object_of_chunk ? ids.triangle[k] : 0);
            else write_aov_background(image.aov, first + x);
        }
    }
}

}  // namespace tessera::image
