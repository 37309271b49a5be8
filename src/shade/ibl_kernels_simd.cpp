// The IBL ambient term (ibl_reference.cpp) over xsimd batches, one fragment a
// lane, compiled once per ISA. Every operation is the reference's, in its
// order, without contraction (src/shade/CMakeLists.txt): the kernels give the
// reference's bits. Cube map taps are hardware gathers of the seamless,
// bordered faces (environment/cube_map.hpp); the face, texel and level of
// each tap are worked out per lane, in float (every index is an integer
// below 2^24, so exact).
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "shade/ibl_reference.hpp"
#include "shade/shade_kernels.hpp"
#include "environment/cube_map_simd.hpp"
#include "simd/hardware_gather.hpp"

namespace tessera::shade {
namespace {

using namespace environment::cube_simd;
using Int = xsimd::batch<std::int32_t, Arch>;

// CubeMap::sample_trilinear (levels >= 2).
V3 sample_trilinear(const CubeArrays& cube, const V3& d, const Batch& lod) {
    const Face c = face_coords(d);
    const float top_level = float(cube.levels - 1);
    const Batch clamped = xsimd::min(xsimd::max(lod, Batch(0.0f)), Batch(top_level));
    const Batch l0 = xsimd::min(xsimd::floor(clamped), Batch(top_level - 1.0f));
    const Batch f = clamped - l0;
    const Batch l1 = l0 + Batch(1.0f);
#if defined(__AVX512F__)
    // One material's fragments mostly share a roughness, so a level: the windowed taps.
    float level;
    if (lanes_uniform(l0, level)) {
        const int l = int(level);
        const V3 a = sample_bilinear_level(cube.texels, cube.float_count, c, cube.size[l], cube.offset[l]);
        const V3 b = sample_bilinear_level(cube.texels, cube.float_count, c, cube.size[l + 1], cube.offset[l + 1]);
        return a + (b - a) * f;
    }
#endif
    const V3 a = sample_bilinear(cube.texels, c, gather(cube.size, l0), gather(cube.offset, l0));
    const V3 b = sample_bilinear(cube.texels, c, gather(cube.size, l1), gather(cube.offset, l1));
    return a + (b - a) * f;
}

// BrdfLut::sample.
void sample_brdf(const IblArrays& ibl, const Batch& u, const Batch& v, Batch& a, Batch& b) {
    const Batch size(ibl.brdf_size);
    const Batch x = u * size - Batch(0.5f), y = v * size - Batch(0.5f);
    const Batch x0f = xsimd::floor(x), y0f = xsimd::floor(y);
    const Batch fx = x - x0f, fy = y - y0f;
    const Batch last = size - Batch(1.0f), zero(0.0f);
    const Batch x0 = xsimd::min(xsimd::max(x0f, zero), last), x1 = xsimd::min(xsimd::max(x0f + Batch(1.0f), zero), last);
    const Batch y0 = xsimd::min(xsimd::max(y0f, zero), last), y1 = xsimd::min(xsimd::max(y0f + Batch(1.0f), zero), last);
    const auto tap = [&](const Batch& tx, const Batch& ty, Batch& ra, Batch& rb) {
        const Batch index = Batch(2.0f) * (ty * size + tx);
        gather_float_pair(ibl.brdf, index, ra, rb);
    };
    Batch a00, b00, a10, b10, a01, b01, a11, b11;
    tap(x0, y0, a00, b00), tap(x1, y0, a10, b10), tap(x0, y1, a01, b01), tap(x1, y1, a11, b11);
    const Batch top_a = a00 + (a10 - a00) * fx, top_b = b00 + (b10 - b00) * fx;
    const Batch bottom_a = a01 + (a11 - a01) * fx, bottom_b = b01 + (b11 - b01) * fx;
    a = top_a + (bottom_a - top_a) * fy;
    b = top_b + (bottom_b - top_b) * fy;
}

V3 environment_direction(const IblArrays& ibl, const V3& d) {
    const Batch c(ibl.cos_rotation), s(ibl.sin_rotation);
    return {c * d.x - s * d.z, d.y, s * d.x + c * d.z};
}

void ambient_batch(const FragmentInputs& in, std::size_t i, const V3& cam, const IblArrays& ibl,
                   const RadianceOutputs& out) {
    const V3 world = load3(in.world_x, in.world_y, in.world_z, i);
    const V3 n = normalize(load3(in.normal_x, in.normal_y, in.normal_z, i));
    const V3 v = normalize(cam - world);
    const V3 albedo = load3(in.albedo_r, in.albedo_g, in.albedo_b, i);
    const Batch metallic = xsimd::load_unaligned(in.metallic + i);
    const Batch roughness = xsimd::load_unaligned(in.roughness + i);
    const Batch ao = xsimd::load_unaligned(in.ao + i);
    const Batch base(0.04f);
    const Batch keep = Batch(1.0f) - metallic;  // glm::mix(x, y, a) = x·(1 − a) + y·a
    const V3 f0 = {base * keep + albedo.x * metallic, base * keep + albedo.y * metallic, base * keep + albedo.z * metallic};
    const Batch n_dot_v = xsimd::max(dot(n, v), Batch(0.0f));
    const V3 minus_v = {-v.x, -v.y, -v.z};
    const Batch twice = Batch(2.0f) * dot(n, minus_v);
    const V3 r = minus_v - n * twice;

    const Batch x = xsimd::min(xsimd::max(Batch(1.0f) - n_dot_v, Batch(0.0f)), Batch(1.0f));
    const Batch x2 = x * x;
    const Batch w = x2 * x2 * x;
    const Batch one_minus_rough = Batch(1.0f) - roughness;
    // glm::max(a, b) is a < b ? b : a.
    const auto gmax = [](const Batch& a, const Batch& b) { return xsimd::select(a < b, b, a); };
    const V3 f = {f0.x + (gmax(one_minus_rough, f0.x) - f0.x) * w, f0.y + (gmax(one_minus_rough, f0.y) - f0.y) * w,
                  f0.z + (gmax(one_minus_rough, f0.z) - f0.z) * w};
    const Batch one(1.0f), diffuse_weight = one - metallic;
    const V3 k_d = {(one - f.x) * diffuse_weight, (one - f.y) * diffuse_weight, (one - f.z) * diffuse_weight};

    const Batch intensity(ibl.intensity);
    const Face nc = face_coords(environment_direction(ibl, n));
    const V3 irradiance = sample_bilinear_level(ibl.irradiance.texels, ibl.irradiance.float_count, nc,
                                                ibl.irradiance.size[0], ibl.irradiance.offset[0]) * intensity;
    const V3 diffuse = irradiance * albedo;
    const V3 prefiltered =
        sample_trilinear(ibl.prefiltered, environment_direction(ibl, r), roughness * Batch(environment::kMaxReflectionLod)) *
        intensity;
    Batch brdf_a, brdf_b;
    sample_brdf(ibl, n_dot_v, roughness, brdf_a, brdf_b);
    const V3 specular = {prefiltered.x * (f.x * brdf_a + brdf_b), prefiltered.y * (f.y * brdf_a + brdf_b),
                         prefiltered.z * (f.z * brdf_a + brdf_b)};
    const V3 ambient = (k_d * diffuse + specular) * ao;
    (ambient.x + xsimd::load_unaligned(out.r + i)).store_unaligned(out.r + i);
    (ambient.y + xsimd::load_unaligned(out.g + i)).store_unaligned(out.g + i);
    (ambient.z + xsimd::load_unaligned(out.b + i)).store_unaligned(out.b + i);
}

}  // namespace

void TESSERA_SIMD_ENTRY(add_ibl_ambient)(const FragmentInputs& in, const glm::vec3& cam_pos, const IblArrays& ibl,
                                         const RadianceOutputs& out) {
    const V3 cam = {Batch(cam_pos.x), Batch(cam_pos.y), Batch(cam_pos.z)};
    const std::size_t end = padded_count(in.count);
    for (std::size_t i = 0; i < end; i += Batch::size) ambient_batch(in, i, cam, ibl, out);
}

}  // namespace tessera::shade

namespace tessera::shade {

void TESSERA_SIMD_ENTRY(sample_environment_background)(std::size_t count, const float* x, const float* y,
                                                       const float* z, const CubeArrays& cube, const IblArrays& ibl,
                                                       float scale, const RadianceOutputs& out) {
    const std::size_t end = padded_count(count);
    const Batch intensity(ibl.intensity);
    for (std::size_t i = 0; i < end; i += Batch::size) {
        const Face c = face_coords(environment_direction(ibl, load3(x, y, z, i)));
        V3 value = sample_bilinear_level(cube.texels, cube.float_count, c, cube.size[0], cube.offset[0]) * intensity;
        if (scale != 1.0f) value = value * Batch(scale);
        value.x.store_unaligned(out.r + i), value.y.store_unaligned(out.g + i), value.z.store_unaligned(out.b + i);
    }
}

void TESSERA_SIMD_ENTRY(sample_environment_background_row)(std::size_t count, const float* column,
                                                           const BackgroundRays& rays, const CubeArrays& cube,
                                                           const IblArrays& ibl, float scale, const RadianceOutputs& out) {
    const std::size_t end = padded_count(count);
    const Batch intensity(ibl.intensity), width(rays.width), ndc_y(rays.ndc_y);
    const V3 forward{Batch(rays.forward.x), Batch(rays.forward.y), Batch(rays.forward.z)};
    const V3 right{Batch(rays.right.x), Batch(rays.right.y), Batch(rays.right.z)};
    const V3 up{Batch(rays.up.x), Batch(rays.up.y), Batch(rays.up.z)};
    for (std::size_t i = 0; i < end; i += Batch::size) {
        // background_ray, operation for operation.
        const Batch ndc_x = Batch(2.0f) * (xsimd::load_unaligned(column + i) + Batch(0.5f)) / width - Batch(1.0f);
        const V3 d = (forward + right * ndc_x) + up * ndc_y;
        const Face c = face_coords(environment_direction(ibl, d));
        V3 value = sample_bilinear_level(cube.texels, cube.float_count, c, cube.size[0], cube.offset[0]) * intensity;
        if (scale != 1.0f) value = value * Batch(scale);
        value.x.store_unaligned(out.r + i), value.y.store_unaligned(out.g + i), value.z.store_unaligned(out.b + i);
    }
}

}  // namespace tessera::shade
