// The chapters' ShadowCalculation (shade/shadow_maps.hpp) on maps written by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "shade/shadow_maps.hpp"

namespace {

using namespace tessera;
using namespace tessera::shade;

// A directional map over x, y in [-1, 1], looking down −z from z = 1 to z = −1
// (window depth = (1 − z) / 2), of `size` texels, every texel at depth `depth`.
ShadowMap flat_directional_map(int size, float depth, int filter_radius = 1) {
    ShadowMap map;
    map.kind = ShadowMapKind::planar_depth;
    map.size = size, map.filter_radius = filter_radius;
    map.view_projection[0] = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.0f, 2.0f) *
                             glm::lookAt(glm::vec3(0, 0, 1), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
    map.to_light = {0, 0, 1};
    map.depth.assign(std::size_t(size) * size, depth);
    return map;
}

// The lights of a cube-kernel test: one light shadowed by `map` (the kernels
// read the light's position from the map), the camera at (0, 3, 8).
ShadingLights one_shadowed_light(const ShadowMap& map) {
    const std::vector<Light> light_list(1);
    ShadingLights lights;
    lights.assign({0.0f, 3.0f, 8.0f}, light_list);
    const ShadowMap* by_light[] = {&map};
    lights.assign_shadows(by_light);
    return lights;
}

// How many floats of `a` differ from `b`'s in their bits.
std::size_t different_bits(const std::vector<float>& a, const std::vector<float>& b) {
    std::size_t different = 0;
    for (std::size_t i = 0; i < a.size(); ++i) different += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
    return different;
}

const glm::vec3 kFacingLight{0, 0, 1};
const glm::vec3 kCamera{0, 0, 5};

}  // namespace

TEST_CASE("shadow map: a point behind the stored depth is in shadow, one in front of it lit") {
    const ShadowMap map = flat_directional_map(64, 0.25f);  // an occluder at z = 0.5
    CHECK(shadow_visibility(map, {0.1f, -0.2f, 0.0f}, kFacingLight, kCamera) == 0.0f);   // depth 0.5
    CHECK(shadow_visibility(map, {0.1f, -0.2f, 0.52f}, kFacingLight, kCamera) == 1.0f);  // at 0.24: lit
    // Within the bias (0.005 facing the light) of the occluder: lit, no acne.
    CHECK(shadow_visibility(map, {0.1f, -0.2f, 0.495f}, kFacingLight, kCamera) == 1.0f);
    // Beyond the far plane (projected depth > 1): lit, as the chapter keeps it.
    CHECK(shadow_visibility(map, {0.1f, -0.2f, -1.5f}, kFacingLight, kCamera) == 1.0f);
    // Outside the map: the border's depth 1, lit.
    CHECK(shadow_visibility(map, {3.0f, 0.0f, 0.0f}, kFacingLight, kCamera) == 1.0f);
    // NaN positions are lit, not undefined behaviour.
    CHECK(shadow_visibility(map, {NAN, 0.0f, 0.0f}, kFacingLight, kCamera) == 1.0f);
}

TEST_CASE("shadow map: the slope-scaled bias grows as the surface turns from the light") {
    // Depth 0.27 stored, point at depth 0.3: 0.03 behind. Facing the light the
    // bias is 0.005 (shadow); at N·L = 0.2 it is 0.05·0.8 = 0.04 (lit).
    const ShadowMap map = flat_directional_map(64, 0.27f);
    const glm::vec3 point{0.0f, 0.0f, 0.4f};  // window depth (1 − 0.4)/2 = 0.3
    CHECK(shadow_visibility(map, point, kFacingLight, kCamera) == 0.0f);
    const glm::vec3 grazing = glm::normalize(glm::vec3(std::sqrt(1.0f - 0.04f), 0.0f, 0.2f));
    CHECK(shadow_visibility(map, point, grazing, kCamera) == 1.0f);
}

TEST_CASE("shadow map: 3x3 PCF gives thirds across an occluder's edge") {
    // Columns 32 and up hold an occluder (depth 0.1), the rest nothing (1).
    const int size = 64;
    ShadowMap map = flat_directional_map(size, 1.0f);
    for (int row = 0; row < size; ++row)
        for (int column = size / 2; column < size; ++column) map.depth[std::size_t(row) * size + column] = 0.1f;
    const auto at_column = [&](int column) {  // a point at the centre of that column, depth 0.5
        const float x = (float(column) + 0.5f) / float(size) * 2.0f - 1.0f;
        return shadow_visibility(map, {x, 0.01f, 0.0f}, kFacingLight, kCamera);
    };
    CHECK(at_column(20) == 1.0f);
    CHECK(at_column(30) == 1.0f);
    CHECK(at_column(31) == doctest::Approx(2.0f / 3.0f));  // its right neighbours are shadowed
    CHECK(at_column(32) == doctest::Approx(1.0f / 3.0f));
    CHECK(at_column(33) == 0.0f);
    // Radius 0: the single-sample test, a hard edge; radius 2: fifths.
    map.filter_radius = 0;
    CHECK(at_column(31) == 1.0f);
    CHECK(at_column(32) == 0.0f);
    map.filter_radius = 2;
    CHECK(at_column(30) == doctest::Approx(4.0f / 5.0f));
    CHECK(at_column(33) == doctest::Approx(1.0f / 5.0f));
}

TEST_CASE("shadow map: rows follow GL's t from the bottom of the picture") {
    const int size = 16;
    ShadowMap map = flat_directional_map(size, 1.0f, 0);
    map.depth[0] = 0.1f;  // row 0 (the top), column 0: the map's upper left corner, y = +1
    CHECK(shadow_visibility(map, {-0.95f, 0.95f, 0.0f}, kFacingLight, kCamera) == 0.0f);
    CHECK(shadow_visibility(map, {-0.95f, -0.95f, 0.0f}, kFacingLight, kCamera) == 1.0f);
}

TEST_CASE("cube shadow map: the point chapter's 20-sample disk") {
    ShadowMap map;
    map.kind = ShadowMapKind::cube_distance;
    map.size = 32, map.faces = 6, map.filter_radius = 1;
    map.position = {0, 0, 0};
    map.far_plane = 10.0f, map.disk_far_plane = 10.0f;
    map.depth.assign(6 * 32 * 32, 1.0f);
    // An occluder at distance 3 filling face +X (face 0).
    std::fill(map.depth.begin(), map.depth.begin() + 32 * 32, 0.3f);
    const glm::vec3 camera{0, 0, 0.5f};
    CHECK(shadow_visibility(map, {5.0f, 0.2f, -0.3f}, {-1, 0, 0}, camera) == 0.0f);  // behind it
    CHECK(shadow_visibility(map, {2.0f, 0.2f, -0.3f}, {-1, 0, 0}, camera) == 1.0f);  // in front of it
    CHECK(shadow_visibility(map, {-5.0f, 0.2f, -0.3f}, {1, 0, 0}, camera) == 1.0f);  // on the other side
    CHECK(shadow_visibility(map, {3.1f, 0.0f, 0.0f}, {-1, 0, 0}, camera) == 1.0f);   // within the 0.15 bias
    // At the face's edge (x = y) some of the disk's samples land on face +Y: a fraction.
    const float v = shadow_visibility(map, {5.0f, 5.0f, 0.0f}, {-1, 0, 0}, camera);
    CHECK(v > 0.0f);
    CHECK(v < 1.0f);
    CHECK(v * 20.0f == doctest::Approx(std::round(v * 20.0f)));  // in twentieths
    // Faces follow GL's table and the chapter's lookAt up vectors: −Z's camera
    // has up = −y, so its upper left texel (row 0, column 0) looks along (+x, −y, −z).
    std::fill(map.depth.begin(), map.depth.end(), 1.0f);
    map.filter_radius = 0;
    map.depth[std::size_t(5) * 32 * 32] = 0.1f;
    CHECK(shadow_visibility(map, {2.9f, -2.9f, -3.0f}, {0, 0, 1}, camera) == 0.0f);
    CHECK(shadow_visibility(map, {-2.9f, -2.9f, -3.0f}, {0, 0, 1}, camera) == 1.0f);
    CHECK(shadow_visibility(map, {2.9f, 2.9f, -3.0f}, {0, 0, 1}, camera) == 1.0f);
}

TEST_CASE("distance maps store distance / far_plane through each texel's centre") {
    ShadowMap map;
    map.kind = ShadowMapKind::cube_distance;
    map.size = 8, map.faces = 6;
    map.near_plane = 0.1f, map.far_plane = 20.0f, map.tan_half_fov = 1.0f;
    const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, map.near_plane, map.far_plane);
    // A surface at view depth 4 seen through texel (5, 2): window depth from the projection.
    const glm::vec4 clip = projection * glm::vec4(0.0f, 0.0f, -4.0f, 1.0f);
    const float window = clip.z / clip.w * 0.5f + 0.5f;
    const float ndc_x = (5.5f / 8.0f) * 2.0f - 1.0f, ndc_y = 1.0f - (2.5f / 8.0f) * 2.0f;
    const float expected = 4.0f * std::sqrt(1.0f + ndc_x * ndc_x + ndc_y * ndc_y) / 20.0f;
    CHECK(distance_from_window_depth(map, window, 5, 2) == doctest::Approx(expected).epsilon(1e-4));
}

TEST_CASE("cube shadow kernels: every ISA gives the scalar lookup's bits") {
    std::mt19937 rng(32);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), box(-6.0f, 6.0f);
    ShadowMap map;
    map.kind = ShadowMapKind::cube_distance;
    map.size = 37, map.faces = 6;
    map.position = {0.5f, -0.25f, 1.0f};
    map.far_plane = 9.0f, map.disk_far_plane = 30.0f;
    map.depth.resize(6 * 37 * 37);
    for (float& d : map.depth) d = unit(rng) < 0.1f ? 1.0f : 0.2f + 0.6f * unit(rng);  // blocky: some lit, some not
    const std::size_t count = 3001;
    std::vector<float> x(padded_count(count)), y(x.size()), z(x.size()), n(x.size(), 1.0f);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = box(rng), y[i] = box(rng), z[i] = box(rng);
    x[5] = map.position.x, y[5] = map.position.y, z[5] = map.position.z;  // at the light: no direction
    x[6] = NAN;
    x[7] = map.position.x + 2.0f, y[7] = map.position.y + 2.0f, z[7] = map.position.z;  // on a face edge
    const ShadingLights lights = one_shadowed_light(map);
    const FragmentInputs in{count, x.data(), y.data(), z.data(), n.data(), n.data(), n.data()};
    for (const int radius : {0, 1, 3}) {
        map.filter_radius = radius;
        std::vector<float> reference(x.size(), -1.0f);
        shadow_visibility_planes(Isa::scalar, in, lights, reference.data(), x.size());
        std::size_t fractional = 0;
        for (std::size_t i = 0; i < count; ++i) fractional += reference[i] > 0.0f && reference[i] < 1.0f;
        if (radius > 0) CHECK(fractional > 100);
        for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
            if (!isa_supported(isa)) continue;
            CAPTURE(isa_name(isa));
            CAPTURE(radius);
            std::vector<float> out(x.size(), -1.0f);
            shadow_visibility_planes(isa, in, lights, out.data(), x.size());
            CHECK(different_bits(out, reference) == 0);
        }
    }
}

TEST_CASE("cube shadow kernels: the block summaries and the fragments facing away skip taps, not bits") {
    // A room 5 units from the light on every side (distance / far = 0.5) and a
    // square occluder 2 units away in the middle of each face; fragments on a
    // sphere 4.9 units out, face by face in rows as a tile would list them:
    // lit, shadowed, and partly shadowed near the occluders' edges.
    ShadowMap map;
    map.kind = ShadowMapKind::cube_distance;
    map.size = 128, map.faces = 6, map.filter_radius = 1;
    map.position = {0.25f, -0.5f, 0.75f};
    map.far_plane = 10.0f, map.disk_far_plane = 30.0f;
    map.depth.assign(6 * 128 * 128, 0.5f);
    for (int face = 0; face < 6; ++face)
        for (int row = 40; row < 88; ++row)
            for (int column = 40 + 4 * face; column < 88; ++column)
                map.depth[(std::size_t(face) * 128 + std::size_t(row)) * 128 + std::size_t(column)] = 0.2f;
    map.depth[(std::size_t(2) * 128 + 10) * 128 + 10] = NAN;  // a NaN texel settles nothing near it
    summarize_cube_blocks(map);
    REQUIRE(map.blocks_per_side == 128 / kShadowBlock);

    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<float> x, y, z, nx, ny, nz;
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < 96; ++j)
            for (int i = 0; i < 96; ++i) {
                const float s = (float(i) + 0.5f) / 48.0f - 1.0f, t = (float(j) + 0.5f) / 48.0f - 1.0f;
                const glm::vec3 axes[6] = {{1, -t, -s}, {-1, -t, s}, {s, 1, t}, {s, -1, -t}, {s, -t, 1}, {-s, -t, -1}};
                const glm::vec3 p = map.position + glm::normalize(axes[face]) * 4.9f;
                x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
                nx.push_back(unit(rng)), ny.push_back(unit(rng)), nz.push_back(unit(rng));
            }
    const std::size_t count = x.size();
    for (std::vector<float>* v : {&x, &y, &z, &nx, &ny, &nz}) v->resize(padded_count(count), 0.0f);
    const ShadingLights lights = one_shadowed_light(map);
    const FragmentInputs in{count, x.data(), y.data(), z.data(), nx.data(), ny.data(), nz.data()};
    for (const int radius : {1, 2}) {
        map.filter_radius = radius;
        std::vector<float> reference(x.size(), -1.0f);
        shadow_visibility_planes(Isa::scalar, in, lights, reference.data(), x.size());
        std::size_t lit = 0, dark = 0;
        for (std::size_t i = 0; i < count; ++i) lit += reference[i] == 1.0f, dark += reference[i] == 0.0f;
        CHECK(lit > count / 4);
        CHECK(dark > count / 20);
        CHECK(count - lit - dark > count / 50);  // partly shadowed
        for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
            if (!isa_supported(isa)) continue;
            CAPTURE(isa_name(isa));
            CAPTURE(radius);
            // Every visibility asked for: the summaries settle most, the bits are the taps'.
            std::vector<float> out(x.size(), -1.0f);
            const CubeLookupStats every = shadow_visibility_planes(isa, in, lights, out.data(), x.size());
            CHECK(different_bits(out, reference) == 0);
            CHECK(every.settled + every.tapped == count);
            CHECK(every.facing_away == 0);
            CHECK(every.settled > count / 2);
            CHECK(every.tapped > count / 50);
            // The picture only: a fragment facing away from the light may hold
            // another value, in [0, 1]; every other one the taps' bits.
            std::fill(out.begin(), out.end(), -1.0f);
            const CubeLookupStats picture = shadow_visibility_planes(isa, in, lights, out.data(), x.size(), false);
            CHECK(picture.settled + picture.tapped + picture.facing_away == count);
            CHECK(picture.facing_away > count / 3);
            std::size_t wrong = 0;
            for (std::size_t i = 0; i < count; ++i) {
                if (std::memcmp(&out[i], &reference[i], sizeof(float)) == 0) continue;
                const glm::vec3 to_light = map.position - glm::vec3(x[i], y[i], z[i]);
                const bool away = glm::dot(glm::vec3(nx[i], ny[i], nz[i]), to_light) < 0.0f;
                wrong += !(away && out[i] >= 0.0f && out[i] <= 1.0f);
            }
            CHECK(wrong == 0);
        }
    }
    // Summaries of another depth than the map's would be wrong, so a map
    // without them (a test's, a caller's) takes every tap.
    map.block_min.clear();
    std::vector<float> out(x.size());
    CHECK(shadow_visibility_planes(simd::best_supported_isa(), in, lights, out.data(), x.size()).settled == 0);
}
