// The IBL ambient term: its SIMD kernels against the scalar reference (the same
// bits, every ISA this CPU runs), the reference against pbr.fs's formula, and
// the direct-light kernels with ao = 0 giving Lo alone.
#include <cstring>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include "shade/ibl_reference.hpp"
#include "shade/shade_kernels.hpp"

using namespace tessera;
using namespace tessera::shade;

namespace {

// Small maps of random texels: every tap's arithmetic is exercised, not the pictures.
environment::EnvironmentMaps random_maps(std::mt19937& random) {
    std::uniform_real_distribution<float> value(0.0f, 4.0f);
    environment::EnvironmentMaps maps;
    maps.irradiance = environment::CubeMap(4, 1);
    maps.prefiltered = environment::CubeMap(16, 5);
    for (environment::CubeMap* cube : {&maps.irradiance, &maps.prefiltered}) {
        for (int l = 0; l < cube->levels(); ++l) {
            for (int f = 0; f < environment::kCubeFaces; ++f)
                for (int y = 0; y < cube->size(l); ++y)
                    for (int x = 0; x < cube->size(l); ++x) cube->texel(l, f, x, y) = {value(random), value(random), value(random)};
            cube->fill_borders(l);
        }
    }
    auto lut = std::make_shared<environment::BrdfLut>(8);
    for (glm::vec2& ab : lut->data()) ab = {value(random) / 4.0f, value(random) / 8.0f};
    maps.brdf = lut;
    return maps;
}

struct Fragments {
    std::size_t count;
    std::vector<float> c[12];
    explicit Fragments(std::size_t n, std::mt19937& random) : count(n) {
        std::uniform_real_distribution<float> pos(-3.0f, 3.0f), unit(0.0f, 1.0f), normal(-1.0f, 1.0f);
        for (auto& v : c) v.resize(padded_count(n));
        for (std::size_t i = 0; i < padded_count(n); ++i) {
            c[0][i] = pos(random), c[1][i] = pos(random), c[2][i] = pos(random);
            c[3][i] = normal(random), c[4][i] = normal(random), c[5][i] = normal(random) + 0.01f;
            c[6][i] = unit(random), c[7][i] = unit(random), c[8][i] = unit(random);
            c[9][i] = unit(random), c[10][i] = i % 7 == 0 ? 0.0f : (i % 11 == 0 ? 1.0f : unit(random)), c[11][i] = unit(random);
        }
    }
    FragmentInputs inputs() const {
        return {count, c[0].data(), c[1].data(), c[2].data(), c[3].data(), c[4].data(), c[5].data(),
                c[6].data(), c[7].data(), c[8].data(), c[9].data(), c[10].data(), c[11].data()};
    }
};

struct Outputs {
    std::vector<float> r, g, b;
    explicit Outputs(std::size_t n) : r(padded_count(n), 0.5f), g(padded_count(n), 0.25f), b(padded_count(n), 0.0f) {}
    RadianceOutputs outputs() { return {r.data(), g.data(), b.data()}; }
};

}  // namespace

TEST_CASE("IBL kernels: every ISA gives the scalar reference's bits") {
    std::mt19937 random(32);
    const environment::EnvironmentMaps maps = random_maps(random);
    const Fragments fragments(203, random);
    const glm::vec3 cam(0.5f, 1.0f, 9.0f);
    for (const float rotation : {0.0f, 73.0f}) {
        EnvironmentLight light;
        light.intensity = 1.7f, light.rotation_degrees = rotation;
        IblLighting ibl = ibl_lighting(light);
        ibl.maps = &maps;
        Outputs expected(fragments.count);
        add_ibl_ambient(Isa::scalar, fragments.inputs(), cam, ibl, expected.outputs());
        for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
            if (!isa_supported(isa)) continue;
            Outputs actual(fragments.count);
            add_ibl_ambient(isa, fragments.inputs(), cam, ibl, actual.outputs());
            INFO(isa_name(isa) << " rotation " << rotation);
            CHECK(std::memcmp(actual.r.data(), expected.r.data(), fragments.count * 4) == 0);
            CHECK(std::memcmp(actual.g.data(), expected.g.data(), fragments.count * 4) == 0);
            CHECK(std::memcmp(actual.b.data(), expected.b.data(), fragments.count * 4) == 0);
        }
        // The scalar loop adds ambient_radiance_ibl to what was there.
        const Material m{.albedo = {fragments.c[6][5], fragments.c[7][5], fragments.c[8][5]}, .metallic = fragments.c[9][5],
                         .roughness = fragments.c[10][5], .ao = fragments.c[11][5]};
        const ShadingPoint p = shading_point({fragments.c[0][5], fragments.c[1][5], fragments.c[2][5]},
                                             {fragments.c[3][5], fragments.c[4][5], fragments.c[5][5]}, m, cam);
        CHECK(expected.g[5] == ambient_radiance_ibl(p, ibl).g + 0.25f);
    }
}

TEST_CASE("IBL reference: pbr.fs's ambient for a uniform environment and a white BRDF table") {
    // Every map constant: irradiance E, pre-filtered P, (A, B): the ambient is
    // (kD·E·albedo + P·(F·A + B))·ao with F = fresnelSchlickRoughness(N·V).
    environment::EnvironmentMaps maps;
    maps.irradiance = environment::CubeMap(2, 1);
    maps.prefiltered = environment::CubeMap(4, 3);
    for (glm::vec3& t : maps.irradiance.data()) t = glm::vec3(2.0f);
    for (glm::vec3& t : maps.prefiltered.data()) t = glm::vec3(3.0f);
    auto lut = std::make_shared<environment::BrdfLut>(2);
    for (glm::vec2& ab : lut->data()) ab = {0.5f, 0.25f};
    maps.brdf = lut;
    IblLighting ibl;
    ibl.maps = &maps;
    const Material m{.albedo = {0.8f, 0.4f, 0.2f}, .metallic = 0.25f, .roughness = 0.6f, .ao = 0.9f};
    const ShadingPoint p = shading_point({0, 0, 0}, {0, 0, 1}, m, {0, 0, 5});  // N·V = 1
    const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), m.albedo, m.metallic);
    const glm::vec3 f = f0;  // (1 − N·V)⁵ = 0
    const glm::vec3 expected = ((1.0f - f) * (1.0f - m.metallic) * 2.0f * m.albedo + 3.0f * (f * 0.5f + 0.25f)) * m.ao;
    const glm::vec3 ambient = ambient_radiance_ibl(p, ibl);
    CHECK(ambient.r == doctest::Approx(expected.r));
    CHECK(ambient.g == doctest::Approx(expected.g));
    CHECK(ambient.b == doctest::Approx(expected.b));
    // Grazing: F rises to max(1 − roughness, F0).
    CHECK(fresnel_schlick_roughness(0.0f, f0, 0.6f).r == doctest::Approx(std::max(0.4f, f0.r)));
    ibl.intensity = 2.0f;
    CHECK(ambient_radiance_ibl(p, ibl).g == doctest::Approx(2.0f * expected.g));
}

TEST_CASE("IBL: the direct-light kernels with ao = 0 give Lo alone, so Lo + ambient is pbr.fs's ambient + Lo") {
    std::mt19937 random(5);
    Fragments fragments(64, random);
    std::fill(fragments.c[11].begin(), fragments.c[11].end(), 0.0f);  // ao
    const std::vector<Light> lights{{.position = {3, 4, 5}, .color = {20, 20, 20}}};
    ShadingLights shading;
    shading.assign({0, 0, 8}, lights);
    Outputs out(fragments.count);
    shade_fragments(Isa::scalar, fragments.inputs(), shading, out.outputs());
    for (std::size_t i = 0; i < fragments.count; i += 9) {
        const Material m{.albedo = {fragments.c[6][i], fragments.c[7][i], fragments.c[8][i]}, .metallic = fragments.c[9][i],
                         .roughness = fragments.c[10][i], .ao = 1.0f};
        const ShadingPoint p = shading_point({fragments.c[0][i], fragments.c[1][i], fragments.c[2][i]},
                                             {fragments.c[3][i], fragments.c[4][i], fragments.c[5][i]}, m, {0, 0, 8});
        CHECK(out.r[i] == reflected_radiance(p, lights[0]).r);
    }
}

TEST_CASE("IBL background: every ISA gives the scalar sampler's bits, times the exposure") {
    std::mt19937 random(9);
    environment::EnvironmentMaps maps = random_maps(random);
    maps.background = environment::CubeMap(8, 1);
    std::uniform_real_distribution<float> value(0.0f, 10.0f), dir(-1.0f, 1.0f);
    for (glm::vec3& t : maps.background.data()) t = {value(random), value(random), value(random)};
    maps.background.fill_borders(0);
    const std::size_t n = 77;
    std::vector<float> x(padded_count(n)), y(padded_count(n)), z(padded_count(n));
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = dir(random), y[i] = dir(random), z[i] = dir(random);
    EnvironmentLight light;
    light.intensity = 0.5f, light.rotation_degrees = -30.0f;
    IblLighting ibl = ibl_lighting(light);
    ibl.maps = &maps;
    Outputs expected(n);
    sample_environment_background(Isa::scalar, n, x.data(), y.data(), z.data(), ibl, 2.0f, expected.outputs());
    CHECK(expected.r[3] == environment_background(ibl, {x[3], y[3], z[3]}).r * 2.0f);
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (!isa_supported(isa)) continue;
        Outputs actual(n);
        sample_environment_background(isa, n, x.data(), y.data(), z.data(), ibl, 2.0f, actual.outputs());
        INFO(isa_name(isa));
        CHECK(std::memcmp(actual.r.data(), expected.r.data(), n * 4) == 0);
        CHECK(std::memcmp(actual.b.data(), expected.b.data(), n * 4) == 0);
    }
}

// Directions along short random lines, a vector's worth each (16 lanes): the
// neighbouring taps the AVX-512 kernels read through windows of texel rows
// (environment/cube_map_simd.hpp), some lines crossing a texel row or a face.
static std::vector<glm::vec3> coherent_directions(std::mt19937& random, std::size_t lines, float step) {
    std::uniform_real_distribution<float> start(-1.0f, 1.0f), slope(-1.0f, 1.0f);
    std::vector<glm::vec3> d;
    for (std::size_t line = 0; line < lines; ++line) {
        const glm::vec3 origin = glm::normalize(glm::vec3(start(random), start(random), start(random)));
        const glm::vec3 along = glm::vec3(slope(random), slope(random) * 0.2f, slope(random)) * step;
        for (int i = 0; i < 16; ++i) d.push_back(origin + along * float(i));
    }
    return d;
}

TEST_CASE("IBL kernels: neighbouring lanes (windowed taps) give the scalar reference's bits too") {
    std::mt19937 random(33);
    environment::EnvironmentMaps maps = random_maps(random);
    maps.background = environment::CubeMap(32, 1);
    std::uniform_real_distribution<float> value(0.0f, 10.0f);
    for (glm::vec3& t : maps.background.data()) t = {value(random), value(random), value(random)};
    maps.background.fill_borders(0);
    IblLighting ibl = ibl_lighting(EnvironmentLight{});
    ibl.maps = &maps;
    // The background: rows of view rays.
    const std::vector<glm::vec3> rays = coherent_directions(random, 64, 0.01f);
    const std::size_t n = rays.size();
    std::vector<float> x(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = rays[i].x, y[i] = rays[i].y, z[i] = rays[i].z;
    Outputs expected(n);
    sample_environment_background(Isa::scalar, n, x.data(), y.data(), z.data(), ibl, 1.0f, expected.outputs());
    // Surfaces: normals along lines, one roughness per vector (one level of the pre-filtered map).
    Fragments fragments(n, random);
    const std::vector<glm::vec3> normals = coherent_directions(random, 64, 0.02f);
    for (std::size_t i = 0; i < n; ++i) {
        fragments.c[0][i] = normals[i].x, fragments.c[1][i] = normals[i].y, fragments.c[2][i] = normals[i].z;
        fragments.c[3][i] = normals[i].x, fragments.c[4][i] = normals[i].y, fragments.c[5][i] = normals[i].z;
        fragments.c[10][i] = fragments.c[10][i / 16 * 16];
    }
    const glm::vec3 cam(0.0f, 0.0f, 0.0f);  // at the centre: V = −N, R = −N
    Outputs shaded(n);
    add_ibl_ambient(Isa::scalar, fragments.inputs(), cam, ibl, shaded.outputs());
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (!isa_supported(isa)) continue;
        INFO(isa_name(isa));
        Outputs background(n), ambient(n);
        sample_environment_background(isa, n, x.data(), y.data(), z.data(), ibl, 1.0f, background.outputs());
        add_ibl_ambient(isa, fragments.inputs(), cam, ibl, ambient.outputs());
        CHECK(std::memcmp(background.r.data(), expected.r.data(), n * 4) == 0);
        CHECK(std::memcmp(background.g.data(), expected.g.data(), n * 4) == 0);
        CHECK(std::memcmp(background.b.data(), expected.b.data(), n * 4) == 0);
        CHECK(std::memcmp(ambient.r.data(), shaded.r.data(), n * 4) == 0);
        CHECK(std::memcmp(ambient.g.data(), shaded.g.data(), n * 4) == 0);
        CHECK(std::memcmp(ambient.b.data(), shaded.b.data(), n * 4) == 0);
    }
}

TEST_CASE("IBL background rows: every ISA gives background_ray's scalar bits, gaps and all") {
    std::mt19937 random(41);
    environment::EnvironmentMaps maps = random_maps(random);
    maps.background = environment::CubeMap(64, 1);
    std::uniform_real_distribution<float> value(0.0f, 10.0f);
    for (glm::vec3& t : maps.background.data()) t = {value(random), value(random), value(random)};
    maps.background.fill_borders(0);
    IblLighting ibl = ibl_lighting(EnvironmentLight{});
    ibl.maps = &maps;
    const BackgroundRays rays{glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f)), {0.76f, 0.0f, 0.2f}, {0.0f, 0.41f, 0.05f},
                              1280.0f, 0.37f};
    // A row's uncovered pixels: runs with gaps where a surface covers the row.
    std::vector<float> columns;
    for (int x = 0; x < 1280; ++x)
        if (x % 97 < 60) columns.push_back(float(x));
    const std::size_t n = columns.size();
    columns.resize(padded_count(n), 0.0f);
    Outputs expected(n);
    sample_environment_background_row(Isa::scalar, n, columns.data(), rays, ibl, 0.5f, expected.outputs());
    CHECK(expected.g[7] == environment_background(ibl, background_ray(rays, columns[7])).g * 0.5f);
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (!isa_supported(isa)) continue;
        INFO(isa_name(isa));
        Outputs actual(n);
        sample_environment_background_row(isa, n, columns.data(), rays, ibl, 0.5f, actual.outputs());
        CHECK(std::memcmp(actual.r.data(), expected.r.data(), n * 4) == 0);
        CHECK(std::memcmp(actual.g.data(), expected.g.data(), n * 4) == 0);
        CHECK(std::memcmp(actual.b.data(), expected.b.data(), n * 4) == 0);
    }
}
