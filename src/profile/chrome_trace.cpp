// Chrome trace-event format ("JSON Object Format"): complete events (ph "X") with
// ts/dur in microseconds on pid/tid tracks, and metadata events (ph "M") naming them.
#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "profile/frame_profile_output.hpp"

namespace tessera::profile {

namespace {

using nlohmann::json;

constexpr int kPid = 1;
constexpr int kFrameTrack = 0;  // tid of the frame/pass track; worker w is tid w + 1

json complete_event(const std::string& name, const char* category, int tid, double start_ms, double duration_ms) {
    return {{"name", name}, {"cat", category}, {"ph", "X"},          {"pid", kPid},
            {"tid", tid},   {"ts", start_ms * 1e3}, {"dur", duration_ms * 1e3}};
}

json thread_name(int tid, const std::string& name) {
    return {{"name", "thread_name"}, {"ph", "M"}, {"pid", kPid}, {"tid", tid}, {"args", {{"name", name}}}};
}

void add_frame(json& events, int number, const TracedFrame& frame) {
    const FrameProfile& p = frame.profile;
    const double t0 = frame.start_ms;
    json span = complete_event("frame " + std::to_string(number), "frame", kFrameTrack, t0, p.total_ms);
    span["args"] = {{"width", p.width}, {"height", p.height}, {"threads", p.threads}, {"tile_size", p.tile_size}};
    events.push_back(std::move(span));
    for (const ProfileSpan& s : p.spans) {
        const double start = t0 + s.start_ms, duration = s.end_ms - s.start_ms;
        switch (s.kind) {
        case ProfileSpan::Kind::pass:
            events.push_back(complete_event(s.name, "pass", kFrameTrack, start, duration));
            break;
        case ProfileSpan::Kind::chunk: {
            json chunk = complete_event("chunk " + std::to_string(s.index), "chunk", s.worker + 1, start, duration);
            chunk["args"] = {{"chunk", s.index}, {"triangles", s.triangles}};
            events.push_back(std::move(chunk));
            break;
        }
        case ProfileSpan::Kind::tile: {
            const int x = s.index % p.tiles_x, y = s.index / p.tiles_x;
            json tile = complete_event("tile " + std::to_string(s.index), "tile", s.worker + 1, start, duration);
            tile["args"] = {{"tile", s.index}, {"x", x * p.tile_size}, {"y", y * p.tile_size},
                            {"triangles", s.triangles}, {"fragments", s.fragments}, {"lights", s.lights},
                            {"fragment_lights", s.fragment_lights}};
            events.push_back(std::move(tile));
            // The steps follow each other from the tile's start; the last ends with it.
            double at = start;
            for (const auto& [name, ms] : {std::pair{"rasterize", s.rasterize_ms}, std::pair{"shade", s.shade_ms},
                                           std::pair{"resolve", s.resolve_ms}}) {
                if (ms > 0) events.push_back(complete_event(name, "step", s.worker + 1, at, ms));
                at += ms;
            }
            break;
        }
        }
    }
}

}  // namespace

void write_chrome_trace(std::span<const TracedFrame> frames, const std::string& title,
                        const std::filesystem::path& path) {
    json events = json::array();
    events.push_back({{"name", "process_name"}, {"ph", "M"}, {"pid", kPid}, {"args", {{"name", title}}}});
    events.push_back(thread_name(kFrameTrack, "frame"));
    int threads = 0;
    for (const TracedFrame& f : frames) threads = std::max(threads, f.profile.threads);
    for (int w = 0; w < threads; ++w) {
        events.push_back(thread_name(w + 1, "worker " + std::to_string(w)));
        // Keep the tracks in order: frame first, then the workers.
        events.push_back({{"name", "thread_sort_index"}, {"ph", "M"}, {"pid", kPid}, {"tid", w + 1},
                          {"args", {{"sort_index", w + 1}}}});
    }
    for (std::size_t i = 0; i < frames.size(); ++i) add_frame(events, int(i), frames[i]);
    const json trace = {{"traceEvents", std::move(events)}, {"displayTimeUnit", "ms"}};

    io::write_text_atomically(path, trace.dump(), "trace");  // never a half-written trace
}

}  // namespace tessera::profile
