// Rendering a scene to an image: the whole pipeline behind one call.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/scene.hpp"

namespace tessera {

// Arbitrary output variables: surface data per pixel, written beside the
// radiance into the EXR (channel names in image_io.hpp).
enum class Aov : std::uint8_t { depth, normal, albedo, roughness, metallic, position, object_id, material_id, shadow };
inline constexpr Aov kAllAovs[] = {Aov::depth,    Aov::normal,   Aov::albedo,    Aov::roughness,
                                   Aov::metallic, Aov::position, Aov::object_id, Aov::material_id,
                                   Aov::shadow};
std::string_view aov_name(Aov aov);  // as the command line spells it: "depth", "normal", ...

// A selection of AOVs, one bit per Aov.
struct AovSet {
    std::uint32_t bits = 0;
    bool empty() const { return bits == 0; }
    bool contains(Aov aov) const { return (bits >> unsigned(aov)) & 1u; }
    void insert(Aov aov) { bits |= 1u << unsigned(aov); }
    friend bool operator==(AovSet, AovSet) = default;
};

// Adds the AOVs of a comma-separated list ("depth,normal") to `set`; names
// may repeat. Throws std::invalid_argument naming an unknown or empty entry.
void parse_aov_list(std::string_view list, AovSet& set);

struct RenderSettings {
    int threads = 0;        // worker threads; 0 = one per hardware thread
    // Screen tile side in pixels, a power of two in [8, 256]; the image does not
    // depend on it.
    int tile_size = 64;
    std::string isa = "auto";  // SIMD kernels: auto | scalar | sse4 | avx2 | avx512
    // Fill RenderedImage::radiance (what EXR output needs). Without it a frame
    // writes only the 8-bit display image, as an OpenGL RGBA8 framebuffer would.
    bool keep_radiance = true;
    // Light ranges and culling: a light with a range (Light::range) adds nothing
    // to a visible point farther away, and clustered culling (shade/light_culling.hpp)
    // skips it per tile and per cluster of fragments where it reaches none.
    // The image depends on neither the tile size nor the thread count. Off,
    // every light is shaded everywhere, as the reference shader does. Scenes
    // without ranges give the same image, bit for bit, either way.
    bool light_culling = true;
    // AOV planes to fill in RenderedImage::aov. None by default: a frame
    // without AOVs neither allocates nor writes them.
    AovSet aovs{};  // (an initializer, or designated initializers that leave it out warn)
    // Record the frame's timeline (Renderer::last_frame_profile): a span per pass,
    // chunk and tile, for traces and cost heat maps. Off, nothing is recorded.
    bool profile = false;
};

// The AOV planes of a frame, row-major like the radiance, row 0 at the top.
// A plane is empty unless RenderSettings::aovs asked for it. Values come from
// the visible surface as the shader saw it (after texturing); background
// pixels hold the value given for each.
struct AovPlanes {
    // Linear view-space depth: distance from the camera along its view axis
    // (not along the pixel's ray), > 0, world units. Background: +infinity,
    // farther than any surface, so a depth merge (min) keeps the other image.
    std::vector<float> depth;
    // World-space unit shading normal, XYZ interleaved (the interpolated vertex
    // normal, or the normal-mapped one, normalized). Background: (0, 0, 0).
    std::vector<float> normal;
    std::vector<float> albedo;     // linear RGB interleaved, [0, 1]. Background: 0
    std::vector<float> roughness;  // [0, 1]. Background: 0
    std::vector<float> metallic;   // [0, 1]. Background: 0
    std::vector<float> position;   // world-space point, XYZ interleaved, world units. Background: (0, 0, 0)
    // Which object and material the pixel shows (opaque and masked surfaces; blended
    // ones are drawn over and leave these as they were). object_id: Object::id, or
    // the object's index + 1 where that is 0; material_id: Object::material + 1.
    // Background: 0. The same for any thread count and run.
    std::vector<std::uint32_t> object_id;
    std::vector<std::uint32_t> material_id;
    // Light visibility (shadow mapping, Light::shadows): the mean over the
    // lights that cast shadows of each one's visibility, 1 − the chapters'
    // `shadow`, in [0, 1]: 1 lit by all of them, 0 in the shadow of all. 1 where
    // no light casts shadows. Background: 1. Opaque and masked surfaces, as the ids.
    std::vector<float> shadow;

    bool empty() const {
        return depth.empty() && normal.empty() && albedo.empty() && roughness.empty() && metallic.empty() &&
               position.empty() && object_id.empty() && material_id.empty() && shadow.empty();
    }
};

// A rendered frame, row 0 at the top of the picture.
struct RenderedImage {
    int width = 0;
    int height = 0;
    // Scene-linear HDR radiance before tonemapping, RGB interleaved: what EXR
    // stores. Background pixels hold the radiance that tonemaps to the clear
    // colour. Empty when the renderer was told not to keep it.
    std::vector<float> radiance;
    // Display-referred RGB8 after Reinhard and gamma 1/2.2: what PNG stores.
    // Background pixels hold the clear colour, as glClear writes it.
    std::vector<std::uint8_t> display;
    AovPlanes aov;
};

// What one frame did and where its time went, in milliseconds.
struct FrameStats {
    std::uint64_t triangles_in = 0;          // submitted by the scene's objects
    std::uint64_t triangles_binned = 0;      // left after clipping, culling and setup
    std::uint64_t fragments_rasterized = 0;  // pixel centres covered, over all triangles
    std::uint64_t fragments_shaded = 0;      // visible pixels, each shaded once
    std::uint64_t fragment_lights = 0;       // Σ fragments × the lights looped over for them, after light culling
    // Lights with shadows: their maps drawn this frame, and those kept as the
    // frame before drew them (nothing they depend on moved).
    std::uint32_t shadow_maps_drawn = 0, shadow_maps_kept = 0;
    // Point-light shadow lookups (fragments × shadowed point lights, SIMD
    // kernels): settled by the maps' block summaries, skipped as facing away
    // from the light (its share is 0 whatever the shadow), and with every tap taken.
    std::uint64_t shadow_lookups_settled = 0, shadow_lookups_facing_away = 0, shadow_lookups_tapped = 0;
    // Wall-clock time of the frame's three passes, one after the other.
    double vertex_ms = 0;       // vertex shader, outcodes, viewport transform
    double triangles_ms = 0;    // the triangle pass: clip+setup, then binning, chunk by chunk
    double tiles_ms = 0;        // the tile pass: rasterize, shade, resolve, tile by tile
    double shadow_ms = 0;       // the shadow maps' depth passes (lights with shadows), before the tile pass
    double total_ms = 0;
    // The steps inside the triangle and tile passes: busy time summed over
    // the workers, divided by the thread count, so that they add up to about
    // their pass's time.
    double clip_setup_ms = 0;   // clipping, culling, triangle setup
    double binning_ms = 0;      // sorting triangles into tiles
    double rasterize_ms = 0;    // edge functions, depth test
    double shade_ms = 0;        // interpolation and the PBR shader
    double resolve_ms = 0;      // tonemap, quantize, write the images
};

// One timed piece of a frame, as recorded with RenderSettings::profile.
struct ProfileSpan {
    enum class Kind : std::uint8_t { pass, chunk, tile };
    Kind kind = Kind::pass;
    const char* name = "";  // pass: "vertex", "triangles" or "tiles"; chunk: "chunk"; tile: "tile"
    int worker = 0;         // oneTBB's slot (0..threads-1) of the thread that ran it
    int index = -1;         // chunk or tile number; -1 for a pass
    double start_ms = 0;    // from the start of the frame
    double end_ms = 0;
    // A tile's three steps, one after the other from start_ms; they add up to its span.
    double rasterize_ms = 0, shade_ms = 0, resolve_ms = 0;
    std::uint64_t triangles = 0;  // chunk: triangles submitted; tile: triangles rasterized in it
    std::uint64_t fragments = 0;  // tile: visible fragments shaded
    std::uint32_t lights = 0;     // tile: lights shaded there, after culling
    std::uint64_t fragment_lights = 0;  // tile: Σ fragments × the lights shaded for each (clusters cull more than the tile)
};

// A frame's timeline: the passes, then every chunk and tile span sorted by
// worker and start. Spans of one worker never overlap; chunks lie inside the
// triangle pass and tiles inside the tile pass, and the passes add up to the frame.
struct FrameProfile {
    int threads = 0;
    int width = 0, height = 0;       // the image, pixels
    int tile_size = 0, tiles_x = 0, tiles_y = 0;
    double total_ms = 0;
    std::vector<ProfileSpan> spans;
};

// Renders scenes, keeping its frame memory from one frame to the next.
class Renderer {
public:
    explicit Renderer(const RenderSettings& settings = {});  // throws std::invalid_argument
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // The returned image stays valid until the next render().
    const RenderedImage& render(const Scene& scene);
    // Exchanges the last frame's image with `other`: the caller keeps the frame
    // without a copy, and the next render() writes into other's memory (reused
    // where large enough, so a caller that hands back its previous frame's image
    // allocates nothing in steady state).
    void swap_image(RenderedImage& other);
    const FrameStats& last_frame_stats() const;
    // The last frame's timeline; empty unless RenderSettings::profile is set.
    const FrameProfile& last_frame_profile() const;
    std::string isa_name() const;  // the shading kernels in use
    int threads() const;

private:
    struct Frame;
    std::unique_ptr<Frame> frame_;
};

}  // namespace tessera
