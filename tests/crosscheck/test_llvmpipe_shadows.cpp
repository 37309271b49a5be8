// Tessera's shadow mapping against LearnOpenGL's shadow chapters on llvmpipe
// (tools/gl_reference/gl_shadows.cpp): the depth passes (a 2D depth texture per directional
// or spot light, a cube per point light through the chapter's geometry shader) and the
// chapters' ShadowCalculation in the peer's PBR shader. The peer takes Tessera's light cameras
// (shade::plan_shadow_map), so what is compared is the depth passes and the shadow factor.
// First the maps texel by texel, then whole images of tests/crosscheck/scenes/shadows_*.toml,
// one per light type. A pixel that differs is explained where it can be: on a silhouette (the
// object ids), in a penumbra (Tessera's visibility strictly between 0 and 1 for a shadowed
// light), or decided by the maps (Tessera's shadow_visibility gives another value from
// llvmpipe's map than from its own). docs/testing.md has the numbers. Skipped (ctest: Skipped)
// where no EGL device/driver makes an llvmpipe context.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "agreement.hpp"
#include "gl_renderer.hpp"
#include "render/shadow_pass.hpp"
#include "shade/pbr_reference.hpp"
#include "shade/shadow_maps.hpp"
#include "simd/isa.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"
#include "test_paths.hpp"

using namespace tessera;
using namespace tessera::crosscheck;

namespace {

Scene shadow_scene(const char* name) {
    return load_scene_file(test::source_dir() / "tests" / "crosscheck" / "scenes" / name);
}

// ---------------------------------------------------------------------------------------
// The maps. Tessera's own depth passes (render::ShadowPass, as Renderer draws them) beside
// the peer's. A texel "on an edge" has a neighbour (8-connected) in Tessera's map whose depth
// differs by more than kEdgeJump, or which one map covers and the other not: there a caster's
// edge crosses the texel, and the two rasterizers may disagree about whether its centre is in.
constexpr float kEdgeJump = 0.01f;

struct MapComparison {
    std::size_t texels = 0;
    std::size_t identical = 0;
    std::size_t coverage_differs = 0;         // one map drew something there, the other not
    std::size_t coverage_differs_on_edge = 0;
    std::size_t depth_differs = 0;            // both covered, |difference| > 1e-5
    std::size_t depth_differs_on_edge = 0;
    double max_depth_difference_off_edge = 0;  // both covered, not on an edge
};
// Measured off edges (docs/testing.md): window depth (directional) at most 1.2e-5 apart;
// distance / far plane (spot, point) at most 9.9e-5, Tessera's distance being reconstructed
// from its float window depth (near = far / 1000), llvmpipe's the chapter's length(FragPos −
// lightPos) / far_plane. Both far below the biases (0.005 of the map's range at least).
constexpr double kMaxWindowDepthDifference = 3e-5;
constexpr double kMaxDistanceDifference = 2e-4;
// Texels one map covers and the other not: measured at most 3 per million.
constexpr double kMaxCoverageDifference = 1e-4;  // of the texels

// Tessera's maps of `scene` (indexed like its shadowed lights) and llvmpipe's.
struct BothMaps {
    std::vector<shade::ShadowMap> tessera;
    std::vector<const shade::ShadowMap*> by_light;
    std::vector<gl_reference::ShadowMapReadback> gl;
    std::vector<shade::ShadowMap> gl_as_tessera;  // llvmpipe's depths in Tessera's ShadowMaps (rows flipped)
};

BothMaps both_maps(gl_reference::GlReferenceRenderer& gl, const Scene& scene) {
    BothMaps m;
    render::ShadowPass pass;
    pass.render_maps(simd::best_supported_isa(), scene, m.tessera, m.by_light);
    m.gl = gl.read_shadow_maps(scene);
    std::size_t shadowed = 0;
    for (const Light& light : scene.lights) shadowed += light.shadows ? 1 : 0;
    REQUIRE(m.gl.size() == shadowed);
    m.tessera.resize(shadowed);
    for (std::size_t s = 0; s < shadowed; ++s) {
        const shade::ShadowMap& t = m.tessera[s];
        const gl_reference::ShadowMapReadback& g = m.gl[s];
        REQUIRE(g.size == t.size);
        REQUIRE(g.faces == t.faces);
        shade::ShadowMap copy = t;
        const std::size_t n = std::size_t(t.size);
        for (std::size_t f = 0; f < std::size_t(t.faces); ++f)
            for (std::size_t row = 0; row < n; ++row)
                std::copy_n(g.depth.data() + (f * n + (n - 1 - row)) * n, n, copy.depth.data() + (f * n + row) * n);
        m.gl_as_tessera.push_back(std::move(copy));
    }
    return m;
}

MapComparison compare_maps(const shade::ShadowMap& t, const shade::ShadowMap& g) {
    MapComparison c;
    const int n = t.size;
    for (int f = 0; f < t.faces; ++f)
        for (int row = 0; row < n; ++row)
            for (int col = 0; col < n; ++col) {
                const float a = t.texel(f, col, row), b = g.texel(f, col, row);
                const bool a_covered = a < 1.0f, b_covered = b < 1.0f;
                bool edge = false;
                for (int dy = -1; dy <= 1 && !edge; ++dy)
                    for (int dx = -1; dx <= 1 && !edge; ++dx) {
                        const int x = col + dx, y = row + dy;
                        if (x < 0 || y < 0 || x >= n || y >= n) continue;
                        const float ta = t.texel(f, x, y), tb = g.texel(f, x, y);
                        edge = std::fabs(ta - a) > kEdgeJump || (ta < 1.0f) != a_covered || (tb < 1.0f) != b_covered;
                    }
                ++c.texels;
                if (a == b) ++c.identical;
                if (a_covered != b_covered) {
                    ++c.coverage_differs;
                    c.coverage_differs_on_edge += edge;
                } else if (a_covered && std::fabs(a - b) > 1e-5f) {
                    ++c.depth_differs;
                    c.depth_differs_on_edge += edge;
                }
                if (a_covered && b_covered && !edge)
                    c.max_depth_difference_off_edge = std::max(c.max_depth_difference_off_edge, double(std::fabs(a - b)));
            }
    return c;
}

std::string describe(const MapComparison& c) {
    return std::to_string(c.texels) + " texels: " + std::to_string(100.0 * double(c.identical) / double(c.texels)) +
           "% identical; coverage differs at " + std::to_string(c.coverage_differs) + " (" +
           std::to_string(c.coverage_differs_on_edge) + " on a caster's edge); depth differs by more than 1e-5 at " +
           std::to_string(c.depth_differs) + " (" + std::to_string(c.depth_differs_on_edge) +
           " on an edge); max difference off edges " + std::to_string(c.max_depth_difference_off_edge);
}

void check_maps(const char* scene_file) {
    gl_reference::GlReferenceRenderer* gl = gl_renderer_or_skip();
    if (!gl) return;
    const Scene scene = shadow_scene(scene_file);
    const BothMaps m = both_maps(*gl, scene);
    for (std::size_t s = 0; s < m.tessera.size(); ++s) {
        const MapComparison c = compare_maps(m.tessera[s], m.gl_as_tessera[s]);
        CHECK(m.gl[s].float_depth);  // GL_DEPTH_COMPONENT32F, as Tessera's float maps
        MESSAGE(std::string(scene_file) << " light " << m.gl[s].light << " (" << m.tessera[s].faces << " face(s) of "
                           << m.tessera[s].size << "²): " << describe(c));
        CAPTURE(s);
        // Every disagreement about coverage is where a caster's edge crosses a texel, and off
        // the edges both hold the same depth to float rounding.
        CHECK(c.coverage_differs == c.coverage_differs_on_edge);
        CHECK(double(c.coverage_differs) <= kMaxCoverageDifference * double(c.texels));
        CHECK(c.max_depth_difference_off_edge <= (m.tessera[s].kind == shade::ShadowMapKind::planar_depth
                                                      ? kMaxWindowDepthDifference
                                                      : kMaxDistanceDifference));
    }
}

// ---------------------------------------------------------------------------------------
// The images.

// Whether one of the chapters' taps for the point is on a knife's edge, where the two
// implementations' arithmetic (not their maps) may decide it: its coordinate within
// kTexelEdge texels of a texel boundary (kCubeTexelEdge on a cube face; or its two largest
// components within 1e-5 of each other: which face), or its depth test within kDepthEdge of
// going the other way. On cube faces llvmpipe's coordinates were seen up to 0.005 texel from
// Tessera's (two penumbra pixels of scenes/shadows.toml, taps 0.0045 and 0.0049 texel from a
// boundary, each 3/255 off); on 2D maps nothing needed more than 0.002.
constexpr float kTexelEdge = 2e-3f;
constexpr float kCubeTexelEdge = 1e-2f;
constexpr float kDepthEdge = 2e-4f;

bool near_integer(float v, float edge = kTexelEdge) { return std::fabs(v - std::round(v)) < edge; }

bool knife_edge(const shade::ShadowMap& map, const glm::vec3& pos, const glm::vec3& normal_in, const glm::vec3& cam) {
    const float size = float(map.size);
    if (map.kind == shade::ShadowMapKind::cube_distance) {
        const glm::vec3 to_frag = pos - map.position;
        const float current = glm::length(to_frag);
        const float radius = (1.0f + glm::length(cam - pos) / map.disk_far_plane) / 25.0f * float(map.filter_radius);
        const auto tap = [&](const glm::vec3& d) {
            const glm::vec3 a = glm::abs(d);
            const float ma = std::max({a.x, a.y, a.z});
            const float mid = a.x + a.y + a.z - ma - std::min({a.x, a.y, a.z});
            if (ma - mid < 1e-5f * ma) return true;
            // The coordinates on the face are ±the two other components over ma.
            const float u = a.x == ma ? d.y : d.x, v = a.z == ma ? d.y : d.z;
            if (near_integer((u / ma + 1.0f) * 0.5f * size, kCubeTexelEdge) ||
                near_integer((v / ma + 1.0f) * 0.5f * size, kCubeTexelEdge))
                return true;
            int face = 0;
            float sc = 0, tc = 0;
            if (a.x >= a.y && a.x >= a.z) face = d.x >= 0 ? 0 : 1, sc = d.x >= 0 ? -d.z : d.z, tc = -d.y;
            else if (a.y >= a.z) face = d.y >= 0 ? 2 : 3, sc = d.x, tc = d.y >= 0 ? d.z : -d.z;
            else face = d.z >= 0 ? 4 : 5, sc = d.z >= 0 ? d.x : -d.x, tc = -d.y;
            const int col = std::clamp(int(std::floor((sc / ma + 1.0f) * 0.5f * size)), 0, map.size - 1);
            const int row = std::clamp(int(std::floor((tc / ma + 1.0f) * 0.5f * size)), 0, map.size - 1);
            const float closest = map.texel(face, col, map.size - 1 - row) * map.far_plane;
            return std::fabs(current - 0.15f - closest) < kDepthEdge * map.far_plane;
        };
        if (map.filter_radius == 0) return tap(to_frag);
        for (const glm::vec3& offset : shade::kGridSamplingDisk)
            if (tap(to_frag + offset * radius)) return true;
        return false;
    }
    const glm::vec4 clip = map.view_projection[0] * glm::vec4(pos, 1.0f);
    if (!(clip.w > 0.0f)) return false;
    const glm::vec3 proj = glm::vec3(clip) / clip.w * 0.5f + 0.5f;
    const bool distance = map.kind == shade::ShadowMapKind::planar_distance;
    const float current = distance ? glm::length(pos - map.position) / map.far_plane : proj.z;
    const glm::vec3 light_dir = distance ? glm::normalize(map.position - pos) : map.to_light;
    const float bias = std::max(0.05f * (1.0f - glm::dot(glm::normalize(normal_in), light_dir)), 0.005f);
    const int r = map.filter_radius;
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y) {
            const float u = (proj.x + float(x) / size) * size, v = (proj.y + float(y) / size) * size;
            if (near_integer(u) || near_integer(v)) return true;
            const int col = int(std::floor(u)), row = int(std::floor(v));
            if (col < 0 || row < 0 || col >= map.size || row >= map.size) continue;
            if (std::fabs(current - bias - map.texel(0, col, map.size - 1 - row)) < kDepthEdge) return true;
        }
    return false;
}
struct Region {
    std::size_t pixels = 0, exact = 0, within_one = 0, within_two = 0;
    int max_difference = 0;
    double fraction(std::size_t n) const { return pixels ? double(n) / double(pixels) : 1.0; }
    void add(int diff) {
        ++pixels;
        exact += diff == 0;
        within_one += diff <= 1;
        within_two += diff <= 2;
        max_difference = std::max(max_difference, diff);
    }
};

std::string describe(const char* what, const Region& g) {
    return std::string(what) + " " + std::to_string(g.pixels) + " px: " + std::to_string(100.0 * g.fraction(g.exact)) +
           "% identical, " + std::to_string(100.0 * g.fraction(g.within_one)) + "% <= 1/255, " +
           std::to_string(100.0 * g.fraction(g.within_two)) + "% <= 2/255, max " + std::to_string(g.max_difference) +
           "/255";
}

// all; silhouettes (object ids); background; surface pixels split four ways: decided by the
// maps (Tessera's shadow_visibility from llvmpipe's maps differs from its own maps' for some
// light), else with a tap on a knife's edge (knife_edge), else in a penumbra (0 < visibility <
// 1 for some light), else the rest (lit or in full shadow).
struct Regions {
    Region all, silhouette, background, maps_decide, knife_edge, penumbra, rest;
};

struct ImageThresholds {
    double min_identical = 0.0;   // of all pixels
    double min_within_one = 0.0;  // of all pixels
    double min_within_two = 0.0;  // of all pixels
    int max_rest = 0;             // 8-bit steps, surface pixels neither decided by the maps nor in a penumbra
    int max_penumbra = 0;         // the same, penumbra pixels the maps do not decide
};

void check_shadow_scene(const Scene& scene, const std::string& name, const ImageThresholds& thresholds) {
    gl_reference::GlReferenceRenderer* gl = gl_renderer_or_skip();
    if (!gl) return;
    const RenderedImage gl_image = gl->render(scene);
    const std::vector<std::uint32_t> ids = gl->render_object_ids(scene);
    RenderSettings settings;
    settings.aovs.insert(Aov::position);
    settings.aovs.insert(Aov::normal);
    settings.aovs.insert(Aov::object_id);
    Renderer renderer(settings);
    const RenderedImage tessera_image = renderer.render(scene);
    REQUIRE(tessera_image.width == gl_image.width);
    REQUIRE(tessera_image.height == gl_image.height);
    const BothMaps maps = both_maps(*gl, scene);

    Regions r;
    int reported = 0;  // surface pixels further than 2/255, the first 20 named
    const int w = gl_image.width, h = gl_image.height;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
            const int diff = max_channel_difference(tessera_image, gl_image, p);
            r.all.add(diff);
            if (on_silhouette(ids, w, h, x, y)) {
                r.silhouette.add(diff);
                continue;
            }
            if (ids[p] == 0 || tessera_image.aov.object_id[p] == 0) {
                r.background.add(diff);
                continue;
            }
            const glm::vec3 pos(tessera_image.aov.position[3 * p], tessera_image.aov.position[3 * p + 1],
                                tessera_image.aov.position[3 * p + 2]);
            const glm::vec3 normal(tessera_image.aov.normal[3 * p], tessera_image.aov.normal[3 * p + 1],
                                   tessera_image.aov.normal[3 * p + 2]);
            bool decided = false, fractional = false, edge = false;
            for (std::size_t s = 0; s < maps.tessera.size(); ++s) {
                const float own = shade::shadow_visibility(maps.tessera[s], pos, normal, scene.camera.position);
                const float peer = shade::shadow_visibility(maps.gl_as_tessera[s], pos, normal, scene.camera.position);
                decided = decided || own != peer;
                fractional = fractional || (own > 0.0f && own < 1.0f);
                edge = edge || knife_edge(maps.tessera[s], pos, normal, scene.camera.position);
            }
            (decided ? r.maps_decide : edge ? r.knife_edge : fractional ? r.penumbra : r.rest).add(diff);
            if (diff > 2 && ++reported <= 20) MESSAGE("pixel (" << x << ", " << y << ") off by " << diff << "/255: "
                                  << std::string(decided ? "maps" : edge ? "knife's edge" : fractional ? "penumbra" : "rest"));
        }
    MESSAGE(name << " vs " << gl->renderer_name() << ":\n  " << describe("all", r.all) << "\n  "
                 << describe("silhouette", r.silhouette) << "\n  " << describe("background", r.background) << "\n  "
                 << describe("decided by the maps", r.maps_decide) << "\n  "
                 << describe("a tap on a knife's edge", r.knife_edge) << "\n  " << describe("penumbra", r.penumbra)
                 << "\n  " << describe("rest of the surfaces", r.rest));
    const bool passed = r.all.fraction(r.all.exact) >= thresholds.min_identical &&
                        r.all.fraction(r.all.within_one) >= thresholds.min_within_one &&
                        r.all.fraction(r.all.within_two) >= thresholds.min_within_two &&
                        r.rest.max_difference <= thresholds.max_rest &&
                        r.penumbra.max_difference <= thresholds.max_penumbra;
    if (!passed) MESSAGE("images: " << write_failure_images(tessera_image, gl_image, name));
    CHECK(r.all.fraction(r.all.exact) >= thresholds.min_identical);
    CHECK(r.all.fraction(r.all.within_one) >= thresholds.min_within_one);
    CHECK(r.all.fraction(r.all.within_two) >= thresholds.min_within_two);
    CHECK(r.rest.max_difference <= thresholds.max_rest);
    CHECK(r.penumbra.max_difference <= thresholds.max_penumbra);
}

Scene without_shadows(Scene scene) {
    for (Light& light : scene.lights) light.shadows = false;
    return scene;
}

Scene with_filter_radius(Scene scene, int radius) {
    for (Light& light : scene.lights) light.shadow_filter_radius = radius;
    return scene;
}

// Measured (docs/testing.md): without shadows 99.955% identical, 99.9996% within 1/255 and
// 2/255, surfaces at most 1/255; with shadows at least 99.836% identical, 99.967% within 1/255,
// 99.997% within 2/255, penumbrae and the rest of the surfaces at most 1/255 (every pixel
// further off is on a silhouette, decided by the maps or has a tap on a knife's edge).
constexpr ImageThresholds kLightTypes{0.995, 0.9999, 0.9999, 2, 2};
constexpr ImageThresholds kShadows{0.995, 0.999, 0.9998, 2, 2};

}  // namespace

// The peer takes Tessera's light cameras; what they promise (src/shade/shadow_maps.hpp) is
// checked here instead: every surface point the camera sees lies inside its lights' maps (a
// spot's where its cone lights it, within the far plane for spot and point lights), and every
// caster's vertex within the directional map's depth range (a caster clipped away would cast
// nothing). No OpenGL needed.
TEST_CASE("crosscheck shadows: every visible point lies in its lights' maps and every caster in the depth range") {
    for (const char* file : {"shadows_point.toml", "shadows_directional.toml", "shadows_spot.toml"}) {
        CAPTURE(std::string(file));
        const Scene scene = shadow_scene(file);
        RenderSettings settings;
        settings.aovs.insert(Aov::position);
        settings.aovs.insert(Aov::object_id);
        Renderer renderer(settings);
        const RenderedImage image = renderer.render(scene);
        const shade::SceneBounds bounds = shade::scene_bounds(scene);
        std::size_t points = 0, outside = 0, casters_clipped = 0;
        for (const Light& light : scene.lights) {
            if (!light.shadows) continue;
            shade::ShadowMap map;
            shade::plan_shadow_map(scene, bounds, light, map);
            for (std::size_t p = 0; p < image.aov.object_id.size(); ++p) {
                if (image.aov.object_id[p] == 0) continue;
                const glm::vec3 pos(image.aov.position[3 * p], image.aov.position[3 * p + 1], image.aov.position[3 * p + 2]);
                ++points;
                if (light.type == LightType::point) {
                    outside += glm::length(pos - light.position) > map.far_plane;
                    continue;
                }
                if (light.type == LightType::spot && !(shade::spot_cone_factor(light, glm::normalize(pos - light.position)) > 0.0f))
                    continue;
                const glm::vec4 clip = map.view_projection[0] * glm::vec4(pos, 1.0f);
                const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                const bool inside = clip.w > 0.0f && std::fabs(ndc.x) <= 1.0f && std::fabs(ndc.y) <= 1.0f &&
                                    std::fabs(ndc.z) <= 1.0f;
                outside += !inside;
            }
            if (light.type != LightType::directional) continue;
            for (const Object& object : scene.objects)
                for (const glm::vec3& v : scene.meshes[object.mesh].positions) {
                    const glm::vec4 clip = map.view_projection[0] * (object.model * glm::vec4(v, 1.0f));
                    casters_clipped += std::fabs(clip.z / clip.w) > 1.0f;
                }
        }
        MESSAGE(std::string(file) << ": " << outside << " of " << points << " visible (point, light) pairs outside the map, "
                     << casters_clipped << " caster vertices outside the depth range");
        CHECK(points > 0);
        CHECK(outside == 0);
        CHECK(casters_clipped == 0);
    }
}

TEST_CASE("crosscheck shadows: llvmpipe's point-light cube maps are Tessera's but where casters' edges cross texels") {
    check_maps("shadows_point.toml");
}

TEST_CASE("crosscheck shadows: llvmpipe's directional-light depth map is Tessera's but where casters' edges cross texels") {
    check_maps("shadows_directional.toml");
}

TEST_CASE("crosscheck shadows: llvmpipe's spot-light distance map is Tessera's but where casters' edges cross texels") {
    check_maps("shadows_spot.toml");
}

TEST_CASE("crosscheck shadows: directional and spot lights without shadows agree with llvmpipe") {
    check_shadow_scene(without_shadows(shadow_scene("shadows_directional.toml")), "shadows_directional_unshadowed",
                       kLightTypes);
    check_shadow_scene(without_shadows(shadow_scene("shadows_spot.toml")), "shadows_spot_unshadowed", kLightTypes);
}

TEST_CASE("crosscheck shadows: shadows_point.toml (three point lights, cube maps, the 20-sample disk) agrees with llvmpipe") {
    check_shadow_scene(shadow_scene("shadows_point.toml"), "shadows_point", kShadows);
}

TEST_CASE("crosscheck shadows: point shadows with one sample (radius 0) and a disk twice the chapter's agree with llvmpipe") {
    check_shadow_scene(with_filter_radius(shadow_scene("shadows_point.toml"), 0), "shadows_point_r0", kShadows);
    check_shadow_scene(with_filter_radius(shadow_scene("shadows_point.toml"), 2), "shadows_point_r2", kShadows);
}

TEST_CASE("crosscheck shadows: shadows_directional.toml (orthographic map, 3x3 PCF) agrees with llvmpipe") {
    check_shadow_scene(shadow_scene("shadows_directional.toml"), "shadows_directional", kShadows);
}

TEST_CASE("crosscheck shadows: directional shadows with one texel (radius 0) agree with llvmpipe") {
    check_shadow_scene(with_filter_radius(shadow_scene("shadows_directional.toml"), 0), "shadows_directional_r0", kShadows);
}

TEST_CASE("crosscheck shadows: shadows_spot.toml (perspective distance map, 5x5 PCF) agrees with llvmpipe") {
    check_shadow_scene(shadow_scene("shadows_spot.toml"), "shadows_spot", kShadows);
}

TEST_CASE("crosscheck shadows: spot shadows with the chapter's 3x3 PCF agree with llvmpipe") {
    check_shadow_scene(with_filter_radius(shadow_scene("shadows_spot.toml"), 1), "shadows_spot_r1", kShadows);
}

TEST_CASE("crosscheck shadows: the chapters' own unsized GL_DEPTH_COMPONENT maps against Tessera") {
    gl_reference::GlReferenceRenderer* gl = gl_renderer_or_skip();
    if (!gl) return;
    gl->set_shadow_options({.chapter_depth_format = true});
    for (const char* file : {"shadows_point.toml", "shadows_directional.toml", "shadows_spot.toml"}) {
        const Scene scene = shadow_scene(file);
        const BothMaps m = both_maps(*gl, scene);
        for (std::size_t s = 0; s < m.tessera.size(); ++s)
            MESSAGE(std::string(file) << " light " << m.gl[s].light << ", chapter's format (" << m.gl[s].depth_bits
                                      << std::string(m.gl[s].float_depth ? "-bit float" : "-bit normalized") << "): "
                                      << describe(compare_maps(m.tessera[s], m.gl_as_tessera[s])));
        check_shadow_scene(scene, std::filesystem::path(file).stem().string() + "_chapter_format", kShadows);
    }
    gl->set_shadow_options({});
}

TEST_CASE("crosscheck shadows: the three scenes with 4x MSAA agree with llvmpipe's 4x MSAA") {
    for (const char* file : {"shadows_point.toml", "shadows_directional.toml", "shadows_spot.toml"}) {
        Scene scene = shadow_scene(file);
        scene.msaa = 4;
        check_shadow_scene(scene, std::filesystem::path(file).stem().string() + "_msaa", kShadows);
    }
}

TEST_CASE("crosscheck shadows: scenes/shadows.toml (a sun, a spot and a point light casting shadows) agrees with llvmpipe") {
    check_shadow_scene(load_scene_file(test::scene_path("shadows.toml")), "shadows", kShadows);
}

TEST_CASE("crosscheck shadows: point shadows with ranges (light culling, the disk scaled by the range) agree with llvmpipe") {
    // Each range ends on the floor, so light culling keeps a light in some tiles and not in others,
    // and the cube's far plane and the disk's are the range.
    Scene scene = shadow_scene("shadows_point.toml");
    const float ranges[] = {10.0f, 8.0f, 8.5f};
    REQUIRE(scene.lights.size() == 3);
    for (std::size_t l = 0; l < 3; ++l) scene.lights[l].range = ranges[l];
    check_shadow_scene(scene, "shadows_point_ranges", kShadows);
}

TEST_CASE("crosscheck shadows: shadows_spot.toml lit by the shipped environment too agrees with llvmpipe") {
    // The environment's ambient is not shadowed (docs/scene-format.md); the spot's term is.
    Scene scene = shadow_scene("shadows_spot.toml");
    scene.environment = load_scene_file(test::scene_path("spheres_environment.toml")).environment;
    scene.environment.background = false;
    check_shadow_scene(scene, "shadows_spot_environment", kShadows);
}
