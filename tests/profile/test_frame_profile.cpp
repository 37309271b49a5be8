// Frame profiles (RenderSettings::profile), the Chrome trace written from them and the
// tile heat map: spans account for the frame, nest, and say what each tile did.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <nlohmann/json.hpp>

#include "profile/frame_profile_output.hpp"
#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

// The demo scene at a small size: background tiles and busy tiles, several chunks.
Scene small_spheres() {
    Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    scene.width = 320, scene.height = 184;  // 184: the last tile row is partial
    return scene;
}

RenderSettings profiled(int threads) {
    RenderSettings settings;
    settings.threads = threads;
    settings.tile_size = 32;  // 10 × 6 tiles, as the checks count them
    settings.profile = true;
    return settings;
}

}  // namespace

TEST_CASE("profile: spans account for every chunk and tile once, inside their passes, without overlap") {
    const Scene scene = small_spheres();
    for (int threads : {1, 2, 3}) {
        CAPTURE(threads);
        Renderer renderer(profiled(threads));
        renderer.render(scene);
        const FrameProfile& p = renderer.last_frame_profile();
        const FrameStats& stats = renderer.last_frame_stats();
        REQUIRE(p.spans.size() > 3);
        CHECK(p.threads == threads);
        CHECK(p.tiles_x == 10);
        CHECK(p.tiles_y == 6);
        // The three passes follow each other and add up to the frame.
        const ProfileSpan &vertex = p.spans[0], &triangles = p.spans[1], &tiles = p.spans[2];
        CHECK(std::string(vertex.name) == "vertex");
        CHECK(std::string(triangles.name) == "triangles");
        CHECK(std::string(tiles.name) == "tiles");
        CHECK(vertex.start_ms == 0.0);
        CHECK(vertex.end_ms == triangles.start_ms);
        CHECK(triangles.end_ms == tiles.start_ms);
        CHECK(tiles.end_ms == doctest::Approx(p.total_ms).epsilon(1e-9));

        std::set<int> chunks_seen, tiles_seen;
        std::uint64_t triangles_in = 0, fragments = 0, fragment_lights = 0;
        std::map<int, double> worker_busy_until;
        for (std::size_t i = 3; i < p.spans.size(); ++i) {
            const ProfileSpan& s = p.spans[i];
            REQUIRE(s.kind != ProfileSpan::Kind::pass);
            CHECK(s.worker >= 0);
            CHECK(s.worker < threads);
            CHECK(s.end_ms >= s.start_ms);
            // Sorted by worker and start, and one worker does one thing at a time.
            CHECK(s.start_ms >= worker_busy_until[s.worker]);
            worker_busy_until[s.worker] = s.end_ms;
            const ProfileSpan& pass = s.kind == ProfileSpan::Kind::chunk ? triangles : tiles;
            CHECK(s.start_ms >= pass.start_ms);
            CHECK(s.end_ms <= pass.end_ms);
            if (s.kind == ProfileSpan::Kind::chunk) {
                CHECK(chunks_seen.insert(s.index).second);
                triangles_in += s.triangles;
            } else {
                CHECK(tiles_seen.insert(s.index).second);
                CHECK(s.rasterize_ms + s.shade_ms + s.resolve_ms ==
                      doctest::Approx(s.end_ms - s.start_ms).epsilon(1e-6));
                fragments += s.fragments;
                CHECK(s.lights <= scene.lights.size());
                if (s.fragments > 0) CHECK(s.lights == scene.lights.size());  // no ranges: nothing culled
                CHECK(s.fragment_lights == s.fragments * s.lights);
                fragment_lights += s.fragment_lights;
            }
        }
        CHECK(tiles_seen.size() == std::size_t(p.tiles_x * p.tiles_y));
        CHECK(triangles_in == stats.triangles_in);
        CHECK(fragments == stats.fragments_shaded);
        CHECK(fragment_lights == stats.fragment_lights);
    }
}

TEST_CASE("profile: with light ranges, each tile records the fragment-lights its clusters shaded") {
    Scene scene = load_scene_file(test::scene_path("many_lights.toml"));
    scene.width = 320, scene.height = 180;
    Renderer renderer(profiled(2));
    renderer.render(scene);
    std::uint64_t fragment_lights = 0;
    bool culled_below_tile = false;  // some tile's clusters shaded fewer lights than the tile's list
    for (const ProfileSpan& s : renderer.last_frame_profile().spans) {
        if (s.kind != ProfileSpan::Kind::tile) continue;
        CHECK(s.fragment_lights <= s.fragments * s.lights);
        culled_below_tile = culled_below_tile || s.fragment_lights < s.fragments * s.lights;
        fragment_lights += s.fragment_lights;
    }
    CHECK(fragment_lights == renderer.last_frame_stats().fragment_lights);
    CHECK(fragment_lights > 0);
    CHECK(culled_below_tile);
}

TEST_CASE("profile: off by default, and recording it changes no pixel") {
    const Scene scene = small_spheres();
    Renderer plain(RenderSettings{});
    const std::vector<std::uint8_t> expected = plain.render(scene).display;
    CHECK(plain.last_frame_profile().spans.empty());
    Renderer profiling(profiled(2));
    CHECK(profiling.render(scene).display == expected);
}

TEST_CASE("profile: the Chrome trace has a track per worker and spans that nest and sum to the frame") {
    const Scene scene = small_spheres();
    Renderer renderer(profiled(2));
    std::vector<profile::TracedFrame> frames;
    for (int i = 0; i < 2; ++i) {
        renderer.render(scene);
        frames.push_back({1e5 * i, renderer.last_frame_profile()});  // far apart: no frame overlaps the next
    }
    const auto path = test::output_dir("profile") / "trace.json";
    profile::write_chrome_trace(frames, "test \"trace\"", path);
    std::ifstream in(path);
    const nlohmann::json trace = nlohmann::json::parse(in);  // throws if it is not JSON
    REQUIRE(trace.contains("traceEvents"));

    std::map<int, std::string> track_names;
    std::map<int, std::vector<nlohmann::json>> spans_by_track;
    for (const auto& e : trace["traceEvents"]) {
        if (e["ph"] == "M" && e["name"] == "thread_name") track_names[e["tid"].get<int>()] = e["args"]["name"];
        if (e["ph"] == "X") {
            CHECK(e["dur"].get<double>() >= 0.0);
            spans_by_track[e["tid"].get<int>()].push_back(e);
        }
    }
    CHECK(track_names[0] == "frame");
    CHECK(track_names[1] == "worker 0");
    CHECK(track_names[2] == "worker 1");

    // On every track, spans nest: each one lies inside the enclosing span still open.
    const double slack_us = 1e-3;  // the steps' ends are sums of durations
    for (auto& [tid, spans] : spans_by_track) {
        std::stable_sort(spans.begin(), spans.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
            const double a_ts = a["ts"], b_ts = b["ts"], a_dur = a["dur"], b_dur = b["dur"];
            return a_ts < b_ts || (a_ts == b_ts && a_dur > b_dur);  // an enclosing span before what it holds
        });
        std::vector<double> open_ends;
        for (const auto& s : spans) {
            const double start = s["ts"], end = start + s["dur"].get<double>();
            while (!open_ends.empty() && start >= open_ends.back() - slack_us) open_ends.pop_back();
            if (!open_ends.empty()) CHECK(end <= open_ends.back() + slack_us);
            open_ends.push_back(end);
        }
    }
    // Each frame's passes add up to the frame span.
    std::size_t frame_spans = 0;
    for (const auto& frame : spans_by_track[0]) {
        if (frame["cat"] != "frame") continue;
        ++frame_spans;
        const double begin = frame["ts"], end = begin + frame["dur"].get<double>();
        double passes_us = 0;
        for (const auto& s : spans_by_track[0])
            if (s["cat"] == "pass" && s["ts"].get<double>() >= begin && s["ts"].get<double>() < end)
                passes_us += s["dur"].get<double>();
        CHECK(passes_us == doctest::Approx(frame["dur"].get<double>()).epsilon(1e-9));
    }
    CHECK(frame_spans == frames.size());
    // Every tile of every frame is there with what it did.
    std::size_t tile_spans = 0;
    for (const auto& [tid, spans] : spans_by_track)
        for (const auto& s : spans)
            if (s["cat"] == "tile") {
                ++tile_spans;
                CHECK(s["args"].contains("triangles"));
                CHECK(s["args"]["fragment_lights"] == s["args"]["fragments"].get<std::uint64_t>() *
                                                          s["args"]["lights"].get<std::uint64_t>());
            }
    CHECK(tile_spans == 2u * 60u);
}

TEST_CASE("profile: the work heat map tints the busiest tile hottest and leaves empty tiles dark") {
    const Scene scene = small_spheres();
    Renderer renderer(profiled(2));
    const RenderedImage& frame = renderer.render(scene);
    const std::vector<profile::TracedFrame> frames{{0.0, renderer.last_frame_profile()}};
    const RenderedImage map = profile::make_tile_heatmap(frame, frames, profile::HeatmapMetric::work);
    CHECK(map.width == frame.width);
    REQUIRE(map.height > frame.height);  // the legend below
    const auto path = test::output_dir("profile") / "heatmap_work.png";
    write_image(map, path);
    CHECK(OIIO::ImageBuf(path.string()).spec().height == map.height);

    // The busiest tile and an empty one (the scene's corner is background).
    const FrameProfile& p = frames[0].profile;
    const ProfileSpan* busiest = nullptr;
    const ProfileSpan* empty = nullptr;
    for (const ProfileSpan& s : p.spans) {
        if (s.kind != ProfileSpan::Kind::tile) continue;
        if (!busiest || s.fragment_lights > busiest->fragment_lights) busiest = &s;
        if (s.fragments == 0) empty = &s;
    }
    REQUIRE(busiest != nullptr);
    REQUIRE(empty != nullptr);
    const auto brightness = [&](const ProfileSpan& tile) {  // summed over the tile's top-left 8×8 pixels
        const int x0 = (tile.index % p.tiles_x) * p.tile_size, y0 = (tile.index / p.tiles_x) * p.tile_size;
        double sum = 0;
        for (int y = y0; y < y0 + 8; ++y)
            for (int x = x0; x < x0 + 8; ++x)
                for (int c = 0; c < 3; ++c) sum += map.display[3 * (std::size_t(y) * map.width + x) + c];
        return sum / (8 * 8 * 3);
    };
    CHECK(brightness(*busiest) > brightness(*empty) + 80.0);
    CHECK(profile::heatmap_ramp_end(frames, profile::HeatmapMetric::work) ==
          double(busiest->fragments) * busiest->lights);
    CHECK_THROWS_AS(profile::parse_heatmap_metric("cycles"), std::invalid_argument);
}
