// tessera_make_textures OUT_DIR [--compare COMMITTED_DIR]
//
// The set is committed (scenes/textures/rust/), so that a build writes nothing
// into the source tree and the textured demo renders from a fresh clone. The
// test tools.make_textures_matches_committed makes it again into the build
// folder and, with --compare, checks every texel against the committed files.
// After changing this generator, remake them:
//   build/tessera_make_textures scenes/textures/rust
//
// Writes the rusted-metal texture set of the textured demo
// (docs/reference/pbr_lighting.md, "Textured variant"), 512×512 8-bit PNGs:
//   albedo.png     RGB, sRGB-encoded base colour (load with ColorSpace::srgb)
//   metallic.png   grey, linear
//   roughness.png  grey, linear
//   ao.png         grey, linear
//   normal.png     RGB, tangent space, n·0.5 + 0.5, linear
// Everything derives from one rust mask, so the maps agree: rust is rough,
// non-metallic, orange-brown, raised and occluded in its pits; bare metal is
// smoother, metallic, grey, with fine brushed scratches.
//
// Deterministic: value noise over an integer hash with a fixed seed (no
// <random> distributions, whose output differs between standard libraries),
// and every noise is periodic over the image, so the textures tile under
// GL_REPEAT with no seam.
//
// Normal map convention (OpenGL's and glTF's): +x (red) along +u (right), +y
// (green) up the image, towards row 0, i.e. along −v (tessera's Texture
// stores row 0 at v = 0). On the demo's sphere (u round the equator, v from
// pole to pole) the reference's derivative-based getNormalFromMap builds
// exactly that frame: T = ∂P/∂u, B = −cross(N, T) = −∂P/∂v.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace {

constexpr int kSize = 512;
constexpr std::uint32_t kSeed = 0x7e55e4a5u;

// A 32-bit integer hash (Chris Wellons' lowbias32) of a lattice point and a
// channel, to [0, 1).
std::uint32_t hash32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

float lattice(int x, int y, std::uint32_t channel) {
    const std::uint32_t h = hash32(static_cast<std::uint32_t>(x) * 0x9e3779b1u ^ hash32(static_cast<std::uint32_t>(y) ^
                                                                                       hash32(channel ^ kSeed)));
    return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

float smooth(float t) { return t * t * (3.0f - 2.0f * t); }

int wrap(int i, int period) { return ((i % period) + period) % period; }

// Value noise at (u, v) in [0, 1)², with `cells_x` × `cells_y` lattice cells
// over the image; periodic in u and v. Range [0, 1].
float value_noise(float u, float v, int cells_x, int cells_y, std::uint32_t channel) {
    const float x = u * static_cast<float>(cells_x), y = v * static_cast<float>(cells_y);
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const float tx = smooth(x - static_cast<float>(x0)), ty = smooth(y - static_cast<float>(y0));
    const auto at = [&](int i, int j) { return lattice(wrap(i, cells_x), wrap(j, cells_y), channel); };
    const float top = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * tx;
    const float bottom = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * tx;
    return top + (bottom - top) * ty;
}

// Fractal sum of `octaves` value noises, each twice the frequency and half the
// amplitude of the last; normalized to [0, 1].
float fbm(float u, float v, int cells_x, int cells_y, int octaves, std::uint32_t channel) {
    float sum = 0.0f, amplitude = 1.0f, total = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * value_noise(u, v, cells_x << o, cells_y << o, channel + static_cast<std::uint32_t>(o) * 101u);
        total += amplitude;
        amplitude *= 0.5f;
    }
    return sum / total;
}

float smoothstep(float edge0, float edge1, float x) { return smooth(std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f)); }
float mix(float a, float b, float t) { return a + (b - a) * t; }

float linear_to_srgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

struct Maps {
    std::vector<float> albedo, metallic, roughness, ao, normal, height;
};

Maps generate() {
    const std::size_t n = static_cast<std::size_t>(kSize) * kSize;
    Maps maps;
    maps.albedo.resize(n * 3);
    maps.normal.resize(n * 3);
    for (std::vector<float>* grey : {&maps.metallic, &maps.roughness, &maps.ao, &maps.height}) grey->resize(n);
    std::vector<float> rust_mask(n), pits(n);

    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * kSize + x;
            const float u = (static_cast<float>(x) + 0.5f) / kSize, v = (static_cast<float>(y) + 0.5f) / kSize;

            // Rust patches: broad fBm thresholded, edges roughened by a finer fBm.
            const float broad = fbm(u, v, 4, 4, 5, 1);
            const float ragged = fbm(u, v, 16, 16, 4, 2);
            const float rust = smoothstep(0.50f, 0.60f, broad + 0.22f * (ragged - 0.5f));
            // Inside the rust: flaky grain and pits.
            const float grain = fbm(u, v, 32, 32, 4, 3);
            const float pit = smoothstep(0.62f, 0.78f, fbm(u, v, 24, 24, 3, 4));
            // Bare metal: brushed scratches, noise stretched along u.
            const float brushed = fbm(u, v, 2, 128, 3, 5);
            const float tint = fbm(u, v, 8, 8, 3, 6);  // colour variation of the rust

            rust_mask[i] = rust;
            pits[i] = pit * rust;

            // Linear base colour. Metal: a slightly varying steel grey; rust:
            // dark brown to orange, darker in pits.
            const float steel = 0.52f + 0.10f * (brushed - 0.5f) + 0.05f * (tint - 0.5f);
            const float orange = smoothstep(0.35f, 0.65f, tint * 0.55f + grain * 0.45f);
            const float rust_dark = 1.0f - 0.6f * pit;
            const float rust_r = mix(0.10f, 0.44f, orange) * rust_dark;
            const float rust_g = mix(0.035f, 0.15f, orange) * rust_dark;
            const float rust_b = mix(0.015f, 0.035f, orange) * rust_dark;
            maps.albedo[i * 3 + 0] = mix(steel, rust_r, rust);
            maps.albedo[i * 3 + 1] = mix(steel * 1.005f, rust_g, rust);
            maps.albedo[i * 3 + 2] = mix(steel * 1.02f, rust_b, rust);

            maps.metallic[i] = mix(0.95f + 0.05f * brushed, 0.02f + 0.06f * grain, rust);
            maps.roughness[i] = mix(0.22f + 0.18f * brushed, 0.78f + 0.18f * grain, rust);
            // Rust stands proud of the metal, grainy, with pits into it.
            maps.height[i] = 0.5f * rust + rust * (0.35f * grain - 0.4f * pit) + (1.0f - rust) * 0.04f * brushed;
        }
    }

    // Normals from the height field by central differences (wrapping: the set
    // tiles). kBump: height units per texel of slope at full strength.
    constexpr float kBump = 6.0f;
    const auto height_at = [&](int x, int y) {
        return maps.height[static_cast<std::size_t>(wrap(y, kSize)) * kSize + wrap(x, kSize)];
    };
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * kSize + x;
            const float dh_du = (height_at(x + 1, y) - height_at(x - 1, y)) * 0.5f * kBump;
            const float dh_dv = (height_at(x, y + 1) - height_at(x, y - 1)) * 0.5f * kBump;
            const float inv_length = 1.0f / std::sqrt(dh_du * dh_du + dh_dv * dh_dv + 1.0f);
            maps.normal[i * 3 + 0] = -dh_du * inv_length * 0.5f + 0.5f;
            maps.normal[i * 3 + 1] = dh_dv * inv_length * 0.5f + 0.5f;  // green up: along −v
            maps.normal[i * 3 + 2] = inv_length * 0.5f + 0.5f;

            // Ambient occlusion: pits and the rust's grain hold less sky; bare metal is open.
            const float local = height_at(x, y);
            const float around = 0.25f * (height_at(x + 2, y) + height_at(x - 2, y) + height_at(x, y + 2) +
                                          height_at(x, y - 2));
            const float cavity = std::max(0.0f, around - local);
            maps.ao[i] = std::clamp(1.0f - 0.35f * pits[i] - 4.0f * cavity - 0.08f * rust_mask[i], 0.0f, 1.0f);
        }
    }
    return maps;
}

constexpr const char* kMapNames[] = {"albedo.png", "metallic.png", "roughness.png", "ao.png", "normal.png"};

void write(const std::filesystem::path& path, int channels, const std::vector<float>& pixels) {
    OIIO::ImageBuf buffer(OIIO::ImageSpec(kSize, kSize, channels, OIIO::TypeDesc::FLOAT),
                          const_cast<float*>(pixels.data()));
    if (!buffer.write(path.string(), OIIO::TypeDesc::UINT8))
        throw std::runtime_error("cannot write " + path.string() + ": " + buffer.geterror());
}

}  // namespace

// The maps in `made` and `committed` hold the same texels (PNG bytes may differ between zlib versions).
int compare(const std::filesystem::path& made, const std::filesystem::path& committed) {
    int differing = 0;
    for (const char* map : kMapNames) {
        OIIO::ImageBuf a((made / map).string()), b((committed / map).string());
        if (!a.read() || !b.read()) {
            std::fprintf(stderr, "tessera_make_textures: cannot read %s: %s%s\n", map, a.geterror().c_str(),
                         b.geterror().c_str());
            ++differing;
            continue;
        }
        const OIIO::ImageBufAlgo::CompareResults result = OIIO::ImageBufAlgo::compare(a, b, 0.0f, 0.0f);
        if (a.spec().width != b.spec().width || a.spec().height != b.spec().height ||
            a.nchannels() != b.nchannels() || result.nfail > 0 || result.error) {
            std::fprintf(stderr, "tessera_make_textures: %s differs from %s: %llu texels, largest difference %g\n",
                         (made / map).string().c_str(), (committed / map).string().c_str(),
                         static_cast<unsigned long long>(result.nfail), result.maxerror);
            ++differing;
        }
    }
    if (differing == 0) std::printf("the committed maps in %s are what the generator makes\n", committed.string().c_str());
    return differing == 0 ? 0 : 1;
}

int main(int argc, char** argv) {
    if (argc != 2 && !(argc == 4 && std::string(argv[2]) == "--compare")) {
        std::fprintf(stderr, "usage: %s OUT_DIR [--compare COMMITTED_DIR]\n", argv[0]);
        return 2;
    }
    try {
        const std::filesystem::path out_dir = argv[1];
        std::filesystem::create_directories(out_dir);
        Maps maps = generate();
        for (float& c : maps.albedo) c = linear_to_srgb(c);  // PNG holds display (sRGB) values
        write(out_dir / "albedo.png", 3, maps.albedo);
        write(out_dir / "metallic.png", 1, maps.metallic);
        write(out_dir / "roughness.png", 1, maps.roughness);
        write(out_dir / "ao.png", 1, maps.ao);
        write(out_dir / "normal.png", 3, maps.normal);
        std::printf("wrote albedo, metallic, roughness, ao, normal (%dx%d PNG) to %s\n", kSize, kSize,
                    out_dir.string().c_str());
        if (argc == 4) return compare(out_dir, argv[3]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tessera_make_textures: %s\n", e.what());
        return 1;
    }
    return 0;
}
