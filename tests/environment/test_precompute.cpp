// LearnOpenGL's IBL pre-computation (src/environment/precompute.cpp), at small
// sizes: known integrals of a uniform environment, the chapter's Hammersley
// points and BRDF table, the SIMD kernels' maps against the scalar reference's
// (the same bits, every ISA this CPU runs), and the same bits on 1 and 2 threads.
#include <cmath>
#include <cstring>
#include <random>

#include <doctest/doctest.h>
#include <tbb/task_arena.h>

#include "environment/precompute.hpp"

using namespace tessera::environment;
using tessera::simd::Isa;

namespace {

EquirectImage uniform_image(glm::vec3 radiance, int width = 16) {
    EquirectImage image;
    image.width = width, image.height = width / 2;
    image.rgb.assign(std::size_t(image.width) * image.height, radiance);
    return image;
}

// A sky brighter above than below: radiance 1 + 3·max(y, 0) (y up).
EquirectImage sky_image() {
    EquirectImage image = uniform_image(glm::vec3(1.0f), 64);
    for (int row = 0; row < image.height; ++row) {
        const float v = (row + 0.5f) / image.height;  // rows bottom-up: v = 1 is the top
        const float y = std::sin((v - 0.5f) * 3.14159265f);
        for (int x = 0; x < image.width; ++x) image.rgb[std::size_t(row) * image.width + x] = glm::vec3(1.0f + 3.0f * std::max(y, 0.0f));
    }
    return image;
}

// A sky with random texels, so that neighbouring taps differ.
EquirectImage noisy_sky_image() {
    EquirectImage image = sky_image();
    std::mt19937 random(7);
    std::uniform_real_distribution<float> scale(0.25f, 4.0f);
    for (glm::vec3& texel : image.rgb) texel *= glm::vec3(scale(random), scale(random), scale(random));
    return image;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("precompute: every ISA's kernels give the scalar reference's irradiance, pre-filtered and BRDF maps") {
    const CubeMap environment = equirect_to_cubemap(noisy_sky_image(), 32);
    // Sizes whose texel counts are and are not multiples of a vector.
    const CubeMap irradiance = convolve_irradiance(environment, 3, Isa::scalar);
    const CubeMap prefiltered = prefilter_specular(environment, 12, 5, Isa::scalar);
    const BrdfLut brdf = integrate_brdf(20, Isa::scalar);
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (!tessera::simd::isa_supported(isa)) continue;
        INFO(tessera::simd::isa_name(isa));
        CHECK(same_bits(convolve_irradiance(environment, 3, isa).data(), irradiance.data()));
        CHECK(same_bits(prefilter_specular(environment, 12, 5, isa).data(), prefiltered.data()));
        CHECK(same_bits(integrate_brdf(20, isa).data(), brdf.data()));
    }
}

TEST_CASE("precompute: Hammersley points are the chapter's radical inverse") {
    CHECK(radical_inverse_vdc(0) == 0.0f);
    CHECK(radical_inverse_vdc(1) == 0.5f);
    CHECK(radical_inverse_vdc(2) == 0.25f);
    CHECK(radical_inverse_vdc(3) == 0.75f);
    CHECK(hammersley(512, 1024).x == 0.5f);
    // roughness 0: every GGX sample is N itself.
    const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 0.9f, -0.3f));
    const glm::vec3 h = importance_sample_ggx(hammersley(77, 1024), n, 0.0f);
    CHECK(glm::dot(h, n) == doctest::Approx(1.0f));
}

TEST_CASE("precompute: a uniform environment gives its radiance back as irradiance and pre-filtered light") {
    const CubeMap environment = equirect_to_cubemap(uniform_image(glm::vec3(2.0f, 1.0f, 0.5f)), 32);
    CHECK(environment.levels() == 6);
    CHECK(environment.sample_bilinear({0.3f, -0.7f, 0.1f}, 0).x == doctest::Approx(2.0f));
    const CubeMap irradiance = convolve_irradiance(environment, 4);
    // π·L·mean(cos θ sin θ) over the chapter's grid: L to within its 2.5% quadrature error.
    for (const glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(0.2f, 0.9f, 0.1f), glm::vec3(-0.5f, -0.5f, 0.7f)})
        CHECK(irradiance.sample_bilinear(d, 0).x == doctest::Approx(2.0f).epsilon(0.03));
    const CubeMap prefiltered = prefilter_specular(environment, 8, 5);
    CHECK(prefiltered.levels() == 5);
    for (int level = 0; level < 5; ++level)
        CHECK(prefiltered.sample_bilinear({0.1f, 0.2f, 1.0f}, level).y == doctest::Approx(1.0f).epsilon(1e-4));
}

TEST_CASE("precompute: irradiance of a sky lit from above is brighter facing up, and rough reflections blur it") {
    const CubeMap environment = equirect_to_cubemap(sky_image(), 32);
    const CubeMap irradiance = convolve_irradiance(environment, 8);
    const float up = irradiance.sample_bilinear({0, 1, 0}, 0).x, down = irradiance.sample_bilinear({0, -1, 0}, 0).x;
    const float side = irradiance.sample_bilinear({1, 0, 0}, 0).x;
    CHECK(up > side);
    CHECK(side > down);
    CHECK(down == doctest::Approx(1.0f).epsilon(0.05));  // the lower hemisphere is radiance 1
    const CubeMap prefiltered = prefilter_specular(environment, 16, 5);
    // Just below the horizon: sharp at roughness 0 (≈ 1), blurred towards the bright sky at roughness 1.
    const glm::vec3 d(1.0f, -0.3f, 0.0f);
    CHECK(prefiltered.sample_bilinear(d, 0).x < prefiltered.sample_bilinear(d, 4).x);
}

TEST_CASE("precompute: the BRDF table is the chapter's split-sum scale and bias") {
    const BrdfLut lut = integrate_brdf(32);
    // Smooth and head-on: all of F0 is reflected (A ≈ 1, B ≈ 0).
    const glm::vec2 smooth = lut.texel(31, 0);
    CHECK(smooth.x == doctest::Approx(1.0f).epsilon(0.03));
    CHECK(smooth.y < 0.02f);
    // Rough surfaces reflect less of F0 head-on than smooth ones.
    CHECK(lut.texel(31, 31).x < smooth.x);
    for (const glm::vec2& ab : lut.data()) {
        CHECK(ab.x >= 0.0f);
        CHECK(ab.y >= 0.0f);
        CHECK(ab.x + ab.y <= 1.001f);
    }
}

TEST_CASE("precompute: the same bits on 1 and 2 threads") {
    const EquirectImage image = sky_image();
    const auto run = [&](int threads) {
        tbb::task_arena arena(threads);
        EnvironmentMaps maps;
        arena.execute([&] {
            const CubeMap environment = equirect_to_cubemap(image, 32);
            maps.irradiance = convolve_irradiance(environment, 8);
            maps.prefiltered = prefilter_specular(environment, 16, 5);
            maps.brdf = std::make_shared<BrdfLut>(integrate_brdf(16));
        });
        return maps;
    };
    const EnvironmentMaps one = run(1), two = run(2);
    const auto same = [](const auto& a, const auto& b) {
        return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
    };
    CHECK(same(one.irradiance.data(), two.irradiance.data()));
    CHECK(same(one.prefiltered.data(), two.prefiltered.data()));
    CHECK(same(one.brdf->data(), two.brdf->data()));
}
