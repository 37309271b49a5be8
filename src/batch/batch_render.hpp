// Rendering a batch: scenes × frames, one shard of it, resumable, with a
// progress display and a per-frame record. The thin CLI (`tessera render`)
// fills a BatchJob and calls run_batch.
#pragma once

#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "batch/shard.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace tessera::batch {

enum class ProgressDisplay {
    quiet,     // nothing (a plain one-scene render)
    lines,     // one line per frame: for logs, when output is not a terminal
    terminal,  // one line rewritten in place: done / total, frames per second, time left
};

struct BatchJob {
    std::vector<std::string> scene_paths;
    // Output patterns ({scene}, {frame}, {frame:0N}: frames.hpp); each frame is written to every one.
    std::vector<std::string> outputs;
    // --frames: the frames of every scene; nullopt = each scene as loaded (frame 0 of an animation).
    std::optional<std::vector<int>> frames;
    ShardChoice shard;
    // A frame whose every output file exists is not rendered again (writes are
    // atomic, so a present file is a finished one).
    bool skip_existing = false;
    std::string log_path;  // JSON Lines, appended to: one record per rendered frame; "" = none
    ProgressDisplay progress = ProgressDisplay::quiet;
    // Encode and write each frame on another thread while the next one renders (the
    // files are the same either way). Off: each frame is written before the next
    // renders, and no copy of the image is kept.
    bool write_behind = true;
    // Reads a scene file and applies the command line's overrides; throws with
    // a message naming the file.
    std::function<Scene(const std::string& path)> load_scene;
    // Called after each rendered frame (the CLI's --stats).
    std::function<void(const Renderer&, const RenderedImage&)> after_frame;
    // Called once a frame's outputs are written, with the wall time their encoding and
    // writing took (the CLI's --stats).
    std::function<void(double write_ms)> after_write;
};

// The (scene, frame) items of a job, in order: scene by scene, frames in the
// order given. The whole job's list, the same in every shard.
struct WorkItem {
    std::size_t scene = 0;  // index into BatchJob::scene_paths
    int frame = 0;
    friend bool operator==(const WorkItem&, const WorkItem&) = default;
};
std::vector<WorkItem> work_items(const BatchJob& job);

// Mistakes in the job itself, found before anything is rendered: unsupported
// output formats, several scenes or frames without {scene}/{frame} in every
// output, two scenes with one stem, malformed placeholders. Throws std::invalid_argument.
void check_job(const BatchJob& job);

struct BatchResult {
    int frames_rendered = 0;
    int frames_skipped = 0;  // --skip-existing
    int scenes_with_work = 0;  // scenes this shard had frames of
    std::vector<std::string> failed_scenes;
};

// Renders this shard's items with one renderer (frame memory reused from frame
// to frame and scene to scene). A scene that fails (load, frame out of range,
// write) is reported on `errors` as "tessera: error: ..." and the others go
// on. Progress goes to `progress`. Throws only for a log file it cannot open.
BatchResult run_batch(const BatchJob& job, Renderer& renderer, std::FILE* progress, std::FILE* errors);

}  // namespace tessera::batch
