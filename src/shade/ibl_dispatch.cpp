// Run-time choice of the IBL kernels (ibl_kernels_simd.cpp), and the scalar loop.
#include "shade/ibl_reference.hpp"

namespace tessera::shade {

#define TESSERA_DECLARE_IBL_ENTRY(suffix)                                                                \
    void add_ibl_ambient_##suffix(const FragmentInputs& in, const glm::vec3& cam_pos, const IblArrays& ibl, \
                                  const RadianceOutputs& out);                                             \
    void sample_environment_background_##suffix(std::size_t count, const float* x, const float* y, const float* z, \
                                                const CubeArrays& cube, const IblArrays& ibl, float scale,       \
                                                const RadianceOutputs& out);                        \
    void sample_environment_background_row_##suffix(std::size_t count, const float* column,                   \
                                                    const BackgroundRays& rays, const CubeArrays& cube,       \
                                                    const IblArrays& ibl, float scale, const RadianceOutputs& out);
TESSERA_DECLARE_IBL_ENTRY(sse4)
TESSERA_DECLARE_IBL_ENTRY(avx2)
TESSERA_DECLARE_IBL_ENTRY(avx512)
#undef TESSERA_DECLARE_IBL_ENTRY

namespace {

CubeArrays cube_arrays(const environment::CubeMap& cube) {
    CubeArrays arrays;
    arrays.texels = &cube.data().front().x;
    arrays.float_count = 3 * cube.data().size();
    arrays.levels = cube.levels();
    for (int l = 0; l < cube.levels() && l < 8; ++l)
        arrays.size[l] = float(cube.size(l)), arrays.offset[l] = float(cube.level_offset(l));
    return arrays;
}

glm::vec3 load_vec3(const float* x, const float* y, const float* z, std::size_t i) { return {x[i], y[i], z[i]}; }

}  // namespace

void add_ibl_ambient(Isa isa, const FragmentInputs& in, const glm::vec3& cam_pos, const IblLighting& ibl,
                     const RadianceOutputs& out) {
    simd::require_supported(isa);
    if (isa == Isa::scalar) {
        for (std::size_t i = 0; i < in.count; ++i) {
            const Material material{.albedo = load_vec3(in.albedo_r, in.albedo_g, in.albedo_b, i),
                                    .metallic = in.metallic[i], .roughness = in.roughness[i], .ao = in.ao[i]};
            const ShadingPoint p = shading_point(load_vec3(in.world_x, in.world_y, in.world_z, i),
                                                 load_vec3(in.normal_x, in.normal_y, in.normal_z, i), material, cam_pos);
            const glm::vec3 ambient = ambient_radiance_ibl(p, ibl);
            out.r[i] = ambient.r + out.r[i], out.g[i] = ambient.g + out.g[i], out.b[i] = ambient.b + out.b[i];
        }
        return;
    }
    const IblArrays arrays{cube_arrays(ibl.maps->irradiance), cube_arrays(ibl.maps->prefiltered),
                           &ibl.maps->brdf->data().front().x, float(ibl.maps->brdf->size()), ibl.intensity,
                           ibl.cos_rotation, ibl.sin_rotation};
    switch (isa) {
        case Isa::scalar: break;
        case Isa::sse4: return add_ibl_ambient_sse4(in, cam_pos, arrays, out);
        case Isa::avx2: return add_ibl_ambient_avx2(in, cam_pos, arrays, out);
        case Isa::avx512: return add_ibl_ambient_avx512(in, cam_pos, arrays, out);
    }
}

namespace {

// The scalar reference of both background entry points: ray_of(i) is pixel i's view ray.
template <class RayOf>
void background_scalar(std::size_t count, RayOf ray_of, const IblLighting& ibl, float scale, const RadianceOutputs& out) {
    for (std::size_t i = 0; i < count; ++i) {
        glm::vec3 value = environment_background(ibl, ray_of(i));
        if (scale != 1.0f) value = value * scale;
        out.r[i] = value.r, out.g[i] = value.g, out.b[i] = value.b;
    }
}

IblArrays background_arrays(const IblLighting& ibl) {
    IblArrays arrays{};
    arrays.intensity = ibl.intensity, arrays.cos_rotation = ibl.cos_rotation, arrays.sin_rotation = ibl.sin_rotation;
    return arrays;
}

}  // namespace

void sample_environment_background(Isa isa, std::size_t count, const float* x, const float* y, const float* z,
                                   const IblLighting& ibl, float scale, const RadianceOutputs& out) {
    simd::require_supported(isa);
    if (isa == Isa::scalar)
        return background_scalar(count, [&](std::size_t i) { return load_vec3(x, y, z, i); }, ibl, scale, out);
    const CubeArrays cube = cube_arrays(ibl.maps->background);
    const IblArrays arrays = background_arrays(ibl);
    switch (isa) {
        case Isa::scalar: break;
        case Isa::sse4: return sample_environment_background_sse4(count, x, y, z, cube, arrays, scale, out);
        case Isa::avx2: return sample_environment_background_avx2(count, x, y, z, cube, arrays, scale, out);
        case Isa::avx512: return sample_environment_background_avx512(count, x, y, z, cube, arrays, scale, out);
    }
}

void sample_environment_background_row(Isa isa, std::size_t count, const float* column, const BackgroundRays& rays,
                                       const IblLighting& ibl, float scale, const RadianceOutputs& out) {
    simd::require_supported(isa);
    if (isa == Isa::scalar)
        return background_scalar(count, [&](std::size_t i) { return background_ray(rays, column[i]); }, ibl, scale, out);
    const CubeArrays cube = cube_arrays(ibl.maps->background);
    const IblArrays arrays = background_arrays(ibl);
    switch (isa) {
        case Isa::scalar: break;
        case Isa::sse4: return sample_environment_background_row_sse4(count, column, rays, cube, arrays, scale, out);
        case Isa::avx2: return sample_environment_background_row_avx2(count, column, rays, cube, arrays, scale, out);
        case Isa::avx512: return sample_environment_background_row_avx512(count, column, rays, cube, arrays, scale, out);
    }
}

}  // namespace tessera::shade
