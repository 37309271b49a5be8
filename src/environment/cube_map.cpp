#include "environment/cube_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera::environment {

namespace {

// x clamped to [low, high], NaN to low.
float clamp_nan_low(float x, float low, float high) {
    const float above = x > low ? x : low;
    return above < high ? above : high;
}

}  // namespace

FaceCoords face_coords(const glm::vec3& d) {
    const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    int face;
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = d.x >= 0.0f ? 0 : 1, ma = ax;
        sc = d.x >= 0.0f ? -d.z : d.z, tc = -d.y;
    } else if (ay >= az) {
        face = d.y >= 0.0f ? 2 : 3, ma = ay;
        sc = d.x, tc = d.y >= 0.0f ? d.z : -d.z;
    } else {
        face = d.z >= 0.0f ? 4 : 5, ma = az;
        sc = d.z >= 0.0f ? d.x : -d.x, tc = -d.y;
    }
    return {face, 0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)};
}

glm::vec3 face_direction(int face, float s, float t) {
    const float sc = 2.0f * s - 1.0f, tc = 2.0f * t - 1.0f;
    switch (face) {
        case 0: return {1.0f, -tc, -sc};
        case 1: return {-1.0f, -tc, sc};
        case 2: return {sc, 1.0f, tc};
        case 3: return {sc, -1.0f, -tc};
        case 4: return {sc, -tc, 1.0f};
        default: return {-sc, -tc, -1.0f};
    }
}

CubeMap::CubeMap(int size, int levels) {
    std::size_t offset = 0;
    for (int l = 0; l < levels; ++l) {
        const int n = std::max(1, size >> l);
        level_size_.push_back(n);
        level_offset_.push_back(offset);
        offset += std::size_t(kCubeFaces) * std::size_t(n + 2) * std::size_t(n + 2);
    }
    data_.assign(offset, glm::vec3(0.0f));
}

void CubeMap::fill_borders(int level) {
    const int n = size(level);
    const auto nearest = [&](const glm::vec3& d) {
        const FaceCoords c = face_coords(d);
        const int x = std::clamp(int(std::floor(c.s * float(n))), 0, n - 1);
        const int y = std::clamp(int(std::floor(c.t * float(n))), 0, n - 1);
        return texel(level, c.face, x, y);
    };
    for (int f = 0; f < kCubeFaces; ++f) {
        for (int i = 0; i < n; ++i) {
            const float mid = (float(i) + 0.5f) / float(n);
            const float before = -0.5f / float(n), after = (float(n) + 0.5f) / float(n);
            texel(level, f, i, -1) = nearest(face_direction(f, mid, before));
            texel(level, f, i, n) = nearest(face_direction(f, mid, after));
            texel(level, f, -1, i) = nearest(face_direction(f, before, mid));
            texel(level, f, n, i) = nearest(face_direction(f, after, mid));
        }
        // A corner meets three faces: GL's seamless rule takes their mean.
        for (const auto [cx, cy, ix, iy] : {std::array<int, 4>{-1, -1, 0, 0}, {n, -1, n - 1, 0}, {-1, n, 0, n - 1},
                                            {n, n, n - 1, n - 1}})
            texel(level, f, cx, cy) = (texel(level, f, ix, iy) + texel(level, f, cx, iy) + texel(level, f, ix, cy)) / 3.0f;
    }
}

void CubeMap::generate_mipmaps() {
    for (int l = 1; l < levels(); ++l) {
        const int n = size(l), above = size(l - 1);
        for (int f = 0; f < kCubeFaces; ++f)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const int x0 = std::min(2 * x, above - 1), x1 = std::min(2 * x + 1, above - 1);
                    const int y0 = std::min(2 * y, above - 1), y1 = std::min(2 * y + 1, above - 1);
                    texel(l, f, x, y) = ((texel(l - 1, f, x0, y0) + texel(l - 1, f, x1, y0)) +
                                         (texel(l - 1, f, x0, y1) + texel(l - 1, f, x1, y1))) * 0.25f;
                }
        fill_borders(l);
    }
}

glm::vec3 CubeMap::sample_bilinear(const glm::vec3& direction, int level) const {
    const FaceCoords c = face_coords(direction);
    const int n = size(level);
    const float u = c.s * float(n) - 0.5f, v = c.t * float(n) - 0.5f;  // in [−0.5, n − 0.5]
    const float x0f = std::floor(u), y0f = std::floor(v);
    const float fx = u - x0f, fy = v - y0f;
    // The clamps only matter for non-finite directions (NaN goes to −1, as the
    // SIMD kernels' max does); the border holds x0 + 1 = n.
    const int x0 = int(clamp_nan_low(x0f, -1.0f, float(n - 1))), y0 = int(clamp_nan_low(y0f, -1.0f, float(n - 1)));
    const glm::vec3& t00 = texel(level, c.face, x0, y0);
    const glm::vec3& t10 = texel(level, c.face, x0 + 1, y0);
    const glm::vec3& t01 = texel(level, c.face, x0, y0 + 1);
    const glm::vec3& t11 = texel(level, c.face, x0 + 1, y0 + 1);
    const glm::vec3 top = t00 + (t10 - t00) * fx;
    const glm::vec3 bottom = t01 + (t11 - t01) * fx;
    return top + (bottom - top) * fy;
}

glm::vec3 CubeMap::sample_trilinear(const glm::vec3& direction, float lod) const {
    const int top_level = levels() - 1;
    const float clamped = std::clamp(lod, 0.0f, float(top_level));
    if (top_level == 0) return sample_bilinear(direction, 0);
    const float l0 = std::min(std::floor(clamped), float(top_level - 1));
    const float f = clamped - l0;
    const glm::vec3 a = sample_bilinear(direction, int(l0));
    const glm::vec3 b = sample_bilinear(direction, int(l0) + 1);
    return a + (b - a) * f;
}

glm::vec2 BrdfLut::sample(float u, float v) const {
    const float x = u * float(size_) - 0.5f, y = v * float(size_) - 0.5f;
    const float x0f = std::floor(x), y0f = std::floor(y);
    const float fx = x - x0f, fy = y - y0f;
    const float last = float(size_ - 1);
    const int x0 = int(clamp_nan_low(x0f, 0.0f, last)), x1 = int(clamp_nan_low(x0f + 1.0f, 0.0f, last));
    const int y0 = int(clamp_nan_low(y0f, 0.0f, last)), y1 = int(clamp_nan_low(y0f + 1.0f, 0.0f, last));
    const glm::vec2 top = texel(x0, y0) + (texel(x1, y0) - texel(x0, y0)) * fx;
    const glm::vec2 bottom = texel(x0, y1) + (texel(x1, y1) - texel(x0, y1)) * fx;
    return top + (bottom - top) * fy;
}

}  // namespace tessera::environment
