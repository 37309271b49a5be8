// The scalar reference shader against values worked out by hand from the GLSL
// formulas (docs/reference/pbr_lighting.md). Expected values are computed
// here in double precision from the formulas written out, not from the code under test.
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include "shade/pbr_reference.hpp"

namespace {

using namespace tessera;
using namespace tessera::shade;

constexpr double kPiD = 3.14159265359;  // the GLSL's PI

// distribution_ggx's denom = N·H²·(a² − 1) + 1 cancels near N·H = 1, where it
// approaches a²: in float it carries an absolute error of about one ulp of 1,
// so NDF = a²/(π·denom²) is only good to a relative 2·2⁻²⁴/a² there (0.5% at
// roughness 0.05). The reference is the GLSL, so that error is the spec's; these
// tests allow it where the GGX peak is involved.
double ggx_peak_tolerance(double a2) { return 1e-5 + 2.0 * std::ldexp(1.0, -24) / a2; }

double alpha2(double roughness) { return std::pow(roughness, 4.0); }  // a = roughness², a2 = a²
double schlick_k(double roughness) { return (roughness + 1.0) * (roughness + 1.0) / 8.0; }
double schlick_ggx(double n_dot_x, double roughness) {
    const double k = schlick_k(roughness);
    return n_dot_x / (n_dot_x * (1.0 - k) + k);
}

// The set-up of the 45° tests: camera and light mirrored at 45° about N, so
// H = N and N·V = N·L = H·V = c = 1/√2. Returns the BRDF's k_D·albedo/π + specular
// there; the light's contribution is that · radiance · c.
glm::dvec3 brdf_mirrored_45(const Material& material) {
    const glm::dvec3 albedo(material.albedo);
    const double metallic = material.metallic, c = std::sqrt(0.5);
    const glm::dvec3 f0 = glm::dvec3(0.04) * (1.0 - metallic) + albedo * metallic;
    const double ndf = 1.0 / (kPiD * alpha2(material.roughness));
    const double g = schlick_ggx(c, material.roughness) * schlick_ggx(c, material.roughness);
    const glm::dvec3 f = f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0);
    const glm::dvec3 k_d = (1.0 - f) * (1.0 - metallic);
    const glm::dvec3 specular = ndf * g * f / (4.0 * c * c + 0.0001);
    return k_d * albedo / kPiD + specular;
}

void check_vec3(const glm::vec3& actual, const glm::dvec3& expected, double rel = 1e-5) {
    for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        CHECK(actual[c] == doctest::Approx(expected[c]).epsilon(rel));
    }
}

}  // namespace

TEST_CASE("distribution_ggx at N·H = 1 is 1/(π·a²), at N·H <= 0 is a²/π") {
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (float roughness : {0.05f, 0.1f, 0.25f, 0.5f, 0.8f, 1.0f}) {
        CAPTURE(roughness);
        const double a2 = alpha2(roughness);
        // denom = 1·(a² − 1) + 1 = a², so NDF = a² / (π·a⁴).
        CHECK(distribution_ggx(n, n, roughness) == doctest::Approx(1.0 / (kPiD * a2)).epsilon(ggx_peak_tolerance(a2)));
        // denom = 1, so NDF = a² / π; a negative N·H is clamped to 0.
        CHECK(distribution_ggx(n, glm::vec3(1.0f, 0.0f, 0.0f), roughness) ==
              doctest::Approx(a2 / kPiD).epsilon(1e-5));
        CHECK(distribution_ggx(n, glm::vec3(0.0f, 0.6f, -0.8f), roughness) ==
              doctest::Approx(a2 / kPiD).epsilon(1e-5));
    }
    // roughness 1: a² = 1, so NDF = 1/π for every H in the hemisphere.
    CHECK(distribution_ggx(n, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)), 1.0f) ==
          doctest::Approx(1.0 / kPiD).epsilon(1e-5));
}

TEST_CASE("geometry_schlick_ggx with k = (roughness + 1)²/8") {
    // roughness 1: k = 1/2, so G = x / (x/2 + 1/2) = 2x / (x + 1).
    CHECK(geometry_schlick_ggx(1.0f, 1.0f) == doctest::Approx(1.0));
    CHECK(geometry_schlick_ggx(0.5f, 1.0f) == doctest::Approx(2.0 / 3.0));
    // roughness 0: k = 1/8, so G(1/2) = (1/2) / (7/16 + 2/16) = 8/9.
    CHECK(geometry_schlick_ggx(0.5f, 0.0f) == doctest::Approx(8.0 / 9.0));
    // roughness 0.5: k = 2.25/8 = 0.28125; G(0.25) = 0.25 / (0.25·0.71875 + 0.28125).
    CHECK(geometry_schlick_ggx(0.25f, 0.5f) == doctest::Approx(0.25 / (0.25 * 0.71875 + 0.28125)));
    CHECK(geometry_schlick_ggx(0.0f, 0.3f) == 0.0f);

    // Smith is the product for N·L and N·V, each clamped at 0.
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    const glm::vec3 v = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));
    const glm::vec3 l = glm::normalize(glm::vec3(1.0f, 0.0f, std::sqrt(3.0f)));  // N·L = √3/2
    const double c45 = std::sqrt(0.5), c30 = std::sqrt(3.0) / 2.0;
    CHECK(geometry_smith(n, v, l, 0.4f) ==
          doctest::Approx(schlick_ggx(c45, 0.4) * schlick_ggx(c30, 0.4)).epsilon(1e-5));
    CHECK(geometry_smith(n, v, -l, 0.4f) == 0.0f);
}

TEST_CASE("fresnel_schlick: F0 head-on, 1 at grazing") {
    const glm::vec3 f0(0.04f, 0.5f, 0.9f);
    check_vec3(fresnel_schlick(1.0f, f0), glm::dvec3(0.04, 0.5, 0.9));
    check_vec3(fresnel_schlick(0.0f, f0), glm::dvec3(1.0));
    // (1 − 0.5)⁵ = 1/32
    check_vec3(fresnel_schlick(0.5f, f0), glm::dvec3(f0) + (1.0 - glm::dvec3(f0)) / 32.0);
    // 1 − cosθ is clamped to [0, 1].
    check_vec3(fresnel_schlick(1.5f, f0), glm::dvec3(0.04, 0.5, 0.9));
    check_vec3(fresnel_schlick(-1.0f, f0), glm::dvec3(1.0));
}

TEST_CASE("Reinhard and gamma") {
    check_vec3(tonemap_reinhard(glm::vec3(1.0f, 0.0f, 3.0f)), glm::dvec3(0.5, 0.0, 0.75));
    CHECK(tonemap_reinhard(glm::vec3(0.0f)) == glm::vec3(0.0f));
    const float half_linear = std::pow(0.5f, 2.2f);
    check_vec3(gamma_encode(glm::vec3(half_linear, 0.0f, 1.0f)), glm::dvec3(0.5, 0.0, 1.0));
    CHECK(gamma_encode(glm::vec3(0.0f)) == glm::vec3(0.0f));
    check_vec3(display_from_radiance(glm::vec3(1.0f)), glm::dvec3(std::pow(0.5, 1.0 / 2.2)));
}

TEST_CASE("shade_pbr: light and camera straight above the surface") {
    // N = V = L = H = +Z: N·H = N·V = N·L = H·V = 1, so NDF = 1/(π·a²), G = 1,
    // F = F0, specular = NDF·F0 / (4 + 0.0001), radiance = color / d².
    const glm::vec3 world_pos(1.0f, -2.0f, 0.5f);
    const glm::vec3 normal(0.0f, 0.0f, 3.0f);  // not unit: the shader normalizes
    const glm::vec3 cam_pos = world_pos + glm::vec3(0.0f, 0.0f, 5.0f);
    const double distance = 3.0;
    const Light light{world_pos + glm::vec3(0.0f, 0.0f, float(distance)), glm::vec3(300.0f, 150.0f, 30.0f)};
    const Material material{.albedo = glm::vec3(0.8f, 0.4f, 0.2f), .metallic = 0.25f, .roughness = 0.5f, .ao = 0.7f};

    const glm::dvec3 albedo(material.albedo);
    const double metallic = material.metallic, ao = material.ao;
    const glm::dvec3 f0 = glm::dvec3(0.04) * (1.0 - metallic) + albedo * metallic;
    const double ndf = 1.0 / (kPiD * alpha2(material.roughness));
    const glm::dvec3 k_d = (1.0 - f0) * (1.0 - metallic);
    const glm::dvec3 specular = ndf * 1.0 * f0 / (4.0 + 0.0001);
    const glm::dvec3 radiance = glm::dvec3(light.color) / (distance * distance);
    const glm::dvec3 expected = 0.03 * albedo * ao + (k_d * albedo / kPiD + specular) * radiance;

    const std::vector<Light> lights{light};
    check_vec3(shade_pbr(world_pos, normal, material, cam_pos, lights), expected,
               ggx_peak_tolerance(alpha2(material.roughness)));

    // No lights, or a light in the tangent plane (N·L = 0) or behind: ambient only.
    const glm::dvec3 ambient = 0.03 * albedo * ao;
    check_vec3(shade_pbr(world_pos, normal, material, cam_pos, {}), ambient);
    // (Not straight below: with L = −V, H = normalize(0) is NaN, in the GLSL too.)
    const std::vector<Light> grazing{{world_pos + glm::vec3(4.0f, 0.0f, 0.0f), glm::vec3(100.0f)},
                                          {world_pos + glm::vec3(1.0f, 0.0f, -2.0f), glm::vec3(100.0f)}};
    check_vec3(shade_pbr(world_pos, normal, material, cam_pos, grazing), ambient);
}

TEST_CASE("shade_pbr: camera and light mirrored at 45° so H = N") {
    // V = (1, 0, 1)/√2, L = (−1, 0, 1)/√2: H = N = +Z, N·V = N·L = H·V = c = 1/√2.
    const glm::vec3 world_pos(0.0f);
    const glm::vec3 normal(0.0f, 0.0f, 1.0f);
    const glm::vec3 cam_pos(4.0f, 0.0f, 4.0f);
    const Light light{glm::vec3(-2.0f, 0.0f, 2.0f), glm::vec3(50.0f, 100.0f, 200.0f)};  // distance² = 8
    const Material material{.albedo = glm::vec3(0.9f, 0.6f, 0.3f), .metallic = 0.3f, .roughness = 0.6f, .ao = 1.0f};

    const glm::dvec3 albedo(material.albedo);
    const double c = std::sqrt(0.5);
    const glm::dvec3 radiance = glm::dvec3(light.color) / 8.0;
    const glm::dvec3 direct = brdf_mirrored_45(material) * radiance * c;
    const glm::dvec3 expected = 0.03 * albedo * double(material.ao) + direct;

    const double tolerance = ggx_peak_tolerance(alpha2(material.roughness));
    const std::vector<Light> lights{light};
    check_vec3(shade_pbr(world_pos, normal, material, cam_pos, lights), expected, tolerance);

    // Lights add: the same light twice doubles the direct part.
    const std::vector<Light> twice{light, light};
    check_vec3(shade_pbr(world_pos, normal, material, cam_pos, twice), expected + direct, tolerance);
}

TEST_CASE("shade_pbr: a directional light arrives along −direction, unattenuated") {
    // The 45° mirror set-up above with L = −direction = (−1, 0, 1)/√2: H = N,
    // N·V = N·L = H·V = c = 1/√2, and radiance = color wherever the surface is.
    const glm::vec3 normal(0.0f, 0.0f, 1.0f);
    Light sun;
    sun.type = LightType::directional;
    sun.direction = glm::normalize(glm::vec3(1.0f, 0.0f, -1.0f));
    sun.color = glm::vec3(2.0f, 1.0f, 0.5f);
    sun.position = glm::vec3(1e6f);  // ignored
    const Material material{.albedo = glm::vec3(0.9f, 0.6f, 0.3f), .metallic = 0.3f, .roughness = 0.6f, .ao = 0.5f};

    const glm::dvec3 albedo(material.albedo);
    const double c = std::sqrt(0.5);
    const glm::dvec3 expected = 0.03 * albedo * double(material.ao) + brdf_mirrored_45(material) * glm::dvec3(sun.color) * c;

    const std::vector<Light> lights{sun};
    const double tolerance = ggx_peak_tolerance(alpha2(material.roughness));
    // The same result near the origin and far from it: no attenuation.
    for (const glm::vec3 world_pos : {glm::vec3(0.0f), glm::vec3(100.0f, -50.0f, 25.0f)}) {
        CAPTURE(world_pos.x);
        const glm::vec3 cam_pos = world_pos + glm::vec3(4.0f, 0.0f, 4.0f);
        check_vec3(shade_pbr(world_pos, normal, material, cam_pos, lights), expected, tolerance);
    }
    // Light from below the surface: ambient only.
    Light from_below = sun;
    from_below.direction = glm::vec3(0.0f, 0.0f, 1.0f);
    const std::vector<Light> below{from_below};
    check_vec3(shade_pbr(glm::vec3(0.0f), normal, material, glm::vec3(4.0f, 0.0f, 4.0f), below),
               0.03 * albedo * double(material.ao));
}

TEST_CASE("shade_pbr: a spot light inside its inner cone, between the cones, outside the outer cone") {
    // Light and camera straight above the surface (N = V = L = H = +Z), as in the
    // point-light case; the spot's direction is tilted by φ from straight down,
    // so θ (direction vs light-to-fragment) = φ and only the cone factor changes:
    //   factor = clamp((cos φ − cos 40°) / (cos 20° − cos 40°), 0, 1).
    const glm::vec3 world_pos(1.0f, -2.0f, 0.5f);
    const glm::vec3 normal(0.0f, 0.0f, 1.0f);
    const glm::vec3 cam_pos = world_pos + glm::vec3(0.0f, 0.0f, 5.0f);
    const double distance = 2.0;
    const Material material{.albedo = glm::vec3(0.8f, 0.4f, 0.2f), .metallic = 0.25f, .roughness = 0.5f, .ao = 1.0f};

    const glm::dvec3 albedo(material.albedo);
    const double metallic = material.metallic;
    const glm::dvec3 f0 = glm::dvec3(0.04) * (1.0 - metallic) + albedo * metallic;
    const double ndf = 1.0 / (kPiD * alpha2(material.roughness));
    const glm::dvec3 k_d = (1.0 - f0) * (1.0 - metallic);
    const glm::dvec3 specular = ndf * f0 / (4.0 + 0.0001);
    const glm::dvec3 color(40.0, 20.0, 10.0);
    const glm::dvec3 point_light_part = (k_d * albedo / kPiD + specular) * color / (distance * distance);
    const glm::dvec3 ambient = 0.03 * albedo;

    const double degrees = kPiD / 180.0;
    const double cos_inner = std::cos(20.0 * degrees), cos_outer = std::cos(40.0 * degrees);
    struct Case {
        double phi_degrees;
        double factor;
    };
    const Case cases[] = {
        {0.0, 1.0},                                                                  // on the axis
        {10.0, 1.0},                                                                 // inside the inner cone
        {30.0, (std::cos(30.0 * degrees) - cos_outer) / (cos_inner - cos_outer)},  // between: 0.5758...
        {39.0, (std::cos(39.0 * degrees) - cos_outer) / (cos_inner - cos_outer)},  // just inside the outer cone
        {50.0, 0.0},                                                                 // outside the outer cone
        {180.0, 0.0},                                                                // pointing away
    };
    for (const Case& c : cases) {
        CAPTURE(c.phi_degrees);
        Light spot;
        spot.type = LightType::spot;
        spot.position = world_pos + glm::vec3(0.0f, 0.0f, float(distance));
        spot.color = glm::vec3(color);
        const double phi = c.phi_degrees * degrees;
        spot.direction = glm::vec3(float(std::sin(phi)), 0.0f, float(-std::cos(phi)));
        spot.inner_cone_degrees = 20.0f;
        spot.outer_cone_degrees = 40.0f;
        const glm::dvec3 expected = ambient + point_light_part * c.factor;
        const std::vector<Light> lights{spot};
        // The factor's float rounding: cos φ to an ulp, divided by cos 20° − cos 40° ≈ 0.18.
        check_vec3(shade_pbr(world_pos, normal, material, cam_pos, lights), expected,
                   ggx_peak_tolerance(alpha2(material.roughness)) + 4e-6);
    }
    CHECK(cases[2].factor == doctest::Approx(0.5758).epsilon(1e-3));  // the hand value of the middle case

    // A spot whose cones cover the fragment is the point light, term for term.
    Light spot;
    spot.type = LightType::spot;
    spot.position = world_pos + glm::vec3(0.0f, 0.0f, float(distance));
    spot.color = glm::vec3(color);
    spot.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    Light point = spot;
    point.type = LightType::point;
    const std::vector<Light> spots{spot}, points{point};
    CHECK(shade_pbr(world_pos, normal, material, cam_pos, spots) == shade_pbr(world_pos, normal, material, cam_pos, points));
}
