#include "environment/precompute.hpp"

#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

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

CubeMap convolve_irradiance(const CubeMap& environment, int size) {
    // The two loops' samples, counted in float as the shader's loops count.
    struct Sample {
        glm::vec3 tangent;  // (sin θ cos φ, sin θ sin φ, cos θ)
        float cos_theta, sin_theta;
    };
    std::vector<Sample> samples;
    for (float phi = 0.0f; phi < 2.0f * kPi; phi += kSampleDelta)
        for (float theta = 0.0f; theta < 0.5f * kPi; theta += kSampleDelta)
            samples.push_back({{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)},
                               std::cos(theta), std::sin(theta)});
    const float nr_samples = float(samples.size());
    const int level = int(kIrradianceLod);
    CubeMap cube(size, 1);
    for_each_texel(cube, 0, [&](int face, int x, int y) {
        const glm::vec3 n = glm::normalize(texel_direction(face, x, y, size));
        glm::vec3 irradiance(0.0f);
        glm::vec3 up(0.0f, 1.0f, 0.0f);
        const glm::vec3 right = glm::cross(up, n);  // not normalized, as in the chapter
        up = glm::cross(n, right);
        for (const Sample& s : samples) {
            const glm::vec3 sample_vec = s.tangent.x * right + s.tangent.y * up + s.tangent.z * n;
            irradiance += environment.sample_bilinear(sample_vec, level) * s.cos_theta * s.sin_theta;
        }
        cube.texel(0, face, x, y) = kPi * irradiance * (1.0f / nr_samples);
    });
    cube.fill_borders(0);
    return cube;
}

CubeMap prefilter_specular(const CubeMap& environment, int size, int levels) {
    CubeMap cube(size, levels);
    const float resolution = float(environment.size(0));  // of the source cubemap, per face
    const float sa_texel = 4.0f * kPi / (6.0f * resolution * resolution);
    for (int mip = 0; mip < levels; ++mip) {
        const float roughness = float(mip) / float(levels - 1);
        const int n = cube.size(mip);
        // The mip level each sample reads depends only on the sample and the
        // roughness (N = V = R makes D, N·H and H·V the tangent-space H's cos θ),
        // so it is worked out once per level from the tangent-space sample.
        std::vector<float> sample_lod(kSampleCount);
        std::vector<glm::vec3> tangent_h(kSampleCount);
        for (unsigned i = 0; i < kSampleCount; ++i) {
            const glm::vec3 z(0.0f, 0.0f, 1.0f);
            tangent_h[i] = ggx_sample_tangent(hammersley(i, kSampleCount), roughness);
            const glm::vec3 h = tangent_h[i];
            const float d = distribution_ggx(z, h, roughness);
            const float n_dot_h = glm::max(h.z, 0.0f);
            const float h_dot_v = glm::max(h.z, 0.0f);
            const float pdf = d * n_dot_h / (4.0f * h_dot_v) + 0.0001f;
            const float sa_sample = 1.0f / (float(kSampleCount) * pdf + 0.0001f);
            sample_lod[i] = roughness == 0.0f ? 0.0f : 0.5f * std::log2(sa_sample / sa_texel);
        }
        for_each_texel(cube, mip, [&](int face, int x, int y) {
            const glm::vec3 normal = glm::normalize(texel_direction(face, x, y, n));
            const glm::vec3 r = normal, v = r;
            if (roughness == 0.0f) {  // every sample is H = L = N at level 0: the sum of equal terms
                cube.texel(mip, face, x, y) = environment.sample_trilinear(normal, 0.0f);
                return;
            }
            glm::vec3 prefiltered(0.0f);
            float total_weight = 0.0f;
            // sample_to_world's frame, once per texel (the same operations).
            const glm::vec3 up = std::fabs(normal.z) < 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
            const glm::vec3 tangent = glm::normalize(glm::cross(up, normal));
            const glm::vec3 bitangent = glm::cross(normal, tangent);
            for (unsigned i = 0; i < kSampleCount; ++i) {
                const glm::vec3& ht = tangent_h[i];
                const glm::vec3 h = glm::normalize(tangent * ht.x + bitangent * ht.y + normal * ht.z);
                const glm::vec3 l = glm::normalize(2.0f * glm::dot(v, h) * h - v);
                const float n_dot_l = glm::max(glm::dot(normal, l), 0.0f);
                if (n_dot_l > 0.0f) {
                    prefiltered += environment.sample_trilinear(l, sample_lod[i]) * n_dot_l;
                    total_weight += n_dot_l;
                }
            }
            cube.texel(mip, face, x, y) = prefiltered / total_weight;
        });
        cube.fill_borders(mip);
    }
    return cube;
}

BrdfLut integrate_brdf(int size) {
    BrdfLut lut(size);
    tbb::parallel_for(0, size, [&](int y) {
        const float roughness = (float(y) + 0.5f) / float(size);
        const glm::vec3 n(0.0f, 0.0f, 1.0f);
        std::vector<glm::vec3> h(kSampleCount);  // the row's samples: they do not depend on N·V
        for (unsigned i = 0; i < kSampleCount; ++i) h[i] = importance_sample_ggx(hammersley(i, kSampleCount), n, roughness);
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

EnvironmentMaps precompute_environment(const EquirectImage& image, std::shared_ptr<const BrdfLut> brdf) {
    const CubeMap environment = equirect_to_cubemap(image, kEnvironmentCubeSize);
    EnvironmentMaps maps;
    maps.irradiance = convolve_irradiance(environment, kIrradianceSize);
    maps.prefiltered = prefilter_specular(environment, kPrefilterSize, kPrefilterLevels);
    maps.background = CubeMap(kEnvironmentCubeSize, 1);
    std::copy(environment.data().begin(), environment.data().begin() + std::ptrdiff_t(maps.background.data().size()),
              maps.background.data().begin());
    maps.brdf = std::move(brdf);
    return maps;
}

}  // namespace tessera::environment
