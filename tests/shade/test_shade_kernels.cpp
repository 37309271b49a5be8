// The vectorized fragment stage against the scalar reference, for every ISA
// this CPU runs, over random fragments, lights and cameras.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "shade/pbr_reference.hpp"
#include "shade/shade_kernels.hpp"
#include "shade/surface_gather.hpp"

namespace {

using namespace tessera;
using namespace tessera::shade;

constexpr std::array kSimdIsas{Isa::sse4, Isa::avx2, Isa::avx512};
constexpr std::size_t kSentinelLanes = 16;      // checked after the padded end
constexpr float kSentinel = -1234.5f;

// HDR bound, per channel:
//   |simd − scalar| <= kRelTolerance·|scalar| + kAbsTolerance + Σ_lights conditioning_allowance
// The shader is well conditioned except in a few corners where it amplifies the
// float rounding of the four dot products it takes of unit vectors (N·V, N·L,
// N·H, H·V, each good to a few ulps of 1 however it is computed): the GGX
// denominator N·H²·(a² − 1) + 1 cancels down to a² (6e-6 at roughness 0.05) at
// the highlight; a grazing view (N·V → 0) or light (N·L → 0, and the clamps at
// 0) turns that absolute error into a large relative one. The reference has the
// same errors in other bits, so there the two can only agree as well as the
// formula lets them. conditioning_allowance is the change in the light's
// contribution, in double, when each dot product moves by kDotProductError; it
// is negligible (< 1e-6 relative) away from those corners. N·H and H·V move
// kDotProductError/|V + L| where |V + L| < 1 (the light behind the surface as
// seen from the camera): H = normalize(V + L) there divides the few-ulp
// rounding of V and L by a short sum, so the reference's own H is off by that
// much, and a kernel that rounds L differently (the SIMD kernels' 1/distance is
// refined from the hardware estimate, not divided) lands elsewhere within it.
constexpr double kRelTolerance = 1e-4;
constexpr double kAbsTolerance = 1e-6;
constexpr double kDotProductError = 8.0 / (1 << 24);  // 8 half-ulps of 1
// Display bound after Reinhard + gamma: one 8-bit step.
constexpr double kDisplayTolerance = 1.0 / 255.0;

// Random fragments in SoA form, generated for padded_count(count) lanes so the
// lanes past count hold valid inputs too.
struct Fragments {
    std::size_t count = 0;
    std::vector<float> world_x, world_y, world_z, normal_x, normal_y, normal_z;
    std::vector<float> albedo_r, albedo_g, albedo_b, metallic, roughness, ao;

    FragmentInputs inputs() const {
        return {count,           world_x.data(),  world_y.data(),  world_z.data(),  normal_x.data(),
                normal_y.data(), normal_z.data(), albedo_r.data(), albedo_g.data(), albedo_b.data(),
                metallic.data(), roughness.data(), ao.data()};
    }
    glm::vec3 world_pos(std::size_t i) const { return {world_x[i], world_y[i], world_z[i]}; }
    glm::vec3 normal(std::size_t i) const { return {normal_x[i], normal_y[i], normal_z[i]}; }
    Material material(std::size_t i) const {
        return {.albedo = glm::vec3(albedo_r[i], albedo_g[i], albedo_b[i]), .metallic = metallic[i], .roughness = roughness[i],
                .ao = ao[i]};
    }
};

// Output channels with kSentinelLanes of sentinels after the padded end.
struct Radiance {
    std::size_t count = 0;
    std::vector<float> r, g, b;
    explicit Radiance(std::size_t n)
        : count(n),
          r(padded_count(n) + kSentinelLanes, kSentinel),
          g(padded_count(n) + kSentinelLanes, kSentinel),
          b(padded_count(n) + kSentinelLanes, kSentinel) {}
    RadianceOutputs outputs() { return {r.data(), g.data(), b.data()}; }
    float channel(int c, std::size_t i) const { return c == 0 ? r[i] : c == 1 ? g[i] : b[i]; }
    bool sentinels_intact() const {
        for (std::size_t i = padded_count(count); i < r.size(); ++i)
            if (r[i] != kSentinel || g[i] != kSentinel || b[i] != kSentinel) return false;
        return true;
    }
};

struct RandomScene {
    glm::vec3 cam_pos;
    std::vector<Light> lights;
    Fragments fragments;
};

float uniform(std::mt19937& rng, float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }
glm::vec3 uniform3(std::mt19937& rng, float lo, float hi) {
    return {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
}
glm::vec3 unit_vector(std::mt19937& rng) {
    std::normal_distribution<float> gauss;
    for (;;) {
        const glm::vec3 v(gauss(rng), gauss(rng), gauss(rng));
        if (glm::length(v) > 1e-3f) return glm::normalize(v);
    }
}

// Fragments in a 16³ box, lights and camera in a 24³ box around it: light
// distances run from 0.5 (closer ones are rejected) to about 35. Lights are of
// every type, in random order; spot cones are at least 5° wide. With
// point_lights > 0: that many point lights and no other. Grey lights (the
// three colour channels equal) if `grey`.
RandomScene random_scene(std::mt19937& rng, std::size_t count, int point_lights = 0, bool grey = false) {
    RandomScene scene;
    scene.cam_pos = uniform3(rng, -12.0f, 12.0f);
    const int light_count = point_lights > 0 ? point_lights : std::uniform_int_distribution<int>(1, 8)(rng);
    for (int j = 0; j < light_count; ++j) {
        Light light{uniform3(rng, -12.0f, 12.0f), uniform3(rng, 0.0f, 300.0f)};
        const int type = point_lights > 0 ? 0 : std::uniform_int_distribution<int>(0, 2)(rng);
        if (type == 1) {
            light.type = LightType::directional;
            light.color = uniform3(rng, 0.0f, 3.0f);  // radiance itself, not radiance·distance²
            light.direction = unit_vector(rng);
        } else if (type == 2) {
            light.type = LightType::spot;
            light.direction = unit_vector(rng);
            light.inner_cone_degrees = uniform(rng, 0.0f, 60.0f);
            light.outer_cone_degrees = uniform(rng, light.inner_cone_degrees + 5.0f, 90.0f);
        }
        if (grey) light.color = glm::vec3(light.color.r);
        scene.lights.push_back(light);
    }

    Fragments& f = scene.fragments;
    f.count = count;
    for (std::size_t i = 0; i < padded_count(count); ++i) {
        glm::vec3 p;
        do {
            p = uniform3(rng, -8.0f, 8.0f);
        } while (glm::length(p - scene.cam_pos) < 0.5f ||
                 std::any_of(scene.lights.begin(), scene.lights.end(),
                             [&](const Light& l) {
                                 return l.type != LightType::directional && glm::length(p - l.position) < 0.5f;
                             }));
        // Unit normals scaled by 0.5..2: the shader must normalize.
        const glm::vec3 n = unit_vector(rng) * uniform(rng, 0.5f, 2.0f);
        f.world_x.push_back(p.x), f.world_y.push_back(p.y), f.world_z.push_back(p.z);
        f.normal_x.push_back(n.x), f.normal_y.push_back(n.y), f.normal_z.push_back(n.z);
        f.albedo_r.push_back(uniform(rng, 0.0f, 1.0f));
        f.albedo_g.push_back(uniform(rng, 0.0f, 1.0f));
        f.albedo_b.push_back(uniform(rng, 0.0f, 1.0f));
        f.metallic.push_back(uniform(rng, 0.0f, 1.0f));
        f.roughness.push_back(uniform(rng, 0.05f, 1.0f));
        f.ao.push_back(uniform(rng, 0.0f, 1.0f));
    }
    return scene;
}

// Counts for the random scenes: the awkward small ones first, then random sizes
// until there are at least min_total fragments.
std::vector<std::size_t> scene_sizes(std::mt19937& rng, std::size_t min_total) {
    std::vector<std::size_t> sizes{1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 31, 33, 47, 63, 65, 100, 257};
    std::size_t total = 0;
    for (std::size_t n : sizes) total += n;
    while (total < min_total) {
        const std::size_t n = std::uniform_int_distribution<std::size_t>(1, 5000)(rng);
        sizes.push_back(n);
        total += n;
    }
    return sizes;
}

Radiance shade_scene(Isa isa, const RandomScene& scene) {
    ShadingLights lights;
    lights.assign(scene.cam_pos, scene.lights);
    Radiance out(scene.fragments.count);
    shade_fragments(isa, scene.fragments.inputs(), lights, out.outputs());
    return out;
}

// The tonemap kernel applied to a copy.
Radiance display(Isa isa, const Radiance& hdr) {
    Radiance out = hdr;
    tonemap_gamma(isa, out.count, out.r.data(), out.g.data(), out.b.data());
    return out;
}

constexpr double kPiD = 3.14159265359;  // the GLSL's PI

// One light's contribution, the shader's loop body in double, from the raw
// (unclamped) dot products of unit vectors.
struct DotProducts {
    double n_dot_v, n_dot_l, n_dot_h, h_dot_v;
};
glm::dvec3 light_contribution(const DotProducts& d, const Material& m, const glm::dvec3& radiance) {
    const glm::dvec3 albedo(m.albedo);
    const double metallic = m.metallic;
    const double a2 = std::pow(double(m.roughness), 4.0);
    const double k = (m.roughness + 1.0) * (m.roughness + 1.0) / 8.0;
    const auto schlick_ggx = [k](double x) { return x / (x * (1.0 - k) + k); };
    const double n_dot_v = std::max(d.n_dot_v, 0.0), n_dot_l = std::max(d.n_dot_l, 0.0);
    const double n_dot_h = std::max(d.n_dot_h, 0.0), h_dot_v = std::max(d.h_dot_v, 0.0);
    const double denom = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    const double ndf = a2 / (kPiD * denom * denom);
    const double g = schlick_ggx(n_dot_l) * schlick_ggx(n_dot_v);
    const glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), albedo, metallic);
    const glm::dvec3 f = f0 + (1.0 - f0) * std::pow(std::clamp(1.0 - h_dot_v, 0.0, 1.0), 5.0);
    const glm::dvec3 k_d = (1.0 - f) * (1.0 - metallic);
    const glm::dvec3 specular = ndf * g * f / (4.0 * n_dot_v * n_dot_l + 0.0001);
    return (k_d * albedo / kPiD + specular) * radiance * n_dot_l;
}

// Σ over lights of the conditioning allowance above, per channel.
glm::dvec3 conditioning_allowance(const RandomScene& scene, std::size_t i) {
    const Fragments& f = scene.fragments;
    const Material m = f.material(i);
    const glm::dvec3 world_pos(f.world_pos(i));
    const glm::dvec3 n = glm::normalize(glm::dvec3(f.normal(i)));
    const glm::dvec3 v = glm::normalize(glm::dvec3(scene.cam_pos) - world_pos);
    glm::dvec3 allowance(0.0);
    for (const Light& light : scene.lights) {
        const glm::dvec3 to_light = glm::dvec3(light.position) - world_pos;
        const glm::dvec3 l =
            light.type == LightType::directional ? -glm::dvec3(light.direction) : glm::normalize(to_light);
        const glm::dvec3 h = glm::normalize(v + l);
        const double h_error_scale = 1.0 / std::min(1.0, glm::length(v + l));  // see kDotProductError
        glm::dvec3 radiance = glm::dvec3(light.color);
        if (light.type != LightType::directional) radiance /= glm::dot(to_light, to_light);
        const DotProducts exact{glm::dot(n, v), glm::dot(n, l), glm::dot(n, h), glm::dot(h, v)};
        if (light.type == LightType::spot) {
            // The cone ramp amplifies cos θ's rounding (a dot product of unit
            // vectors) by 1/(cos inner − cos outer).
            const double cos_theta = glm::dot(glm::dvec3(light.direction), -l);
            const double cos_inner = std::cos(glm::radians(double(light.inner_cone_degrees)));
            const double cos_outer = std::cos(glm::radians(double(light.outer_cone_degrees)));
            const auto factor = [&](double c) { return std::clamp((c - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0); };
            const glm::dvec3 unit = light_contribution(exact, m, radiance);
            const double spread = std::max(std::abs(factor(cos_theta + kDotProductError) - factor(cos_theta)),
                                           std::abs(factor(cos_theta - kDotProductError) - factor(cos_theta)));
            allowance += glm::abs(unit) * spread;
            radiance *= factor(cos_theta);
        }
        const glm::dvec3 base = light_contribution(exact, m, radiance);
        for (double DotProducts::*term : {&DotProducts::n_dot_v, &DotProducts::n_dot_l, &DotProducts::n_dot_h,
                                          &DotProducts::h_dot_v}) {
            glm::dvec3 worst(0.0);
            const bool of_h = term == &DotProducts::n_dot_h || term == &DotProducts::h_dot_v;
            for (double step : {-kDotProductError, kDotProductError}) {
                DotProducts moved = exact;
                moved.*term += of_h ? step * h_error_scale : step;
                worst = glm::max(worst, glm::abs(light_contribution(moved, m, radiance) - base));
            }
            allowance += worst;
        }
    }
    return allowance;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("ISA names and support") {
    CHECK(isa_name(Isa::scalar) == "scalar");
    CHECK(isa_name(Isa::sse4) == "sse4");
    CHECK(isa_name(Isa::avx2) == "avx2");
    CHECK(isa_name(Isa::avx512) == "avx512");
    CHECK(isa_supported(Isa::scalar));
    CHECK(isa_supported(best_supported_isa()));
    for (Isa isa : kSimdIsas)
        MESSAGE("ISA ", isa_name(isa), std::string(isa_supported(isa) ? " supported" : " NOT supported"));
    MESSAGE("best ISA: ", isa_name(best_supported_isa()));
    // Support is nested: a wider ISA implies the narrower ones.
    if (isa_supported(Isa::avx512)) CHECK(isa_supported(Isa::avx2));
    if (isa_supported(Isa::avx2)) CHECK(isa_supported(Isa::sse4));

    float value = 1.0f;
    const Isa bogus = static_cast<Isa>(99);
    CHECK_THROWS_AS(tonemap_gamma(bogus, 1, &value, &value, &value), std::invalid_argument);
    CHECK_THROWS_AS(shade_fragments(bogus, FragmentInputs{}, ShadingLights{}, RadianceOutputs{}),
                    std::invalid_argument);
    for (Isa isa : kSimdIsas)
        if (!isa_supported(isa)) CHECK_THROWS_AS(tonemap_gamma(isa, 1, &value, &value, &value), std::invalid_argument);
}

TEST_CASE("Isa::scalar is the reference shader, bit for bit") {
    std::mt19937 rng(7);
    for (std::size_t count : {1u, 13u, 16u, 200u}) {
        const RandomScene scene = random_scene(rng, count);
        const Radiance out = shade_scene(Isa::scalar, scene);
        const Radiance shown = display(Isa::scalar, out);
        const Fragments& f = scene.fragments;
        bool equal = true;
        // ShadingLights groups the lights by type (points, spots, directionals), and the sum follows that order.
        std::vector<Light> grouped;
        for (LightType type : {LightType::point, LightType::spot, LightType::directional})
            for (const Light& light : scene.lights)
                if (light.type == type) grouped.push_back(light);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::vec3 expected =
                shade_pbr(f.world_pos(i), f.normal(i), f.material(i), scene.cam_pos, grouped);
            const glm::vec3 expected_display = display_from_radiance(expected);
            for (int c = 0; c < 3; ++c)
                equal = equal && same_bits(out.channel(c, i), expected[c]) &&
                        same_bits(shown.channel(c, i), expected_display[c]);
        }
        CAPTURE(count);
        CHECK(equal);
        // The scalar path writes exactly count lanes.
        for (std::size_t i = count; i < out.r.size(); ++i) CHECK(out.r[i] == kSentinel);
    }
}

TEST_CASE("SIMD shader matches the scalar reference on random fragments") {
    std::mt19937 rng(20240611);
    const std::vector<std::size_t> sizes = scene_sizes(rng, 120000);
    std::vector<RandomScene> scenes;
    for (std::size_t n : sizes) scenes.push_back(random_scene(rng, n));
    std::vector<Radiance> reference, reference_display;
    std::vector<std::vector<glm::dvec3>> allowance;
    for (const RandomScene& scene : scenes) {
        reference.push_back(shade_scene(Isa::scalar, scene));
        reference_display.push_back(display(Isa::scalar, reference.back()));
        allowance.emplace_back();
        for (std::size_t i = 0; i < scene.fragments.count; ++i)
            allowance.back().push_back(conditioning_allowance(scene, i));
    }
    std::size_t total = 0;
    for (std::size_t n : sizes) total += n;
    MESSAGE(total, " fragments in ", scenes.size(), " scenes, HDR bound |simd - scalar| <= ", kRelTolerance,
            "*|scalar| + ", kAbsTolerance, " + conditioning allowance, display bound ", kDisplayTolerance);

    for (Isa isa : kSimdIsas) {
        if (!isa_supported(isa)) {
            MESSAGE("skipping ", isa_name(isa), ": not supported by this CPU");
            continue;
        }
        CAPTURE(isa_name(isa));
        double worst_ratio = 0.0, worst_display = 0.0;  // ratio: error / allowed error
        double worst_plain_ratio = 0.0;                 // the same without the conditioning allowance
        std::size_t failures = 0, sentinel_failures = 0, needed_allowance = 0;
        std::string worst_case;
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            const Radiance out = shade_scene(isa, scenes[s]);
            const Radiance shown = display(isa, out);
            if (!out.sentinels_intact() || !shown.sentinels_intact()) ++sentinel_failures;
            for (std::size_t i = 0; i < out.count; ++i) {
                for (int c = 0; c < 3; ++c) {
                    const double expected = reference[s].channel(c, i), actual = out.channel(c, i);
                    const double plain_bound = kRelTolerance * std::abs(expected) + kAbsTolerance;
                    const double error = std::abs(actual - expected);
                    const double ratio = error / (plain_bound + allowance[s][i][c]);
                    worst_plain_ratio = std::max(worst_plain_ratio, error / plain_bound);
                    if (error > plain_bound) ++needed_allowance;
                    const double display_error =
                        std::abs(double(shown.channel(c, i)) - reference_display[s].channel(c, i));
                    if (!(ratio <= 1.0) || !(display_error <= kDisplayTolerance)) ++failures;
                    if (!(ratio <= worst_ratio)) {
                        worst_ratio = ratio;
                        const Fragments& f = scenes[s].fragments;
                        worst_case = "scene " + std::to_string(s) + " fragment " + std::to_string(i) + " channel " +
                                     std::to_string(c) + ": scalar " + std::to_string(expected) + " simd " +
                                     std::to_string(actual) + " roughness " + std::to_string(f.roughness[i]);
                    }
                    worst_display = std::max(worst_display, display_error);
                }
            }
        }
        MESSAGE(isa_name(isa), ": worst HDR error ", worst_ratio, " of the bound (", worst_case, "); ",
                needed_allowance, " channel values needed the conditioning allowance, worst ", worst_plain_ratio,
                " of the plain bound; worst display error ", worst_display * 255.0, "/255");
        CHECK(failures == 0);
        CHECK(sentinel_failures == 0);
    }
}

// shade_fragment_runs as the renderer calls it after the fast gather: the
// material channels of plain runs hold garbage (NaN) except where
// fill_plain_run_edges fills them; the result must be shade_fragments' with
// every channel filled, bit for bit, for every ISA.
// The check of the test case below over scenes of count fragments from
// random_scene(rng, count, point_lights, grey); returns the fragments checked per ISA in plain runs.
std::size_t check_plain_runs(std::mt19937& rng, std::size_t min_total, int point_lights, bool grey) {
    const std::vector<std::size_t> sizes = scene_sizes(rng, min_total);
    std::vector<Material> materials(5);
    for (Material& m : materials)
        m = {.albedo = uniform3(rng, 0.0f, 1.0f), .metallic = uniform(rng, 0.0f, 1.0f),
             .roughness = uniform(rng, 0.05f, 1.0f), .ao = uniform(rng, 0.0f, 1.0f)};
    std::size_t uniform_fragments = 0, checked = 0;
    for (const std::size_t count : sizes) {
        RandomScene scene = random_scene(rng, count, point_lights, grey);
        Fragments& f = scene.fragments;
        // Runs of 1 to 40 fragments (some up to 300), most of them plain.
        std::vector<MaterialRun> runs;
        for (std::uint32_t begin = 0; begin < count;) {
            const std::uint32_t most = rng() % 4 == 0 ? 300 : 40;
            const std::uint32_t end = std::min<std::uint32_t>(std::uint32_t(count), begin + 1 + rng() % most);
            MaterialRun run{begin, end, &materials[rng() % materials.size()], false, rng() % 10 < 7};
            if (!runs.empty() && runs.back().material == run.material) run.material = &materials[(run.material - materials.data() + 1) % materials.size()];
            if (run.plain)
                for (std::uint32_t i = begin; i < end; ++i) {
                    f.albedo_r[i] = run.material->albedo.r, f.albedo_g[i] = run.material->albedo.g;
                    f.albedo_b[i] = run.material->albedo.b, f.metallic[i] = run.material->metallic;
                    f.roughness[i] = run.material->roughness, f.ao[i] = run.material->ao;
                }
            runs.push_back(run);
            begin = end;
        }
        FragmentBuffer buffer;
        buffer.reserve(count);
        const float* const full[] = {f.world_x.data(),  f.world_y.data(),  f.world_z.data(),  f.normal_x.data(),
                                     f.normal_y.data(), f.normal_z.data(), f.albedo_r.data(), f.albedo_g.data(),
                                     f.albedo_b.data(), f.metallic.data(), f.roughness.data(), f.ao.data()};
        for (int c = 0; c <= FragmentBuffer::ao; ++c)
            std::copy_n(full[c], padded_count(count), buffer.channel(FragmentBuffer::Channel(c)));
        for (const MaterialRun& run : runs) {
            if (!run.plain) continue;
            uniform_fragments += run.end - run.begin;
            for (int c = FragmentBuffer::albedo_r; c <= FragmentBuffer::ao; ++c)
                std::fill(buffer.channel(FragmentBuffer::Channel(c)) + run.begin,
                          buffer.channel(FragmentBuffer::Channel(c)) + run.end, NAN);
        }
        for (int c = FragmentBuffer::albedo_r; c <= FragmentBuffer::ao; ++c)  // the padding too
            std::fill(buffer.channel(FragmentBuffer::Channel(c)) + count,
                      buffer.channel(FragmentBuffer::Channel(c)) + padded_count(count), NAN);
        ShadingLights lights;
        lights.assign(scene.cam_pos, scene.lights);
        for (const Isa isa : {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512}) {
            if (!isa_supported(isa)) continue;
            CAPTURE(isa_name(isa));
            CAPTURE(count);
            const Radiance expected = shade_scene(isa, scene);
            FragmentBuffer sparse = buffer;
            if (isa == Isa::scalar) sparse.fill_plain_runs(runs, count);
            else sparse.fill_plain_run_edges(runs, count);
            Radiance out(count);
            shade_fragment_runs(isa, sparse.inputs(count), runs, lights, out.outputs());
            std::size_t differing = 0;
            for (std::size_t i = 0; i < count; ++i)
                for (int c = 0; c < 3; ++c) differing += !same_bits(out.channel(c, i), expected.channel(c, i));
            CHECK(differing == 0);
            CHECK(out.sentinels_intact());
            checked += count;
        }
    }
    MESSAGE(checked, " fragments checked, ", uniform_fragments, " per ISA in plain runs");
    return uniform_fragments;
}

TEST_CASE("shade_fragment_runs takes plain runs' material from the run, with shade_fragments' bits") {
    std::mt19937 rng(1311);
    CHECK(check_plain_runs(rng, 40000, 0, false) > 10000);
    // Grey lights of every type: the kernel sums one colour channel.
    CHECK(check_plain_runs(rng, 12000, 0, true) > 3000);
}

TEST_CASE("shade_fragment_runs unrolls lists of a few point lights with shade_fragments' bits") {
    // One to four point lights and nothing else take an unrolled copy of the
    // kernel (the reference scene's four among them), which sums one colour
    // channel where every light is grey; five, the loop.
    std::mt19937 rng(4077);
    for (const bool grey : {false, true})
        for (int point_lights = 1; point_lights <= 5; ++point_lights) {
            CAPTURE(grey);
            CAPTURE(point_lights);
            CHECK(check_plain_runs(rng, 8000, point_lights, grey) > 2000);
        }
}

TEST_CASE("SIMD tonemap_gamma matches display_from_radiance") {
    std::mt19937 rng(99);
    // Zero, denormal-adjacent, and log-uniform over 1e-8..1e6.
    std::vector<float> values{0.0f, 1e-30f, 1e-8f, 0.5f, 1.0f, 2.0f, 1e6f};
    while (values.size() < 10007) values.push_back(std::pow(10.0f, uniform(rng, -8.0f, 6.0f)));
    Radiance hdr(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        hdr.r[i] = values[i];
        hdr.g[i] = values[(i * 7 + 3) % values.size()];
        hdr.b[i] = values[(i * 13 + 5) % values.size()];
    }
    for (std::size_t i = values.size(); i < padded_count(values.size()); ++i) hdr.r[i] = hdr.g[i] = hdr.b[i] = 1.0f;
    const Radiance expected = display(Isa::scalar, hdr);

    for (Isa isa : kSimdIsas) {
        if (!isa_supported(isa)) {
            MESSAGE("skipping ", isa_name(isa), ": not supported by this CPU");
            continue;
        }
        CAPTURE(isa_name(isa));
        const Radiance shown = display(isa, hdr);
        double worst = 0.0;
        for (std::size_t i = 0; i < shown.count; ++i)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(double(shown.channel(c, i)) - expected.channel(c, i)));
        MESSAGE(isa_name(isa), ": worst tonemap+gamma error ", worst);
        CHECK(worst <= 1e-6);  // a few float ulps of values in [0, 1]
        CHECK(shown.r[0] == 0.0f);  // pow(0, 1/2.2) = 0, not NaN
        CHECK(shown.sentinels_intact());
    }
}

TEST_CASE("ShadingLights: type groups and per-frame spot constants") {
    std::vector<Light> lights(5);
    lights[0].type = LightType::directional, lights[0].color = glm::vec3(1.0f);
    lights[1].type = LightType::point, lights[1].position = glm::vec3(1.0f);
    lights[2].type = LightType::spot, lights[2].inner_cone_degrees = 30.0f, lights[2].outer_cone_degrees = 60.0f;
    lights[3].type = LightType::point, lights[3].position = glm::vec3(3.0f);
    lights[4].type = LightType::directional, lights[4].color = glm::vec3(4.0f);
    ShadingLights soa;
    soa.assign(glm::vec3(0.0f), lights);
    REQUIRE(soa.count() == 5);
    CHECK(soa.spot_begin == 2);
    CHECK(soa.directional_begin == 3);
    // Scene order within each group.
    CHECK(soa.pos_x[0] == 1.0f);
    CHECK(soa.pos_x[1] == 3.0f);
    CHECK(soa.color_r[3] == 1.0f);
    CHECK(soa.color_r[4] == 4.0f);
    // cos 60° = 0.5, 1/(cos 30° − cos 60°) = 1/(0.8660 − 0.5) = 2.732
    CHECK(soa.cos_outer[2] == doctest::Approx(0.5));
    CHECK(soa.inv_cone_width[2] == doctest::Approx(2.7320508));
    CHECK_FALSE(soa.any_range);
}

// Shadows (shade/shadow_maps.hpp): a shadowed light's share of Lo times its
// visibility. The SIMD kernels against the scalar reference, within the bound
// above (visibility <= 1 only shrinks each light's share and its error).
namespace {

struct ShadowedScene {
    ShadingLights lights;
    std::vector<float> visibility;  // plane per shadowed light, padded
    std::size_t stride = 0;
};

// Every other light (in ShadingLights order) shadowed, its visibility per
// fragment 0, 1 or some ninths (as the 3×3 filter gives).
ShadowedScene shadow_every_other_light(std::mt19937& rng, const RandomScene& scene) {
    ShadowedScene s;
    s.lights.assign(scene.cam_pos, scene.lights);
    s.stride = padded_count(scene.fragments.count);
    std::int32_t slots = 0;
    for (std::size_t j = 0; j < s.lights.count(); j += 2) s.lights.shadow_slot[j] = slots++;
    s.lights.shadow_maps.assign(std::size_t(slots), nullptr);  // only their count is read here
    s.visibility.resize(std::size_t(slots) * s.stride);
    for (float& v : s.visibility) {
        const int pick = std::uniform_int_distribution<int>(0, 11)(rng);
        v = pick <= 1 ? float(pick) : float(pick - 2) / 9.0f;
    }
    return s;
}

FragmentInputs with_visibility(FragmentInputs in, const ShadowedScene& s) {
    in.visibility = s.visibility.data(), in.visibility_stride = s.stride;
    return in;
}

}  // namespace

TEST_CASE("shadow visibility: the scalar path scales each shadowed light's share of Lo") {
    std::mt19937 rng(32);
    for (std::size_t count : {1u, 13u, 200u}) {
        const RandomScene scene = random_scene(rng, count);
        ShadowedScene s = shadow_every_other_light(rng, scene);
        Radiance shadowed(count), unshadowed(count);
        shade_fragments(Isa::scalar, with_visibility(scene.fragments.inputs(), s), s.lights, shadowed.outputs());
        shade_fragments(Isa::scalar, scene.fragments.inputs(), s.lights, unshadowed.outputs());
        bool equal = true, all_lit_equal = true;
        const Fragments& f = scene.fragments;
        for (std::size_t i = 0; i < count; ++i) {
            // The reference with each light's visibility, in ShadingLights order.
            std::vector<float> visibility;
            for (std::size_t j = 0; j < s.lights.count(); ++j)
                visibility.push_back(s.lights.shadow_slot[j] >= 0
                                         ? s.visibility[std::size_t(s.lights.shadow_slot[j]) * s.stride + i]
                                         : 1.0f);
            const glm::vec3 expected =
                shade_pbr(f.world_pos(i), f.normal(i), f.material(i), scene.cam_pos, s.lights.records, visibility);
            for (int c = 0; c < 3; ++c) equal = equal && same_bits(shadowed.channel(c, i), expected[c]);
        }
        CHECK(equal);
        // Visibility 1 everywhere: the unshadowed bits.
        std::fill(s.visibility.begin(), s.visibility.end(), 1.0f);
        Radiance lit(count);
        shade_fragments(Isa::scalar, with_visibility(scene.fragments.inputs(), s), s.lights, lit.outputs());
        for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < 3; ++c) all_lit_equal = all_lit_equal && same_bits(lit.channel(c, i), unshadowed.channel(c, i));
        CHECK(all_lit_equal);
    }
    // The reference overload itself: visibility 1 is shade_pbr's bits, 0 leaves the ambient term.
    const RandomScene scene = random_scene(rng, 50);
    const Fragments& f = scene.fragments;
    bool same = true, dark = true;
    for (std::size_t i = 0; i < f.count; ++i) {
        const std::vector<float> ones(scene.lights.size(), 1.0f), zeros(scene.lights.size(), 0.0f);
        const glm::vec3 plain = shade_pbr(f.world_pos(i), f.normal(i), f.material(i), scene.cam_pos, scene.lights);
        const glm::vec3 lit = shade_pbr(f.world_pos(i), f.normal(i), f.material(i), scene.cam_pos, scene.lights, ones);
        const glm::vec3 none = shade_pbr(f.world_pos(i), f.normal(i), f.material(i), scene.cam_pos, scene.lights, zeros);
        const glm::vec3 ambient = ambient_radiance(f.material(i));
        for (int c = 0; c < 3; ++c) same = same && same_bits(plain[c], lit[c]), dark = dark && same_bits(none[c], ambient[c]);
    }
    CHECK(same);
    CHECK(dark);
}

TEST_CASE("shadow visibility: SIMD kernels match the scalar reference, and visibility 1 changes no bit") {
    std::mt19937 rng(3232);
    const std::vector<std::size_t> sizes = scene_sizes(rng, 30000);
    for (Isa isa : kSimdIsas) {
        if (!isa_supported(isa)) {
            MESSAGE("skipping ", isa_name(isa), ": not supported by this CPU");
            continue;
        }
        CAPTURE(isa_name(isa));
        std::mt19937 scene_rng(7);
        std::size_t failures = 0, lit_differences = 0, run_differences = 0, range_differences = 0;
        for (std::size_t n : sizes) {
            const RandomScene scene = random_scene(scene_rng, n);
            ShadowedScene s = shadow_every_other_light(scene_rng, scene);
            const FragmentInputs in = with_visibility(scene.fragments.inputs(), s);
            Radiance reference(n), out(n);
            shade_fragments(Isa::scalar, in, s.lights, reference.outputs());
            shade_fragments(isa, in, s.lights, out.outputs());
            for (std::size_t i = 0; i < n; ++i) {
                const glm::dvec3 allowance = conditioning_allowance(scene, i);
                for (int c = 0; c < 3; ++c) {
                    const double expected = reference.channel(c, i), actual = out.channel(c, i);
                    const double bound = kRelTolerance * std::abs(expected) + kAbsTolerance + allowance[c];
                    if (!(std::abs(actual - expected) <= bound)) ++failures;
                }
            }
            // The same lights through the other entry points: the same bits.
            Radiance in_range(n);
            shade_fragments_in_range(isa, in, s.lights, s.lights.every, in_range.outputs());
            const MaterialRun run{0, std::uint32_t(n), nullptr, false, false};
            Radiance runs(n);
            shade_fragment_runs(isa, in, std::span(&run, 1), s.lights, runs.outputs());
            for (std::size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) {
                    run_differences += !same_bits(runs.channel(c, i), out.channel(c, i));
                    range_differences += !same_bits(in_range.channel(c, i), out.channel(c, i));
                }
            // Visibility 1: the unshadowed kernel's bits.
            std::fill(s.visibility.begin(), s.visibility.end(), 1.0f);
            Radiance lit(n), unshadowed(n);
            shade_fragments(isa, in, s.lights, lit.outputs());
            shade_fragments(isa, scene.fragments.inputs(), s.lights, unshadowed.outputs());
            for (std::size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) lit_differences += !same_bits(lit.channel(c, i), unshadowed.channel(c, i));
        }
        CHECK(failures == 0);
        CHECK(run_differences == 0);
        CHECK(range_differences == 0);
        CHECK(lit_differences == 0);
    }
}
