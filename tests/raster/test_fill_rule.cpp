#include <doctest/doctest.h>

#include <cmath>

#include "raster/raster_limits.hpp"
#include "raster_test_util.hpp"

using namespace tessera;
using test::coverage;
using test::screen_triangle;

namespace {

constexpr int kSize = 64;

// Sign of the exact edge function at pixel (i, j)'s centre for a polygon
// corner list given in screen positions that are exact in 24.8 fixed point.
std::int64_t edge_at_centre(glm::vec2 a, glm::vec2 b, int i, int j) {
    const auto f = [](float v) { return std::int64_t(std::lrint(v * raster::kSubpixelScale)); };
    const std::int64_t px = std::int64_t(i) * raster::kSubpixelScale + raster::kSubpixelScale / 2;
    const std::int64_t py = std::int64_t(j) * raster::kSubpixelScale + raster::kSubpixelScale / 2;
    return raster::edge_function(f(a.x), f(a.y), f(b.x), f(b.y), px, py);
}

// -1 strictly outside, 0 on the boundary, 1 strictly inside a convex polygon
// (either winding) whose corners are exact in 24.8 fixed point.
int classify_centre(const std::vector<glm::vec2>& polygon, int i, int j) {
    int positive = 0, negative = 0;
    for (std::size_t k = 0; k < polygon.size(); ++k) {
        const std::int64_t e = edge_at_centre(polygon[k], polygon[(k + 1) % polygon.size()], i, j);
        positive += e > 0;
        negative += e < 0;
    }
    const int n = int(polygon.size());
    if (positive == n || negative == n) return 1;
    if (positive > 0 && negative > 0) return -1;
    return 0;
}

void add(std::vector<int>& total, const std::vector<int>& part) {
    for (std::size_t i = 0; i < total.size(); ++i) total[i] += part[i];
}

}  // namespace

TEST_CASE("two triangles sharing an edge cover every pixel centre exactly once") {
    // The shared diagonal runs through pixel centres (x.5, x.5): every one of
    // them is a tie that only the fill rule decides.
    const glm::vec2 a{2.5f, 2.5f}, b{61.25f, 3.0f}, c{60.5f, 60.5f}, d{1.75f, 58.0f};
    std::vector<int> total(kSize * kSize, 0);
    add(total, coverage(screen_triangle(a, b, c, kSize), kSize));
    add(total, coverage(screen_triangle(c, d, a, kSize), kSize));  // opposite winding on screen

    const std::vector<glm::vec2> quad{a, b, c, d};
    int inside = 0, diagonal_hits = 0;
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const int n = total[j * kSize + i];
            CHECK_MESSAGE(n <= 1, "pixel " << i << "," << j << " covered " << n << " times");
            const int where = classify_centre(quad, i, j);
            if (where > 0) {
                ++inside;
                CHECK_MESSAGE(n == 1, "interior pixel " << i << "," << j << " covered " << n << " times");
            }
            if (where < 0) CHECK(n == 0);
            if (i == j && i >= 3 && i <= 59) {
                ++diagonal_hits;
                CHECK_MESSAGE(n == 1, "diagonal pixel " << i << " covered " << n << " times");
            }
        }
    CHECK(inside > 3000);
    CHECK(diagonal_hits == 57);
}

TEST_CASE("a fan of triangles around one vertex covers every pixel centre exactly once") {
    // The shared vertex sits exactly on a pixel centre, as do several rim corners.
    const glm::vec2 centre{32.5f, 32.5f};
    // A convex rim, every corner on a pixel centre, with edges at 0°, 45° and 90°
    // so that many centres lie exactly on the spokes.
    const std::vector<glm::vec2> rim{{52.5f, 32.5f}, {46.5f, 46.5f}, {32.5f, 52.5f}, {18.5f, 46.5f},
                                     {12.5f, 32.5f}, {18.5f, 18.5f}, {32.5f, 12.5f}, {46.5f, 18.5f}};
    const int kSpokes = int(rim.size());
    std::vector<int> total(kSize * kSize, 0);
    for (int k = 0; k < kSpokes; ++k) {
        const glm::vec2 p = rim[k], q = rim[(k + 1) % kSpokes];
        add(total, coverage(k % 2 ? screen_triangle(centre, p, q, kSize) : screen_triangle(q, p, centre, kSize), kSize));
    }
    CHECK(total[32 * kSize + 32] == 1);  // the pixel at the shared vertex
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const int n = total[j * kSize + i];
            CHECK_MESSAGE(n <= 1, "pixel " << i << "," << j << " covered " << n << " times");
            const int where = classify_centre(rim, i, j);
            if (where > 0) CHECK_MESSAGE(n == 1, "interior pixel " << i << "," << j << " covered " << n << " times");
            if (where < 0) CHECK(n == 0);
        }
}

TEST_CASE("top-left rule: a centre on a top or left edge is covered, on a bottom or right edge it is not") {
    // Axis-aligned right triangle with corners on pixel centres.
    // Edges: top (y = 10.5, interior below), left (x = 10.5), and the hypotenuse (bottom-right).
    const auto covered = coverage(screen_triangle({10.5f, 10.5f}, {20.5f, 10.5f}, {10.5f, 20.5f}, kSize), kSize);
    CHECK(covered[10 * kSize + 15] == 1);  // on the top edge
    CHECK(covered[15 * kSize + 10] == 1);  // on the left edge
    CHECK(covered[15 * kSize + 15] == 0);  // on the hypotenuse, a right/bottom edge
    CHECK(covered[14 * kSize + 14] == 1);  // inside
    // The mirrored triangle: its vertical edge is a right edge, its horizontal edge a bottom edge.
    const auto mirrored = coverage(screen_triangle({20.5f, 20.5f}, {10.5f, 20.5f}, {20.5f, 10.5f}, kSize), kSize);
    CHECK(mirrored[20 * kSize + 15] == 0);  // on the bottom edge
    CHECK(mirrored[15 * kSize + 20] == 0);  // on the right edge
    CHECK(mirrored[15 * kSize + 15] == 1);  // on the hypotenuse, now a top-left edge
}

TEST_CASE("triangles covering no pixel centre are dropped at setup") {
    CHECK_FALSE(screen_triangle({10.1f, 10.1f}, {10.4f, 10.1f}, {10.1f, 10.4f}, kSize));  // no centre in its box
    CHECK_FALSE(screen_triangle({5, 5}, {10, 10}, {15, 15}, kSize));                     // no area
    // The centre (10.5, 10.5) lies exactly on the hypotenuse, a bottom-right edge: not covered.
    CHECK_FALSE(screen_triangle({10.1f, 10.1f}, {10.9f, 10.1f}, {10.1f, 10.9f}, kSize));
    CHECK(screen_triangle({10.1f, 10.1f}, {11.0f, 10.1f}, {10.1f, 11.0f}, kSize));
}
