#include "environment/precompute.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "environment/precompute_kernels.hpp"
#include "simd/lane_padding.hpp"

namespace tessera::environment {

namespace {

// Runs texel(level, face, x, y) for every texel of one level, rows in parallel.
template <class Texel>
void for_each_texel(const CubeMap& cube, int level, Texel&& texel) {
    const int n = cube.size(level);
    tbb::parallel_for(0, kCubeFaces * n, [&](int row) {
        const int face = row / n, y = row % n;
        for (int x = 0; x < n; ++x) texel(face, x, y);
    });
}

// The direction through the centre of texel (x, y) of a face of side n: what
// the capture pass interpolates into WorldPos there (normalized by the shaders).
glm::vec3 texel_direction(int face, int x, int y, int n) {
    return face_direction(face, (float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
}

float distribution_ggx(const glm::vec3& n, const glm::vec3& h, float roughness) {
    const float a = roughness * roughness;
    const float a2 = a * a;
    const float n_dot_h = glm::max(glm::dot(n, h), 0.0f);
    const float n_dot_h2 = n_dot_h * n_dot_h;
    float denom = (n_dot_h2 * (a2 - 1.0f) + 1.0f);
    denom = kPi * denom * denom;
    return a2 / denom;
}

// brdf.fs's GeometrySchlickGGX: k = roughness² / 2 for IBL.
float geometry_schlick_ggx_ibl(float n_dot_v, float roughness) {
    const float a = roughness;
    const float k = (a * a) / 2.0f;
    return n_dot_v / (n_dot_v * (1.0f - k) + k);
}

}  // namespace

float radical_inverse_vdc(unsigned bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10f;  // / 0x100000000
}

glm::vec2 hammersley(unsigned i, unsigned n) { return {float(i) / float(n), radical_inverse_vdc(i)}; }

glm::vec3 ggx_sample_tangent(const glm::vec2& xi, float roughness) {
    const float a = roughness * roughness;
    const float phi = 2.0f * kPi * xi.x;
    const float cos_theta = std::sqrt((1.0f - xi.y) / (1.0f + (a * a - 1.0f) * xi.y));
    const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
    return {std::cos(phi) * sin_theta, std::sin(phi) * sin_theta, cos_theta};
}

glm::vec3 sample_to_world(const glm::vec3& h, const glm::vec3& n) {
    const glm::vec3 up = std::fabs(n.z) < 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 tangent = glm::normalize(glm::cross(up, n));
    const glm::vec3 bitangent = glm::cross(n, tangent);
    const glm::vec3 sample_vec = tangent * h.x + bitangent * h.y + n * h.z;
    return glm::normalize(sample_vec);
}

glm::vec3 importance_sample_ggx(const glm::vec2& xi, const glm::vec3& n, float roughness) {
    return sample_to_world(ggx_sample_tangent(xi, roughness), n);
}

CubeMap equirect_to_cubemap(const EquirectImage& image, int size) {
    int levels = 1;
    while ((size >> (levels - 1)) > 1) ++levels;
    CubeMap cube(size, levels);
    const glm::vec2 inv_atan(0.1591f, 0.3183f);  // the shader's constants, as written
    for_each_texel(cube, 0, [&](int face, int x, int y) {
        const glm::vec3 v = glm::normalize(texel_direction(face, x, y, size));
        glm::vec2 uv(std::atan2(v.z, v.x), std::asin(v.y));
        uv *= inv_atan;
        uv += 0.5f;
        cube.texel(0, face, x, y) = image.sample(uv.x, uv.y);
    });
    cube.fill_borders(0);
    cube.generate_mipmaps();
    return cube;
}

namespace {

// The two loops' samples of irradiance_convolution.fs, counted in float as the shader's loops count.
struct IrradianceSample {
    glm::vec3 tangent;  // (sin θ cos φ, sin θ sin φ, cos θ)
    float cos_theta, sin_theta;
};
std::vector<IrradianceSample> irradiance_samples() {
    std::vector<IrradianceSample> samples;
    for (float phi = 0.0f; phi < 2.0f * kPi; phi += kSampleDelta)
        for (float theta = 0.0f; theta < 0.5f * kPi; theta += kSampleDelta)
            samples.push_back({{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)},
                               std::cos(theta), std::sin(theta)});
    return samples;
}

// The convolution's frame at a texel: N, right = cross(up, N) (not normalized,
// as in the chapter) and up = cross(N, right).
struct IrradianceFrame {
    glm::vec3 n, right, up;
};
IrradianceFrame irradiance_frame(int face, int x, int y, int size) {
    const glm::vec3 n = glm::normalize(texel_direction(face, x, y, size));
    const glm::vec3 right = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), n);
    return {n, right, glm::cross(n, right)};
}

// sample_to_world's frame around a pre-filtered texel's N.
struct PrefilterFrame {
    glm::vec3 normal, tangent, bitangent;
};
PrefilterFrame prefilter_frame(int face, int x, int y, int size) {
    const glm::vec3 normal = glm::normalize(texel_direction(face, x, y, size));
    const glm::vec3 up = std::fabs(normal.z) < 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 tangent = glm::normalize(glm::cross(up, normal));
    return {normal, tangent, glm::cross(normal, tangent)};
}

// A pre-filter level's samples: the tangent-space H and the mip level each
// reads. With N = V = R, D, N·H and H·V depend only on the sample (the
// tangent-space H's cos θ), so they are worked out once per level.
struct PrefilterSamples {
    std::vector<glm::vec3> tangent_h;
    std::vector<float> lod;
};
PrefilterSamples prefilter_samples(float roughness, float sa_texel) {
    PrefilterSamples samples{std::vector<glm::vec3>(kSampleCount), std::vector<float>(kSampleCount)};
    for (unsigned i = 0; i < kSampleCount; ++i) {
        const glm::vec3 z(0.0f, 0.0f, 1.0f);
        const glm::vec3 h = samples.tangent_h[i] = ggx_sample_tangent(hammersley(i, kSampleCount), roughness);
        const float d = distribution_ggx(z, h, roughness);
        const float n_dot_h = glm::max(h.z, 0.0f);
        const float h_dot_v = glm::max(h.z, 0.0f);
        const float pdf = d * n_dot_h / (4.0f * h_dot_v) + 0.0001f;
        const float sa_sample = 1.0f / (float(kSampleCount) * pdf + 0.0001f);
        samples.lod[i] = roughness == 0.0f ? 0.0f : 0.5f * std::log2(sa_sample / sa_texel);
    }
    return samples;
}

// Plain-array lanes for the SIMD kernels: `channels` float arrays of
// padded_count(count) entries.
struct Lanes {
    std::size_t count, padded;
    std::vector<std::vector<float>> channel;
    Lanes(std::size_t n, int channels) : count(n), padded(simd::padded_count(n)), channel(std::size_t(channels)) {
        for (auto& c : channel) c.assign(padded, 0.0f);
    }
    float* operator[](int c) { return channel[std::size_t(c)].data(); }
    void set3(int c, std::size_t i, const glm::vec3& v) { (*this)[c][i] = v.x, (*this)[c + 1][i] = v.y, (*this)[c + 2][i] = v.z; }
};

// Runs kernel(first, count) over the lanes [0, padded) in parallel, in blocks
// of whole vectors: each lane is computed by one call, so the result does not
// depend on the thread count.
template <class Kernel>
void for_each_lane_block(std::size_t padded, Kernel&& kernel) {
    constexpr std::size_t block = simd::kLanePadding;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, padded / block), [&](const tbb::blocked_range<std::size_t>& r) {
        kernel(r.begin() * block, (r.end() - r.begin()) * block);
    });
}

// The SIMD kernels compute texel indices in float: exact while below 2^24.
bool float_indices_exact(const CubeMap& cube) { return cube.data().size() * 3 < (std::size_t(1) << 24); }

simd::Isa checked(simd::Isa isa) {
    simd::require_supported(isa);
    return isa;
}

CubeMap convolve_irradiance_reference(const CubeMap& environment, int size) {
    const std::vector<IrradianceSample> samples = irradiance_samples();
    const float nr_samples = float(samples.size());
    const int level = int(kIrradianceLod);
    CubeMap cube(size, 1);
    for_each_texel(cube, 0, [&](int face, int x, int y) {
        const IrradianceFrame frame = irradiance_frame(face, x, y, size);
        glm::vec3 irradiance(0.0f);
        for (const IrradianceSample& s : samples) {
            const glm::vec3 sample_vec = s.tangent.x * frame.right + s.tangent.y * frame.up + s.tangent.z * frame.n;
            irradiance += environment.sample_bilinear(sample_vec, level) * s.cos_theta * s.sin_theta;
        }
        cube.texel(0, face, x, y) = kPi * irradiance * (1.0f / nr_samples);
    });
    cube.fill_borders(0);
    return cube;
}

// The reference's sums of one pre-filtered texel at roughness > 0.
glm::vec3 prefilter_texel_reference(const CubeMap& environment, const PrefilterFrame& frame,
                                    const PrefilterSamples& samples) {
    const glm::vec3 &normal = frame.normal, r = normal, v = r;
    glm::vec3 prefiltered(0.0f);
    float total_weight = 0.0f;
    for (unsigned i = 0; i < kSampleCount; ++i) {
        const glm::vec3& ht = samples.tangent_h[i];
        // sample_to_world with the texel's frame (the same operations).
        const glm::vec3 h = glm::normalize(frame.tangent * ht.x + frame.bitangent * ht.y + normal * ht.z);
        const glm::vec3 l = glm::normalize(2.0f * glm::dot(v, h) * h - v);
        const float n_dot_l = glm::max(glm::dot(normal, l), 0.0f);
        if (n_dot_l > 0.0f) {
            prefiltered += environment.sample_trilinear(l, samples.lod[i]) * n_dot_l;
            total_weight += n_dot_l;
        }
    }
    return prefiltered / total_weight;
}

CubeMap convolve_irradiance_simd(const CubeMap& environment, int size, simd::Isa isa) {
    const std::vector<IrradianceSample> samples = irradiance_samples();
    const float nr_samples = float(samples.size());
    const int level = int(kIrradianceLod);
    CubeMap cube(size, 1);
    const std::size_t texels = std::size_t(kCubeFaces) * std::size_t(size) * std::size_t(size);
    Lanes frames(texels, 9);
    for (std::size_t i = 0; i < frames.padded; ++i) {
        const std::size_t t = i < texels ? i : 0;  // padding lanes repeat texel 0
        const int face = int(t / (std::size_t(size) * size)), y = int(t / std::size_t(size) % std::size_t(size)),
                  x = int(t % std::size_t(size));
        const IrradianceFrame frame = irradiance_frame(face, x, y, size);
        frames.set3(0, i, frame.n), frames.set3(3, i, frame.right), frames.set3(6, i, frame.up);
    }
    Lanes sample_lanes(samples.size(), 5);
    for (std::size_t s = 0; s < samples.size(); ++s) {
        sample_lanes.set3(0, s, samples[s].tangent);
        sample_lanes[3][s] = samples[s].cos_theta, sample_lanes[4][s] = samples[s].sin_theta;
    }
    const IrradianceKernelInput in{frames[0], frames[1], frames[2], frames[3], frames[4], frames[5], frames[6],
                                   frames[7], frames[8], sample_lanes[0], sample_lanes[1], sample_lanes[2],
                                   sample_lanes[3], sample_lanes[4], samples.size(),
                                   {&environment.data().front().x, float(environment.size(level)),
                                    float(environment.level_offset(level))}};
    Lanes sums(texels, 3);
    for_each_lane_block(frames.padded, [&](std::size_t first, std::size_t count) {
        irradiance_sums(isa, in, first, count, {sums[0], sums[1], sums[2], nullptr});
    });
    for (std::size_t t = 0; t < texels; ++t) {
        const int face = int(t / (std::size_t(size) * size)), y = int(t / std::size_t(size) % std::size_t(size)),
                  x = int(t % std::size_t(size));
        const glm::vec3 irradiance(sums[0][t], sums[1][t], sums[2][t]);
        cube.texel(0, face, x, y) = kPi * irradiance * (1.0f / nr_samples);
    }
    cube.fill_borders(0);
    return cube;
}

// One level (roughness > 0) of prefilter_specular through the SIMD kernel.
void prefilter_level_simd(const CubeMap& environment, const PrefilterSamples& samples, int mip, simd::Isa isa,
                          CubeMap& cube) {
    const int n = cube.size(mip);
    const std::size_t texels = std::size_t(kCubeFaces) * std::size_t(n) * std::size_t(n);
    Lanes frames(texels, 9);
    for (std::size_t i = 0; i < frames.padded; ++i) {
        const std::size_t t = i < texels ? i : 0;
        const int face = int(t / (std::size_t(n) * n)), y = int(t / std::size_t(n) % std::size_t(n)), x = int(t % std::size_t(n));
        const PrefilterFrame frame = prefilter_frame(face, x, y, n);
        frames.set3(0, i, frame.normal), frames.set3(3, i, frame.tangent), frames.set3(6, i, frame.bitangent);
    }
    // CubeMap::sample_trilinear's level choice, per sample.
    const int top_level = environment.levels() - 1;
    std::vector<int> level0(kSampleCount);
    Lanes sample_lanes(kSampleCount, 4);
    for (unsigned s = 0; s < kSampleCount; ++s) {
        const float clamped = std::clamp(samples.lod[s], 0.0f, float(top_level));
        const float l0 = std::min(std::floor(clamped), float(top_level - 1));
        level0[s] = int(l0);
        sample_lanes.set3(0, s, samples.tangent_h[s]);
        sample_lanes[3][s] = clamped - l0;
    }
    std::vector<float> level_size(std::size_t(environment.levels())), level_offset(level_size.size());
    for (int l = 0; l < environment.levels(); ++l)
        level_size[std::size_t(l)] = float(environment.size(l)), level_offset[std::size_t(l)] = float(environment.level_offset(l));
    const PrefilterKernelInput in{frames[0], frames[1], frames[2], frames[3], frames[4], frames[5], frames[6], frames[7],
                                  frames[8], sample_lanes[0], sample_lanes[1], sample_lanes[2], level0.data(),
                                  sample_lanes[3], kSampleCount, &environment.data().front().x, level_size.data(),
                                  level_offset.data()};
    Lanes sums(texels, 4);
    for_each_lane_block(frames.padded, [&](std::size_t first, std::size_t count) {
        prefilter_sums(isa, in, first, count, {sums[0], sums[1], sums[2], sums[3]});
    });
    for (std::size_t t = 0; t < texels; ++t) {
        const int face = int(t / (std::size_t(n) * n)), y = int(t / std::size_t(n) % std::size_t(n)), x = int(t % std::size_t(n));
        const glm::vec3 prefiltered(sums[0][t], sums[1][t], sums[2][t]);
        cube.texel(mip, face, x, y) = prefiltered / sums[3][t];
    }
}

}  // namespace

CubeMap convolve_irradiance(const CubeMap& environment, int size, simd::Isa isa) {
    if (checked(isa) == simd::Isa::scalar || !float_indices_exact(environment))
        return convolve_irradiance_reference(environment, size);
    return convolve_irradiance_simd(environment, size, isa);
}

CubeMap prefilter_specular(const CubeMap& environment, int size, int levels, simd::Isa isa) {
    const bool simd = checked(isa) != simd::Isa::scalar && float_indices_exact(environment) && environment.levels() >= 2;
    CubeMap cube(size, levels);
    const float resolution = float(environment.size(0));  // of the source cubemap, per face
    const float sa_texel = 4.0f * kPi / (6.0f * resolution * resolution);
    for (int mip = 0; mip < levels; ++mip) {
        const float roughness = float(mip) / float(levels - 1);
        const int n = cube.size(mip);
        if (roughness == 0.0f) {  // every sample is H = L = N at level 0: the sum of equal terms
            for_each_texel(cube, mip, [&](int face, int x, int y) {
                cube.texel(mip, face, x, y) =
                    environment.sample_trilinear(glm::normalize(texel_direction(face, x, y, n)), 0.0f);
            });
        } else {
            const PrefilterSamples samples = prefilter_samples(roughness, sa_texel);
            if (simd) {
                prefilter_level_simd(environment, samples, mip, isa, cube);
            } else {
                for_each_texel(cube, mip, [&](int face, int x, int y) {
                    cube.texel(mip, face, x, y) =
                        prefilter_texel_reference(environment, prefilter_frame(face, x, y, n), samples);
                });
            }
        }
        cube.fill_borders(mip);
    }
    return cube;
}

BrdfLut integrate_brdf(int size, simd::Isa isa) {
    const bool simd = checked(isa) != simd::Isa::scalar;
    BrdfLut lut(size);
    // N·V and V per column, the same on every row.
    Lanes columns(std::size_t(size), 4);
    for (std::size_t x = 0; x < columns.padded; ++x) {
        const float n_dot_v = (float(x < std::size_t(size) ? x : 0) + 0.5f) / float(size);
        columns[0][x] = n_dot_v;
        columns.set3(1, x, glm::vec3(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v));
    }
    tbb::parallel_for(0, size, [&](int y) {
        const float roughness = (float(y) + 0.5f) / float(size);
        const glm::vec3 n(0.0f, 0.0f, 1.0f);
        std::vector<glm::vec3> h(kSampleCount);  // the row's samples: they do not depend on N·V
        for (unsigned i = 0; i < kSampleCount; ++i) h[i] = importance_sample_ggx(hammersley(i, kSampleCount), n, roughness);
        if (simd) {
            Lanes samples(kSampleCount, 3), sums(std::size_t(size), 2);
            for (unsigned i = 0; i < kSampleCount; ++i) samples.set3(0, i, h[i]);
            const BrdfKernelInput in{columns[0], columns[1], columns[2], columns[3], samples[0], samples[1], samples[2],
                                     kSampleCount, roughness};
            brdf_sums(isa, in, columns.padded, sums[0], sums[1]);
            for (int x = 0; x < size; ++x)
                lut.texel(x, y) = {sums[0][x] / float(kSampleCount), sums[1][x] / float(kSampleCount)};
            return;
        }
        for (int x = 0; x < size; ++x) {
            const float n_dot_v = (float(x) + 0.5f) / float(size);
            const glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
            float a = 0.0f, b = 0.0f;
            for (unsigned i = 0; i < kSampleCount; ++i) {
                const glm::vec3 l = glm::normalize(2.0f * glm::dot(v, h[i]) * h[i] - v);
                const float n_dot_l = glm::max(l.z, 0.0f);
                const float n_dot_h = glm::max(h[i].z, 0.0f);
                const float v_dot_h = glm::max(glm::dot(v, h[i]), 0.0f);
                if (n_dot_l > 0.0f) {
                    // GeometrySmith with max(dot(N, V), 0) = V.z and max(dot(N, L), 0) = L.z.
                    const float g = geometry_schlick_ggx_ibl(glm::max(v.z, 0.0f), roughness) *
                                    geometry_schlick_ggx_ibl(n_dot_l, roughness);
                    const float g_vis = (g * v_dot_h) / (n_dot_h * n_dot_v);
                    const float one_minus = 1.0f - v_dot_h;
                    const float one_minus2 = one_minus * one_minus;
                    const float fc = one_minus2 * one_minus2 * one_minus;  // pow(1 − V·H, 5)
                    a += (1.0f - fc) * g_vis;
                    b += fc * g_vis;
                }
            }
            a /= float(kSampleCount);
            b /= float(kSampleCount);
            lut.texel(x, y) = {a, b};
        }
    });
    return lut;
}

EnvironmentMaps precompute_environment(const EquirectImage& image, std::shared_ptr<const BrdfLut> brdf, simd::Isa isa) {
    const CubeMap environment = equirect_to_cubemap(image, kEnvironmentCubeSize);
    EnvironmentMaps maps;
    maps.irradiance = convolve_irradiance(environment, kIrradianceSize, isa);
    maps.prefiltered = prefilter_specular(environment, kPrefilterSize, kPrefilterLevels, isa);
    maps.background = CubeMap(kEnvironmentCubeSize, 1);
    std::copy(environment.data().begin(), environment.data().begin() + std::ptrdiff_t(maps.background.data().size()),
              maps.background.data().begin());
    maps.brdf = std::move(brdf);
    return maps;
}

}  // namespace tessera::environment
