#include "image/environment_background.hpp"

#include <cmath>

#include "image/display_encoding.hpp"
#include "raster/raster_limits.hpp"
#include "simd/lane_padding.hpp"

namespace tessera::image {

EnvironmentBackground::EnvironmentBackground(const Scene& scene, float exposure_scale)
    : exposure_scale_(exposure_scale), width_(scene.width), height_(scene.height) {
    if (!scene.environment.present() || !scene.environment.background) return;
    ibl_ = shade::ibl_lighting(scene.environment);
    // The inverse of the view rotation (background.vs drops the translation),
    // and the projection's extent at unit distance.
    const Camera& camera = scene.camera;
    forward_ = glm::normalize(camera.target - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward_, camera.up));
    const glm::vec3 up = glm::cross(right, forward_);
    const float tan_half = std::tan(glm::radians(camera.fov_y_degrees) * 0.5f);
    const float aspect = float(scene.width) / float(scene.height);
    right_ = right * (tan_half * aspect);
    up_ = up * tan_half;
}

glm::vec3 EnvironmentBackground::direction(int x, float ndc_y) const {
    return shade::background_ray({forward_, right_, up_, float(width_), ndc_y}, float(x));
}

glm::vec3 EnvironmentBackground::radiance(int x, int y) const {
    const glm::vec3 value =
        shade::environment_background(ibl_, direction(x, 1.0f - 2.0f * (float(y) + 0.5f) / float(height_)));
    return exposure_scale_ == 1.0f ? value : value * exposure_scale_;
}

template <class Covered>
void EnvironmentBackground::paint_pixels(const raster::TileRect& rect, Covered&& covered, simd::Isa isa,
                                         RenderedImage& image) const {
    constexpr std::size_t kRow = simd::padded_count(raster::kMaxTileSize);
    float columns[kRow], r[kRow], g[kRow], b[kRow];
    int column[raster::kMaxTileSize];
    shade::BackgroundRays rays{forward_, right_, up_, float(width_), 0.0f};
    for (int y = 0; y < rect.height(); ++y) {
        std::size_t n = 0;
        rays.ndc_y = 1.0f - 2.0f * (float(rect.y0 + y) + 0.5f) / float(height_);
        for (int x = 0; x < rect.width(); ++x) {
            if (covered(x, y)) continue;
            columns[n] = float(rect.x0 + x), column[n] = x;
            ++n;
        }
        for (std::size_t k = n; k < simd::padded_count(n); ++k) columns[k] = float(rect.x0);
        shade::sample_environment_background_row(isa, n, columns, rays, ibl_, exposure_scale_, {r, g, b});
        if (n == 0) continue;
        const std::size_t row_first = std::size_t(rect.y0 + y) * std::size_t(image.width) + std::size_t(rect.x0);
        if (!image.radiance.empty())
            for (std::size_t k = 0; k < n; ++k) {
                float* out = &image.radiance[3 * (row_first + std::size_t(column[k]))];
                out[0] = r[k], out[1] = g[k], out[2] = b[k];
            }
        for (std::size_t k = n; k < simd::padded_count(n); ++k) r[k] = g[k] = b[k] = 0.0f;
        encode_display_unorm8(isa, n, r, g, b);
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint32_t value = packed_unorm8(r[k]);
            std::uint8_t* out = &image.display[3 * (row_first + std::size_t(column[k]))];
            out[0] = std::uint8_t(value), out[1] = std::uint8_t(value >> 8), out[2] = std::uint8_t(value >> 16);
        }
    }
}

void EnvironmentBackground::paint(const raster::TileRect& rect, const raster::TileBuffers* coverage, simd::Isa isa,
                                  RenderedImage& image) const {
    if (coverage == nullptr) return paint_pixels(rect, [](int, int) { return false; }, isa, image);
    paint_pixels(rect, [&](int x, int y) { return coverage->covered(std::size_t(y) * coverage->side + std::size_t(x)); },
                 isa, image);
}

void EnvironmentBackground::paint(const raster::TileRect& rect, const raster::TileSamples& samples, simd::Isa isa,
                                  RenderedImage& image) const {
    constexpr int n = raster::kMsaaSamples;
    paint_pixels(rect, [&](int x, int y) {
        const std::int32_t* fragment = &samples.fragment[std::size_t(n) * (std::size_t(y) * samples.side + std::size_t(x))];
        for (int s = 0; s < n; ++s)
            if (fragment[s] >= 0) return true;
        return false;
    }, isa, image);
}

void EnvironmentBackground::paint(const raster::TileRect& rect, const raster::TileBuffers* coverage,
                                  const raster::TileSamples* samples, TileRadiance& tile) const {
    constexpr int n = raster::kMsaaSamples;
    for (int y = 0; y < rect.height(); ++y)
        for (int x = 0; x < rect.width(); ++x) {
            const std::size_t first = std::size_t(tile.samples) * (std::size_t(y) * tile.side + std::size_t(x));
            bool any = false;
            glm::vec3 value;
            for (int s = 0; s < tile.samples; ++s) {
                bool covered = false;
                if (coverage) covered = coverage->covered(std::size_t(y) * coverage->side + std::size_t(x));
                if (samples)
                    covered = samples->fragment[std::size_t(n) * (std::size_t(y) * samples->side + std::size_t(x)) +
                                                std::size_t(s)] >= 0;
                if (covered) continue;
                if (!any) value = radiance(rect.x0 + x, rect.y0 + y), any = true;
                tile.r[first + std::size_t(s)] = value.r, tile.g[first + std::size_t(s)] = value.g,
                tile.b[first + std::size_t(s)] = value.b;
            }
        }
}

}  // namespace tessera::image
