// Light culling (shade/light_culling.hpp) and the range cut of the kernels:
// culling never drops a light that reaches a fragment, down to the last bit at
// a range's edge, and every ISA draws that edge where the scalar reference does.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include "shade/light_culling.hpp"
#include "shade/pbr_reference.hpp"
#include "shade/shade_kernels.hpp"

namespace {

using namespace tessera;
using namespace tessera::shade;

constexpr std::array kIsas{Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512};

// Fragments in SoA form, padded_count(count) lanes of valid inputs.
struct Fragments {
    std::size_t count = 0;
    std::vector<float> world_x, world_y, world_z, normal_x, normal_y, normal_z;
    std::vector<float> albedo_r, albedo_g, albedo_b, metallic, roughness, ao;

    void add(const glm::vec3& p, const glm::vec3& n, const Material& m) {
        world_x.push_back(p.x), world_y.push_back(p.y), world_z.push_back(p.z);
        normal_x.push_back(n.x), normal_y.push_back(n.y), normal_z.push_back(n.z);
        albedo_r.push_back(m.albedo.r), albedo_g.push_back(m.albedo.g), albedo_b.push_back(m.albedo.b);
        metallic.push_back(m.metallic), roughness.push_back(m.roughness), ao.push_back(m.ao);
    }
    // Fixes the count and pads with copies of the last fragment, as FragmentBuffer does.
    void finish() {
        count = world_x.size();
        for (std::vector<float>* c : {&world_x, &world_y, &world_z, &normal_x, &normal_y, &normal_z, &albedo_r,
                                      &albedo_g, &albedo_b, &metallic, &roughness, &ao})
            c->resize(padded_count(count), c->back());
    }
    FragmentInputs inputs() const {
        return {count,           world_x.data(),  world_y.data(),  world_z.data(),  normal_x.data(),
                normal_y.data(), normal_z.data(), albedo_r.data(), albedo_g.data(), albedo_b.data(),
                metallic.data(), roughness.data(), ao.data()};
    }
    glm::vec3 world_pos(std::size_t i) const { return {world_x[i], world_y[i], world_z[i]}; }
};

struct Radiance {
    std::vector<float> r, g, b;
    explicit Radiance(std::size_t count) : r(padded_count(count)), g(padded_count(count)), b(padded_count(count)) {}
    RadianceOutputs outputs() { return {r.data(), g.data(), b.data()}; }
    glm::vec3 at(std::size_t i) const { return {r[i], g[i], b[i]}; }
};

bool same_bits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

float uniform(std::mt19937& rng, float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }
glm::vec3 uniform3(std::mt19937& rng, float lo, float hi) {
    return {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
}

const Material kMatte{.albedo = glm::vec3(0.8f, 0.5f, 0.3f), .metallic = 0.0f, .roughness = 0.5f, .ao = 1.0f};

// A point on the sphere of radius `range` around `centre`, in direction `dir`,
// nudged by `ulps` floats along each axis (rounding puts it on either side).
glm::vec3 on_sphere(const glm::vec3& centre, const glm::vec3& dir, float range, int ulps) {
    glm::vec3 p = centre + glm::normalize(dir) * range;
    for (int k = 0; k < 3; ++k)
        for (int u = 0; u < std::abs(ulps); ++u) p[k] = std::nextafter(p[k], ulps > 0 ? INFINITY : -INFINITY);
    return p;
}

}  // namespace

TEST_CASE("select_reaching keeps the lights whose range sphere meets the bounds") {
    // Bounds: the unit cube [0, 1]³.
    const WorldBounds bounds{glm::vec3(0.0f), glm::vec3(1.0f)};
    std::vector<Light> lights;
    const auto add = [&](LightType type, glm::vec3 position, float range) {
        Light light;
        light.type = type;
        light.position = position;
        light.range = range;
        light.color = glm::vec3(float(lights.size()));  // identifies the light
        lights.push_back(light);
    };
    add(LightType::point, {3.0f, 0.5f, 0.5f}, 2.5f);        // 0: 2 from the face: kept
    add(LightType::point, {3.0f, 0.5f, 0.5f}, 1.5f);        // 1: out of reach
    add(LightType::point, {2.0f, 2.0f, 2.0f}, 1.8f);        // 2: corner at √3 = 1.73: kept
    add(LightType::point, {2.0f, 2.0f, 2.0f}, 1.7f);        // 3: just short of the corner
    add(LightType::point, {0.5f, 0.5f, 0.5f}, 0.1f);        // 4: inside the bounds: kept
    add(LightType::point, {50.0f, 0.0f, 0.0f}, 0.0f);       // 5: no range, never culled
    add(LightType::spot, {0.5f, -3.0f, 0.5f}, 2.0f);        // 6: out of reach
    add(LightType::spot, {0.5f, -3.0f, 0.5f}, 3.5f);        // 7: kept
    add(LightType::point, {3.0f, 0.5f, 0.5f}, 2.0f);        // 8: exactly touching the face: kept
    add(LightType::directional, {99.0f, 0.0f, 0.0f}, 0.0f);  // 9: never culled
    ShadingLights all;
    all.assign(glm::vec3(0.0f), lights);
    CHECK(all.any_range);
    LightSelection every, kept;
    every.assign_all(all);
    CHECK(every.count() == all.count());
    select_reaching(all, every, bounds, kept);
    std::vector<float> ids;
    for (std::uint32_t entry : kept.index) ids.push_back(all.color_r[entry & kLightIndexMask]);
    const auto reaches_all = [&](const LightSelection& s) {
        std::vector<bool> flags;
        for (std::uint32_t entry : s.index) flags.push_back((entry & kReachesAll) != 0);
        return flags;
    };
    // Only the lights without a range reach all of the cube: light 4 is inside, but only 0.1 far.
    CHECK(reaches_all(kept) == std::vector<bool>{false, false, false, true, false, false, true});
    // Type groups first (points, spots, directionals), scene order within them.
    CHECK(ids == std::vector<float>{0.0f, 2.0f, 4.0f, 5.0f, 8.0f, 7.0f, 9.0f});
    CHECK(kept.spot_begin == 5);
    CHECK(kept.directional_begin == 6);

    // A selection narrows further: from `kept`, the box [0.45, 0.55]³ is 2.45 from
    // lights 0 (range 2.5: kept), 8 (2: dropped) and 2.45·√3 from light 2 (1.8: dropped).
    LightSelection fewer;
    select_reaching(all, kept, WorldBounds{glm::vec3(0.45f), glm::vec3(0.55f)}, fewer);
    ids.clear();
    for (std::uint32_t entry : fewer.index) ids.push_back(all.color_r[entry & kLightIndexMask]);
    CHECK(ids == std::vector<float>{0.0f, 4.0f, 5.0f, 7.0f, 9.0f});
    // Light 4 reaches all of this box (its far corner is 0.05·√3 = 0.087 away), lights 0 and 7 only part.
    CHECK(reaches_all(fewer) == std::vector<bool>{false, true, true, false, true});
    CHECK(fewer.spot_begin == 3);
    CHECK(fewer.directional_begin == 4);

    // A culled-away group still gets its boundaries: nothing but the unlimited lights.
    const WorldBounds far_away{glm::vec3(-100.0f), glm::vec3(-99.0f)};
    select_reaching(all, every, far_away, kept);
    CHECK(kept.count() == 2);  // the point light without range and the directional light
    CHECK(kept.spot_begin == 1);
    CHECK(kept.directional_begin == 1);
}

TEST_CASE("fragment_bounds") {
    const std::vector<float> x{1.0f, -2.0f, 3.0f}, y{0.5f, 0.25f, -4.0f}, z{7.0f, 8.0f, 9.0f};
    FragmentInputs in;
    in.count = 3;
    in.world_x = x.data(), in.world_y = y.data(), in.world_z = z.data();
    const WorldBounds b = fragment_bounds(in);
    CHECK(b.min == glm::vec3(-2.0f, -4.0f, 7.0f));
    CHECK(b.max == glm::vec3(3.0f, 0.5f, 9.0f));
}

TEST_CASE("fragment_bounds equals glm's one-by-one fold for every count, NaNs after the first passed over") {
    // The fold the bounds are defined by: glm::min/max from the first point on.
    std::mt19937 rng(77);
    for (std::size_t count = 1; count <= 70; ++count) {
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<float> axes[3];
            for (auto& axis : axes) {
                for (std::size_t i = 0; i < count; ++i) axis.push_back(uniform(rng, -100.0f, 100.0f));
                if (count > 1 && trial % 4 == 1) {  // a NaN somewhere after the first
                    axis[std::uniform_int_distribution<std::size_t>(1, count - 1)(rng)] = NAN;
                }
                if (trial % 4 == 2) axis[count - 1] = -1000.0f;  // the extreme in the scalar tail
            }
            FragmentInputs in;
            in.count = count;
            in.world_x = axes[0].data(), in.world_y = axes[1].data(), in.world_z = axes[2].data();
            glm::vec3 min(axes[0][0], axes[1][0], axes[2][0]), max = min;
            for (std::size_t i = 1; i < count; ++i) {
                const glm::vec3 p(axes[0][i], axes[1][i], axes[2][i]);
                min = glm::min(min, p), max = glm::max(max, p);
            }
            const WorldBounds b = fragment_bounds(in);
            CAPTURE(count);
            CHECK(b.min == min);
            CHECK(b.max == max);
        }
    }
}

TEST_CASE("select_reaching never drops a light that reaches a point of the box, nor marks one that misses one") {
    // Boxes around random points; lights whose range sphere passes through (or
    // within an ulp or two of) one of the points, seen from every side: the
    // rounding of the box test must never fall on the wrong side of the
    // rounding of the per-point test.
    std::mt19937 rng(1301);
    std::size_t reached = 0, dropped = 0, flagged = 0, wrongly_flagged = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        std::vector<glm::vec3> points(std::uniform_int_distribution<int>(1, 6)(rng));
        const glm::vec3 centre = uniform3(rng, -50.0f, 50.0f);
        const float extent = std::pow(10.0f, uniform(rng, -3.0f, 1.0f));
        for (glm::vec3& p : points) p = centre + uniform3(rng, -extent, extent);
        WorldBounds box{points[0], points[0]};
        for (const glm::vec3& p : points) box.min = glm::min(box.min, p), box.max = glm::max(box.max, p);

        std::vector<Light> lights;
        for (int j = 0; j < 8; ++j) {
            Light light;
            light.position = centre + uniform3(rng, -3.0f * extent - 20.0f, 3.0f * extent + 20.0f);
            const glm::vec3& target = points[std::uniform_int_distribution<std::size_t>(0, points.size() - 1)(rng)];
            light.range = std::sqrt(distance_squared(light.position, target));
            const int ulps = std::uniform_int_distribution<int>(-2, 2)(rng);
            for (int u = 0; u < std::abs(ulps); ++u) light.range = std::nextafter(light.range, ulps > 0 ? INFINITY : 0.0f);
            if (j % 4 == 3) light.type = LightType::spot;
            lights.push_back(light);
        }
        ShadingLights all;
        all.assign(glm::vec3(0.0f), lights);
        LightSelection every, kept;
        every.assign_all(all);
        select_reaching(all, every, box, kept);
        for (std::size_t j = 0; j < all.count(); ++j) {
            const auto entry = std::find_if(kept.index.begin(), kept.index.end(),
                                            [&](std::uint32_t e) { return (e & kLightIndexMask) == j; });
            const bool selected = entry != kept.index.end();
            const auto reaches = [&](const glm::vec3& p) { return light_reaches(all.records[j], p); };
            const bool reaches_any = std::any_of(points.begin(), points.end(), reaches);
            if (reaches_any) ++reached;
            if (reaches_any && !selected) ++dropped;
            // kReachesAll promises every point: the kernels then test no lane.
            if (selected && (*entry & kReachesAll)) {
                ++flagged;
                if (!std::all_of(points.begin(), points.end(), reaches)) ++wrongly_flagged;
            }
        }
    }
    CAPTURE(reached);
    CHECK(reached > 10000);  // the edge cases were really there
    CHECK(dropped == 0);
    CAPTURE(flagged);
    CHECK(flagged > 1000);
    CHECK(wrongly_flagged == 0);
}

TEST_CASE("the range cut: scalar is shade_pbr_within_range, and every ISA cuts the same lanes") {
    // One bright point light that every fragment faces; fragments on its range
    // sphere, nudged to either side by rounding. A lane the light does not
    // reach shows the ambient term alone, bit for bit what the same ISA gives
    // without any light; a lane it reaches is far brighter.
    std::mt19937 rng(77);
    Light light;
    light.position = glm::vec3(1.5f, -2.25f, 0.75f);
    light.color = glm::vec3(50.0f);
    light.range = 7.3f;
    Fragments f;
    std::size_t inside = 0;
    for (int i = 0; i < 301; ++i) {
        const glm::vec3 dir = uniform3(rng, -1.0f, 1.0f) + glm::vec3(0.0f, 0.0f, 1e-3f);
        const glm::vec3 p = on_sphere(light.position, dir, light.range, std::uniform_int_distribution<int>(-2, 2)(rng));
        f.add(p, light.position - p, kMatte);  // normal towards the light
        inside += light_reaches(light, p);
    }
    f.finish();
    CAPTURE(inside);
    REQUIRE(inside > 30);
    REQUIRE(inside < 270);  // both sides of the edge

    const glm::vec3 cam_pos = light.position;  // seen from the light: every lit fragment is bright
    ShadingLights lights, none;
    lights.assign(cam_pos, std::vector<Light>{light});
    none.assign(cam_pos, std::vector<Light>{});
    LightSelection every;
    every.assign_all(lights);
    for (Isa isa : kIsas) {
        if (!isa_supported(isa)) continue;
        CAPTURE(isa_name(isa));
        Radiance cut(f.count), ambient(f.count);
        shade_fragments_in_range(isa, f.inputs(), lights, every, cut.outputs());
        shade_fragments(isa, f.inputs(), none, ambient.outputs());
        std::size_t wrong_side = 0, not_reference = 0;
        for (std::size_t i = 0; i < f.count; ++i) {
            const bool reaches = light_reaches(light, f.world_pos(i));
            const bool unlit = same_bits(cut.at(i), ambient.at(i));
            if (reaches == unlit) ++wrong_side;
            if (reaches && !(cut.at(i).r > 10.0f * ambient.at(i).r)) ++wrong_side;
            if (isa == Isa::scalar) {
                const glm::vec3 expected = shade_pbr_within_range(f.world_pos(i), glm::vec3(f.normal_x[i], f.normal_y[i], f.normal_z[i]),
                                                                  kMatte, cam_pos, std::vector<Light>{light});
                if (!same_bits(cut.at(i), expected)) ++not_reference;
            }
        }
        CHECK(wrong_side == 0);
        CHECK(not_reference == 0);
    }
}

TEST_CASE("shade_fragments_culled gives the bits of shading every light cut at its range") {
    // Tile-sized fragment sets (several clusters, a partial last one) on two
    // surfaces far apart in depth, lit by many short-range lights of every
    // type, some spots among them, with lights placed at cluster boxes' edges.
    std::mt19937 rng(4242);
    for (std::size_t count : {1u, 63u, 64u, 65u, 200u, 1024u}) {
        CAPTURE(count);
        Fragments f;
        for (std::size_t i = 0; i < count; ++i) {
            const bool near = (i / 32) % 3 != 2;  // rows of a tile that alternate between a near and a far surface
            const glm::vec3 p(float(i % 32) * 0.1f, float(i / 32) * 0.1f, near ? uniform(rng, 0.0f, 0.2f)
                                                                                 : uniform(rng, -9.0f, -8.0f));
            const Material m{.albedo = uniform3(rng, 0.1f, 1.0f), .metallic = uniform(rng, 0.0f, 1.0f),
                             .roughness = uniform(rng, 0.05f, 1.0f), .ao = 1.0f};
            f.add(p, glm::vec3(0.0f, 0.0f, 1.0f) + uniform3(rng, -0.3f, 0.3f), m);
        }
        f.finish();
        std::vector<Light> lights;
        for (int j = 0; j < 96; ++j) {
            Light light;
            light.position = uniform3(rng, -1.0f, 4.0f) + glm::vec3(0.0f, 0.0f, j % 2 ? -7.0f : 1.0f);
            light.color = uniform3(rng, 0.0f, 2.0f);
            light.range = uniform(rng, 0.3f, 3.0f);
            if (j % 8 == 0) {  // exactly reaching one fragment
                const glm::vec3 p = f.world_pos(std::uniform_int_distribution<std::size_t>(0, count - 1)(rng));
                light.range = std::sqrt(distance_squared(light.position, p));
            }
            if (j % 5 == 0) {
                light.type = LightType::spot;
                light.direction = glm::normalize(uniform3(rng, -1.0f, 1.0f));
                light.outer_cone_degrees = 70.0f;
            }
            if (j % 17 == 0) light.range = 0.0f;  // unlimited
            lights.push_back(light);
        }
        Light sun;
        sun.type = LightType::directional;
        sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.4f));
        sun.color = glm::vec3(0.5f);
        lights.push_back(sun);
        ShadingLights all;
        all.assign(glm::vec3(1.0f, 2.0f, 10.0f), lights);
        LightSelection every;
        every.assign_all(all);
        LightCullScratch scratch;
        scratch.reserve(all.count());
        for (Isa isa : kIsas) {
            if (!isa_supported(isa)) continue;
            CAPTURE(isa_name(isa));
            Radiance culled(count), reference(count);
            const CulledWork work = shade_fragments_culled(isa, f.inputs(), all, scratch, culled.outputs());
            shade_fragments_in_range(isa, f.inputs(), all, every, reference.outputs());
            std::size_t differ = 0;
            for (std::size_t i = 0; i < count; ++i) differ += !same_bits(culled.at(i), reference.at(i));
            CHECK(differ == 0);
            // Culling did cull, and (with more than one cluster) further than the tile's lights.
            CHECK(work.fragment_lights < all.count() * count);
            CHECK(work.fragment_lights <= work.tile_lights * count);
            if (count > 64) CHECK(work.fragment_lights < work.tile_lights * count);
        }
    }
}
