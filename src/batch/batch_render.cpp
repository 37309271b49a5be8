#include "batch/batch_render.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <sys/stat.h>

#include <cerrno>
#include <ctime>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <functional>
#include <future>
#include <optional>
#include <map>
#include <set>
#include <stdexcept>

#include "batch/frames.hpp"
#include "io/input_file.hpp"
#include "io/memory_budget.hpp"
#include "scene/scene_validation.hpp"
#include "tessera/animation.hpp"
#include "tessera/image_io.hpp"

namespace tessera::batch {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// CPU time in ms: the process's (all threads: the renderer's workers) or this thread's (the PNG/EXR
// encoder). Beside the wall-clock times they tell work from waiting on a busy machine.
double cpu_ms(clockid_t clock) {
    timespec now{};
    clock_gettime(clock, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

std::string stem_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

// A JSON string literal.
std::string json_string(std::string_view text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char escape[8];
            std::snprintf(escape, sizeof escape, "\\u%04x", unsigned(c));
            out += escape;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

// The JSON Lines record file: each record goes out in one write() to a file
// opened O_APPEND, so the shards of an array may share one log.
class RecordLog {
public:
    explicit RecordLog(const std::string& path) : path_(path) {
        if (path.empty()) return;
        io::check_output_file(path, "the log");  // a FIFO would block the open, a device swallow the records
        // O_NONBLOCK: a name that became a FIFO since is refused (ENXIO) instead of waiting for a reader.
        fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOCTTY | O_NONBLOCK, 0644);
        if (fd_ < 0) throw std::runtime_error(path + ": cannot open the log: " + std::strerror(errno));
        struct stat st {};
        if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
            ::close(fd_);
            throw std::runtime_error(path + ": cannot write the log: not a regular file");
        }
        ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);  // blocking writes again
    }
    ~RecordLog() {
        if (fd_ >= 0) ::close(fd_);
    }
    RecordLog(const RecordLog&) = delete;
    RecordLog& operator=(const RecordLog&) = delete;

    void write(const std::string& line) {
        if (fd_ < 0) return;
        if (::write(fd_, line.data(), line.size()) != ssize_t(line.size()))
            throw std::runtime_error(path_ + ": cannot write the log: " + std::strerror(errno));
    }

private:
    std::string path_;
    int fd_ = -1;
};

// Frames done / total, frames per second, time left.
class Progress {
public:
    Progress(ProgressDisplay display, std::FILE* out, std::size_t total) : display_(display), out_(out), total_(total) {}

    void frame_done(int frame, const std::string& file, bool skipped, double ms) {
        ++done_;
        if (!skipped) ++rendered_;
        if (display_ == ProgressDisplay::lines) {
            if (skipped) {
                std::fprintf(out_, "frame %d: %s present, skipped (%zu/%zu)\n", frame, file.c_str(), done_, total_);
            } else {
                std::fprintf(out_, "frame %d: %s %.1f ms (%zu/%zu)\n", frame, file.c_str(), ms, done_, total_);
            }
            std::fflush(out_);
        } else if (display_ == ProgressDisplay::terminal) {
            const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
            const double fps = seconds > 0 ? double(rendered_) / seconds : 0.0;
            const double left = fps > 0 ? double(total_ - done_) / fps : 0.0;
            // \33[K clears what a longer previous line left behind.
            std::fprintf(out_, "\r%zu/%zu frames, %.2f frames/s, %d:%02d left\33[K", done_, total_, fps,
                         int(left) / 60, int(left) % 60);
            std::fflush(out_);
            line_open_ = true;
        }
    }

    void finish() {
        if (line_open_) std::fputc('\n', out_);
        line_open_ = false;
    }

private:
    ProgressDisplay display_;
    std::FILE* out_;
    std::size_t total_, done_ = 0, rendered_ = 0;
    Clock::time_point start_ = Clock::now();
    bool line_open_ = false;  // the terminal line is written and not yet ended
};

bool all_present(const std::vector<std::string>& paths) {
    std::error_code ignored;
    for (const std::string& path : paths)
        if (!std::filesystem::is_regular_file(path, ignored)) return false;
    return true;
}

// A frame to render and the files it goes to.
struct Pending {
    int frame;
    std::vector<std::string> paths;
};

// What writing one frame's outputs gave: every output is tried; errors in order.
struct WriteResult {
    double write_ms = 0, write_cpu_ms = 0;
    Clock::time_point end;
    std::vector<std::string> errors;
};

WriteResult write_outputs(const RenderedImage& image, const std::vector<std::string>& paths) {
    WriteResult result;
    const Clock::time_point start = Clock::now();
    const double cpu_start = cpu_ms(CLOCK_THREAD_CPUTIME_ID);
    for (const std::string& path : paths) {
        try {
            write_image(image, path);
        } catch (const std::exception& e) {
            result.errors.push_back(e.what());
        }
    }
    result.write_ms = ms_since(start);
    result.write_cpu_ms = cpu_ms(CLOCK_THREAD_CPUTIME_ID) - cpu_start;
    result.end = Clock::now();
    return result;
}

// A rendered frame whose outputs are being written, and what its record needs.
struct InFlight {
    const Pending* item;
    Clock::time_point start;
    double setup_ms, render_ms, render_cpu_ms;
    FrameStats stats;
    std::future<WriteResult> written;
};

}  // namespace

std::vector<WorkItem> work_items(const BatchJob& job) {
    std::vector<WorkItem> items;
    for (std::size_t s = 0; s < job.scene_paths.size(); ++s) {
        if (!job.frames) {
            items.push_back({s, 0});
            continue;
        }
        for (const int frame : *job.frames) items.push_back({s, frame});
    }
    return items;
}

namespace {

// Two -o patterns that name the same file for different frames or scenes
// (x{frame}.png at 11 and x1{frame}.png at 1) would overwrite one another:
// refused before anything renders. Jobs of more files than are worth listing
// are left to the patterns' own checks.
void check_scene_placeholders(const BatchJob& job);

void check_outputs_distinct(const BatchJob& job) {
    const std::vector<int> frames = job.frames ? *job.frames : std::vector<int>{0};
    const std::size_t files = frames.size() * job.scene_paths.size() * job.outputs.size();
    if (job.outputs.size() < 2 || files > 4'000'000) return;
    struct Writer {
        std::size_t output;
        std::size_t scene;
        int frame;
    };
    std::map<std::string, Writer> writers;
    for (std::size_t s = 0; s < job.scene_paths.size(); ++s)
        for (const int frame : frames)
            for (std::size_t o = 0; o < job.outputs.size(); ++o) {
                const std::string file = expand_output_pattern(job.outputs[o], stem_of(job.scene_paths[s]), frame);
                const auto [it, added] = writers.emplace(file, Writer{o, s, frame});
                if (added || (it->second.frame == frame && it->second.scene == s)) continue;
                const Writer& first = it->second;
                throw std::invalid_argument(
                    "-o '" + job.outputs[first.output] + "' (frame " + std::to_string(first.frame) + " of " +
                    job.scene_paths[first.scene] + ") and -o '" + job.outputs[o] + "' (frame " +
                    std::to_string(frame) + " of " + job.scene_paths[s] + ") both write '" + file +
                    "': one would overwrite the other");
            }
}

}  // namespace

void check_job(const BatchJob& job) {
    for (const std::string& out : job.outputs) {
        if (!is_supported_image_path(out))
            throw ImageError(out + ": unsupported output format (expected .png or .exr)");
        check_output_pattern(out);
    }
    if (job.frames && job.frames->size() > 1) {
        for (const std::string& out : job.outputs)
            if (!has_frame_placeholder(out))
                throw std::invalid_argument("with several frames every -o must contain {frame} or {frame:0N}, got '" +
                                            out + "'");
    }
    if (job.scene_paths.size() >= 2) check_scene_placeholders(job);
    check_outputs_distinct(job);  // after the rules above, which name the mistake more plainly
}

namespace {

void check_scene_placeholders(const BatchJob& job) {
    for (const std::string& out : job.outputs) {
        if (out.find("{scene}") == std::string::npos)
            throw std::invalid_argument("with several scenes every -o must contain {scene} (the scene file's stem), "
                                        "got '" + out + "'");
    }
    std::set<std::string> stems;
    for (const std::string& path : job.scene_paths) {
        if (!stems.insert(stem_of(path)).second)
            throw std::invalid_argument("two scene files have the stem '" + stem_of(path) +
                                        "': their outputs would overwrite each other");
    }
}

}  // namespace

BatchResult run_batch(const BatchJob& job, Renderer& renderer, std::FILE* progress_out, std::FILE* errors) {
    const std::vector<WorkItem> all = work_items(job);
    const std::vector<WorkItem> mine = take_shard(all, job.shard.shard);
    if (job.shard.sharded()) {
        std::fprintf(progress_out, "shard %s (from %s): %zu of %zu frames\n", shard_text(job.shard.shard).c_str(),
                     job.shard.origin.c_str(), mine.size(), all.size());
        std::fflush(progress_out);
    }
    RecordLog log(job.log_path);
    Progress progress(job.progress, progress_out, mine.size());
    const std::string shard_json = json_string(shard_text(job.shard.shard));
    BatchResult result;

    for (std::size_t first = 0; first < mine.size();) {
        // This scene's items: contiguous, since work_items goes scene by scene.
        const std::size_t scene_index = mine[first].scene;
        std::size_t end = first;
        while (end < mine.size() && mine[end].scene == scene_index) ++end;
        const std::string& scene_path = job.scene_paths[scene_index];
        const std::string stem = stem_of(scene_path);
        ++result.scenes_with_work;

        std::vector<Pending> pending;
        for (std::size_t i = first; i < end; ++i) {
            Pending item{mine[i].frame, {}};
            for (const std::string& pattern : job.outputs)
                item.paths.push_back(expand_output_pattern(pattern, stem, item.frame));
            if (job.skip_existing && all_present(item.paths)) {
                ++result.frames_skipped;
                progress.frame_done(item.frame, item.paths.front(), true, 0.0);
            } else {
                pending.push_back(std::move(item));
            }
        }
        first = end;
        if (pending.empty()) continue;  // everything present: the scene is not even loaded

        try {
            Scene scene = job.load_scene(scene_path);
            const int frame_count = scene_frame_count(scene);
            for (const Pending& item : pending) {
                if (item.frame >= frame_count)
                    throw std::out_of_range(scene_path + ": --frames asks for frame " + std::to_string(item.frame) +
                                            (scene.animation ? ", but the animation has frames 0-" +
                                                                   std::to_string(frame_count - 1)
                                                             : ", but the scene has no [animation] (only frame 0)"));
            }
            // The previous frame's outputs are encoded and written on another thread while this
            // frame renders (PNG encoding costs about as much CPU as a render): a copy of the
            // image, since the renderer reuses its own. Outputs, records and their order are
            // those of writing each frame in turn.
            RenderedImage copy;
            std::optional<InFlight> in_flight;  // declared after the copy: destroyed (joined) first
            const auto finish = [&](InFlight& frame) {
                const WriteResult written = frame.written.get();
                for (std::size_t e = 0; e + 1 < written.errors.size(); ++e)
                    std::fprintf(errors, "tessera: error: %s\n", written.errors[e].c_str());
                if (!written.errors.empty()) throw ImageError(written.errors.back());
                if (job.after_write) job.after_write(written.write_ms);
                const double total_ms = std::chrono::duration<double, std::milli>(written.end - frame.start).count();
                ++result.frames_rendered;
                char numbers[400];
                std::snprintf(numbers, sizeof numbers,
                              ", \"ms\": %.3f, \"setup_ms\": %.3f, \"render_ms\": %.3f, \"write_ms\": %.3f, "
                              "\"render_cpu_ms\": %.3f, \"write_cpu_ms\": %.3f, \"triangles\": %llu, "
                              "\"fragments\": %llu, \"shard\": ",
                              total_ms, frame.setup_ms, frame.render_ms, written.write_ms, frame.render_cpu_ms,
                              written.write_cpu_ms, (unsigned long long)frame.stats.triangles_in,
                              (unsigned long long)frame.stats.fragments_shaded);
                log.write("{\"scene\": " + json_string(scene_path) + ", \"frame\": " + std::to_string(frame.item->frame) +
                          ", \"file\": " + json_string(frame.item->paths.front()) + numbers + shard_json + "}\n");
                progress.frame_done(frame.item->frame, frame.item->paths.front(), false, total_ms);
            };
            try {
                for (const Pending& item : pending) {
                    const Clock::time_point start = Clock::now();
                    set_scene_frame(scene, item.frame);
                    validate_scene(scene);  // an animated value may leave the valid range
                    const double setup_ms = ms_since(start);
                    const Clock::time_point render_start = Clock::now();
                    const double render_cpu_start = cpu_ms(CLOCK_PROCESS_CPUTIME_ID);
                    const RenderedImage& image = renderer.render(scene);
                    const double render_ms = ms_since(render_start);
                    const double render_cpu_ms = cpu_ms(CLOCK_PROCESS_CPUTIME_ID) - render_cpu_start;
                    if (in_flight) {  // the copy it writes is the one this frame's copy goes into
                        InFlight previous = std::move(*in_flight);
                        in_flight.reset();
                        finish(previous);
                    }
                    if (job.after_frame) job.after_frame(renderer, image);
                    copy = image;
                    in_flight = InFlight{&item, start, setup_ms, render_ms, render_cpu_ms, renderer.last_frame_stats(),
                                         std::async(std::launch::async, write_outputs, std::cref(copy), std::cref(item.paths))};
                    if (!job.write_behind) {
                        InFlight now = std::move(*in_flight);
                        in_flight.reset();
                        finish(now);
                    }
                }
                if (in_flight) {
                    InFlight last = std::move(*in_flight);
                    in_flight.reset();
                    finish(last);
                }
            } catch (...) {
                if (in_flight) in_flight->written.wait();  // its copy must outlive the writing
                throw;
            }
        } catch (const std::exception& e) {
            progress.finish();
            const bool internal = dynamic_cast<const std::bad_alloc*>(&e) || dynamic_cast<const std::length_error*>(&e);
            std::fprintf(errors, "tessera: error: %s%s\n", internal ? (scene_path + ": ").c_str() : "",
                         io::error_sentence(e).c_str());
            result.failed_scenes.push_back(scene_path);
        }
    }
    progress.finish();
    return result;
}

}  // namespace tessera::batch
