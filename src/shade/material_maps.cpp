#include "shade/material_maps.hpp"

#include <cmath>

#include "shade/pbr_reference.hpp"
#include "shade/material_kernels.hpp"
#include "texture/texture.hpp"

namespace tessera::shade {

namespace {

// normalize(v), or nothing when v has no usable direction (zero, denormal-small or not finite).
bool normalize_if_usable(glm::vec3& v) {
    const float length2 = glm::dot(v, v);
    if (!(length2 > 0.0f && length2 < INFINITY)) return false;
    v *= 1.0f / std::sqrt(length2);
    return true;
}

glm::vec3 apply_frame(const glm::vec3& t, const glm::vec3& b, const glm::vec3& n, const glm::vec3& tangent_normal) {
    return glm::normalize(t * tangent_normal.x + b * tangent_normal.y + n * tangent_normal.z);
}

}  // namespace

// vec3 T = normalize(Q1*st2.t - Q2*st1.t); vec3 B = -normalize(cross(N, T));
glm::vec3 normal_from_map_learnopengl(const glm::vec3& tangent_normal, const glm::vec3& normal, const glm::vec3& dp_dx,
                                      const glm::vec3& dp_dy, const glm::vec2& duv_dx, const glm::vec2& duv_dy) {
    const glm::vec3 n = glm::normalize(normal);
    glm::vec3 t = dp_dx * duv_dy.y - dp_dy * duv_dx.y;
    if (!normalize_if_usable(t)) return n;
    glm::vec3 b = glm::cross(n, t);
    if (!normalize_if_usable(b)) return n;
    return apply_frame(t, -b, n, tangent_normal);
}

// T = ∂P/∂u and ∂P/∂v from the derivatives (the sign of the uv Jacobian
// makes them point along +u and +v), T made orthogonal to N, B = ±cross(N, T)
// pointing along −v.
glm::vec3 normal_from_map_gltf(const glm::vec3& tangent_normal, const glm::vec3& normal, const glm::vec3& dp_dx,
                               const glm::vec3& dp_dy, const glm::vec2& duv_dx, const glm::vec2& duv_dy) {
    const glm::vec3 n = glm::normalize(normal);
    const float det = duv_dx.x * duv_dy.y - duv_dy.x * duv_dx.y;
    const float sign = det < 0.0f ? -1.0f : 1.0f;
    const glm::vec3 dp_du = (dp_dx * duv_dy.y - dp_dy * duv_dx.y) * sign;
    const glm::vec3 dp_dv = (dp_dy * duv_dx.x - dp_dx * duv_dy.x) * sign;
    glm::vec3 t = dp_du - n * glm::dot(n, dp_du);
    if (!normalize_if_usable(t)) return n;
    glm::vec3 b = glm::cross(n, t);
    if (!normalize_if_usable(b)) return n;
    if (glm::dot(b, dp_dv) > 0.0f) b = -b;
    return apply_frame(t, b, n, tangent_normal);
}

glm::vec3 normal_from_map_tangent(const glm::vec3& tangent_normal, const glm::vec3& normal, const glm::vec4& tangent) {
    const glm::vec3 n = glm::normalize(normal);
    glm::vec3 t = glm::vec3(tangent) - n * glm::dot(n, glm::vec3(tangent));
    if (!normalize_if_usable(t)) return n;
    const glm::vec3 b = glm::cross(n, t) * tangent.w;
    return apply_frame(t, b, n, tangent_normal);
}

void MaterialScratch::reserve(std::size_t max_fragments) {
    const std::size_t n = padded_count(max_fragments);
    for (std::vector<float>* v : {&lod, &r, &g, &b, &a}) v->resize(n);
    for (std::vector<float>& v : uv) v.resize(n);
}

texture::Sampler sampler_of(const TextureSlot& slot) {
    const auto wrap = [](TextureWrap w) {
        switch (w) {
            case TextureWrap::clamp_to_edge: return texture::Wrap::clamp_to_edge;
            case TextureWrap::mirrored_repeat: return texture::Wrap::mirrored_repeat;
            case TextureWrap::repeat: break;
        }
        return texture::Wrap::repeat;
    };
    return {wrap(slot.wrap_s), wrap(slot.wrap_t), texture::Filter(int(slot.mag_filter)),
            texture::Filter(int(slot.min_filter))};
}

void transform_uvs(const glm::mat3& m, std::size_t count, const float* const (&in)[6], float* const (&out)[6]) {
    // (u, v) → M·(u, v, 1); a derivative (du, dv) → M's linear part·(du, dv).
    for (std::size_t i = 0; i < count; ++i) {
        const float u = in[0][i], v = in[1][i];
        out[0][i] = m[0][0] * u + m[1][0] * v + m[2][0];
        out[1][i] = m[0][1] * u + m[1][1] * v + m[2][1];
        for (int d = 2; d < 6; d += 2) {
            const float du = in[d][i], dv = in[d + 1][i];
            out[d][i] = m[0][0] * du + m[1][0] * dv;
            out[d + 1][i] = m[0][1] * du + m[1][1] * dv;
        }
    }
}

namespace {


// Samples a run's maps into the scratch channels, skipping a map already
// sampled (glTF's metallic and roughness share one texture) and a level of
// detail already computed for the same texture size.
class RunSampler {
public:
    RunSampler(simd::Isa isa, std::span<const std::shared_ptr<const texture::Texture>> textures,
               const FragmentBuffer& fragments, const MaterialRun& run, MaterialScratch& scratch)
        : isa_(isa), textures_(textures), fragments_(fragments), begin_(run.begin), count_(run.end - run.begin),
          scratch_(scratch) {}

    // Samples channels 0..last_channel (at least) of the slot's texture.
    void sample(const TextureSlot& slot, int last_channel) {
        // The sampler does R, RGB or RGBA.
        const int channels = last_channel == 0 ? 1 : last_channel <= 2 ? 3 : 4;
        const texture::Sampler sampler = sampler_of(slot);
        const UvKey uv_key{slot.uv_set, slot.uv_transformed, slot.uv_transform};
        if (slot.texture == sampled_ && sampler == sampled_sampler_ && uv_key == sampled_uvs_ &&
            channels <= sampled_channels_)
            return;
        const float* const* uvs = uvs_of(uv_key);
        const texture::Texture& texture = *textures_[std::size_t(slot.texture)];
        if (texture.width() != lod_width_ || texture.height() != lod_height_ || !(uv_key == lod_uvs_)) {
            const texture::DerivativeInputs derivatives{count_, uvs[2], uvs[3], uvs[4], uvs[5]};
            texture::lod_from_derivatives(isa_, derivatives, texture.width(), texture.height(), scratch_.lod.data());
            lod_width_ = texture.width(), lod_height_ = texture.height(), lod_uvs_ = uv_key;
        }
        texture::sample(isa_, texture, sampler, {count_, uvs[0], uvs[1], scratch_.lod.data()},
                        {scratch_.r.data(), channels > 1 ? scratch_.g.data() : nullptr,
                         channels > 1 ? scratch_.b.data() : nullptr, channels > 3 ? scratch_.a.data() : nullptr});
        sampled_ = slot.texture, sampled_sampler_ = sampler, sampled_uvs_ = uv_key, sampled_channels_ = channels;
    }
    // The scratch channels were changed in place: the next sample() must refetch.
    void forget() { sampled_ = -1; }
    // The sampled values of channel c; writable, for decoding in place (then forget()).
    float* channel(int c) const {
        std::vector<float>* channels[] = {&scratch_.r, &scratch_.g, &scratch_.b, &scratch_.a};
        return channels[c]->data();
    }
    std::size_t count() const { return count_; }
    const float* at(FragmentBuffer::Channel c) const { return fragments_.channel(c) + begin_; }

private:
    // Which uvs a slot reads (TextureSlot::uv_set, uv_transformed, uv_transform).
    struct UvKey {
        int set = 0;
        bool transformed = false;
        glm::mat3 transform{1.0f};
        bool operator==(const UvKey& o) const {
            return set == o.set && transformed == o.transformed && (!transformed || transform == o.transform);
        }
    };
    // u, v, du/dx, dv/dx, du/dy, dv/dy of a key: the gathered channels, or
    // (transformed) the scratch's, worked out when the key changes.
    const float* const* uvs_of(const UvKey& key) {
        using C = FragmentBuffer;
        const C::Channel first = key.set == 1 ? C::u1 : C::u;
        const C::Channel derivative = key.set == 1 ? C::du1dx : C::dudx;
        for (int k = 0; k < 2; ++k) gathered_[k] = at(C::Channel(first + k));
        for (int k = 0; k < 4; ++k) gathered_[2 + k] = at(C::Channel(derivative + k));
        if (!key.transformed) return gathered_;
        if (!(key == transformed_uvs_)) {
            float* const out[6] = {scratch_.uv[0].data(), scratch_.uv[1].data(), scratch_.uv[2].data(),
                                   scratch_.uv[3].data(), scratch_.uv[4].data(), scratch_.uv[5].data()};
            transform_uvs(key.transform, padded_count(count_), gathered_, out);
            transformed_uvs_ = key;
        }
        for (int k = 0; k < 6; ++k) transformed_[k] = scratch_.uv[std::size_t(k)].data();
        return transformed_;
    }

    const float* gathered_[6] = {};
    const float* transformed_[6] = {};
    UvKey transformed_uvs_{-1};  // what scratch_.uv holds (set −1: nothing yet)
    UvKey sampled_uvs_{-1}, lod_uvs_{};
    simd::Isa isa_;
    std::span<const std::shared_ptr<const texture::Texture>> textures_;
    const FragmentBuffer& fragments_;
    std::size_t begin_, count_;
    MaterialScratch& scratch_;
    std::int32_t sampled_ = -1;
    texture::Sampler sampled_sampler_{};
    int sampled_channels_ = 0;
    int lod_width_ = 0, lod_height_ = 0;
};

void apply_run(simd::Isa isa, std::span<const std::shared_ptr<const texture::Texture>> textures, const MaterialRun& run,
               FragmentBuffer& f, MaterialScratch& scratch) {
    using C = FragmentBuffer;
    const Material& m = *run.material;
    RunSampler sampler(isa, textures, f, run, scratch);
    const std::size_t n = sampler.count();
    const auto out = [&](C::Channel c) { return f.channel(c) + run.begin; };
    // factor × one channel of a map
    const auto scale_channel = [&](const TextureSlot& slot, int channel, float factor, C::Channel target) {
        sampler.sample(slot, channel);
        const float* texel = sampler.channel(channel);
        float* dst = out(target);
        for (std::size_t i = 0; i < n; ++i) dst[i] = factor * texel[i];
    };
    if (m.metallic_map.present()) scale_channel(m.metallic_map, m.metallic_channel, m.metallic, C::metallic);
    if (m.roughness_map.present()) scale_channel(m.roughness_map, m.roughness_channel, m.roughness, C::roughness);
    if (m.ao_map.present()) {
        sampler.sample(m.ao_map, 0);
        const float* texel = sampler.channel(0);
        float* ao = out(C::ao);
        for (std::size_t i = 0; i < n; ++i) ao[i] = m.ao * (1.0f + m.ao_strength * (texel[i] - 1.0f));
    }
    if (m.emissive_map.present()) {
        sampler.sample(m.emissive_map, 2);
        for (int c = 0; c < 3; ++c) scale_channel(m.emissive_map, c, m.emissive[c], C::Channel(C::emissive_r + c));
    }
    if (m.normal_map.present()) {
        sampler.sample(m.normal_map, 2);
        NormalMapBatch batch;
        batch.count = n;
        batch.scale = m.normal_scale;
        for (int k = 0; k < 3; ++k) {
            batch.map[k] = sampler.channel(k);
            batch.dp_dx[k] = sampler.at(C::Channel(C::dpdx_x + k));
            batch.dp_dy[k] = sampler.at(C::Channel(C::dpdy_x + k));
            batch.normal[k] = out(C::Channel(C::normal_x + k));
        }
        for (int k = 0; k < 2; ++k) {
            batch.duv_dx[k] = sampler.at(C::Channel(C::dudx + k));
            batch.duv_dy[k] = sampler.at(C::Channel(C::dudy + k));
        }
        for (int k = 0; k < 4; ++k) batch.tangent[k] = sampler.at(C::Channel(C::tangent_x + k));
        perturb_normals(isa, batch, m.derived_tangent_frame);
    }
    // Last: the power changes the sampled values in place.
    if (m.albedo_map.present()) {
        const bool blended = m.alpha_mode == AlphaMode::blend;
        sampler.sample(m.albedo_map, blended ? 3 : 2);
        float* texel[] = {sampler.channel(0), sampler.channel(1), sampler.channel(2)};
        if (m.albedo_decode == AlbedoDecode::pow_2_2_after_filter) {
            pow_2_2(isa, n, texel[0], texel[1], texel[2]);
            sampler.forget();
        }
        // The gathered albedo is the factor (× the vertex colour): for meshes
        // without colours, factor × texel exactly as before.
        for (int c = 0; c < 3; ++c) {
            float* dst = out(C::Channel(C::albedo_r + c));
            for (std::size_t i = 0; i < n; ++i) dst[i] *= texel[c][i];
        }
        if (blended) {
            const float* texel_alpha = sampler.channel(3);
            float* alpha = out(C::alpha);
            for (std::size_t i = 0; i < n; ++i) alpha[i] *= texel_alpha[i];
        }
    }
}

}  // namespace

void apply_material_maps(simd::Isa isa, std::span<const std::shared_ptr<const texture::Texture>> textures,
                         std::span<const MaterialRun> runs, FragmentBuffer& fragments, MaterialScratch& scratch) {
    for (const MaterialRun& run : runs)
        if (run.textured && run.end > run.begin) apply_run(isa, textures, run, fragments, scratch);
}

void apply_unlit(std::span<const MaterialRun> runs, FragmentBuffer& f) {
    using C = FragmentBuffer;
    for (const MaterialRun& run : runs) {
        const Material& m = *run.material;
        if (!m.unlit) continue;
        // A plain run's albedo channels may be unfilled (the fast gather): its albedo is the material's.
        const glm::vec3 plain = radiance_for_display(m.albedo);
        for (std::size_t i = run.begin; i < run.end; ++i) {
            const glm::vec3 radiance =
                run.plain ? plain
                          : radiance_for_display({f.channel(C::albedo_r)[i], f.channel(C::albedo_g)[i],
                                                  f.channel(C::albedo_b)[i]});
            for (int c = 0; c < 3; ++c) f.channel(C::Channel(C::out_r + c))[i] = radiance[c];
        }
    }
}

void add_emission(std::span<const MaterialRun> runs, FragmentBuffer& f) {
    using C = FragmentBuffer;
    for (const MaterialRun& run : runs) {
        const Material& m = *run.material;
        if (m.emissive == glm::vec3(0.0f)) continue;
        for (int c = 0; c < 3; ++c) {
            float* radiance = f.channel(C::Channel(C::out_r + c)) + run.begin;
            const std::size_t n = run.end - run.begin;
            if (m.emissive_map.present()) {
                const float* emission = f.channel(C::Channel(C::emissive_r + c)) + run.begin;
                for (std::size_t i = 0; i < n; ++i) radiance[i] += emission[i];
            } else {
                for (std::size_t i = 0; i < n; ++i) radiance[i] += m.emissive[c];
            }
        }
    }
}

// Defined in material_kernels_simd.cpp, once per ISA.
#define TESSERA_DECLARE_MATERIAL_ENTRIES(suffix)                                        \
    void pow_2_2_##suffix(std::size_t count, float* r, float* g, float* b);             \
    void perturb_normals_##suffix(const NormalMapBatch& batch, DerivedTangentFrame frame);
TESSERA_DECLARE_MATERIAL_ENTRIES(sse4)
TESSERA_DECLARE_MATERIAL_ENTRIES(avx2)
TESSERA_DECLARE_MATERIAL_ENTRIES(avx512)
#undef TESSERA_DECLARE_MATERIAL_ENTRIES

void pow_2_2(simd::Isa isa, std::size_t count, float* r, float* g, float* b) {
    simd::require_supported(isa);
    switch (isa) {
        case simd::Isa::scalar:
            for (float* channel : {r, g, b})
                for (std::size_t i = 0; i < count; ++i) channel[i] = std::pow(channel[i], 2.2f);
            return;
        case simd::Isa::sse4: return pow_2_2_sse4(count, r, g, b);
        case simd::Isa::avx2: return pow_2_2_avx2(count, r, g, b);
        case simd::Isa::avx512: return pow_2_2_avx512(count, r, g, b);
    }
}

void perturb_normals(simd::Isa isa, const NormalMapBatch& batch, DerivedTangentFrame frame) {
    simd::require_supported(isa);
    switch (isa) {
        case simd::Isa::scalar:
            for (std::size_t i = 0; i < batch.count; ++i) {
                const auto load3 = [i](const float* const a[3]) { return glm::vec3(a[0][i], a[1][i], a[2][i]); };
                const auto load2 = [i](const float* const a[2]) { return glm::vec2(a[0][i], a[1][i]); };
                glm::vec3 tangent_normal = load3(batch.map) * 2.0f - 1.0f;
                tangent_normal.x *= batch.scale, tangent_normal.y *= batch.scale;
                const glm::vec3 normal(batch.normal[0][i], batch.normal[1][i], batch.normal[2][i]);
                const glm::vec4 tangent(batch.tangent[0][i], batch.tangent[1][i], batch.tangent[2][i], batch.tangent[3][i]);
                glm::vec3 result;
                if (tangent.w != 0.0f) {
                    result = normal_from_map_tangent(tangent_normal, normal, tangent);
                } else if (frame == DerivedTangentFrame::gltf) {
                    result = normal_from_map_gltf(tangent_normal, normal, load3(batch.dp_dx), load3(batch.dp_dy),
                                                  load2(batch.duv_dx), load2(batch.duv_dy));
                } else {
                    result = normal_from_map_learnopengl(tangent_normal, normal, load3(batch.dp_dx), load3(batch.dp_dy),
                                                         load2(batch.duv_dx), load2(batch.duv_dy));
                }
                for (int k = 0; k < 3; ++k) batch.normal[k][i] = result[k];
            }
            return;
        case simd::Isa::sse4: return perturb_normals_sse4(batch, frame);
        case simd::Isa::avx2: return perturb_normals_avx2(batch, frame);
        case simd::Isa::avx512: return perturb_normals_avx512(batch, frame);
    }
}

}  // namespace tessera::shade
