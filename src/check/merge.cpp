#include "check/merge.hpp"

#include <map>
#include <set>

#include "check/atomic_file.hpp"
#include "check/report.hpp"

namespace tessera::check {

namespace fs = std::filesystem;

namespace {

fs::path normal_absolute(const fs::path& path) { return fs::absolute(path).lexically_normal(); }

bool is_inside(const fs::path& path, const fs::path& folder) {
    const fs::path relative = path.lexically_relative(folder);
    return !relative.empty() && *relative.begin() != "..";
}

// The path with every symbolic link resolved (as far as it exists).
fs::path resolved(const fs::path& path) {
    std::error_code error;
    fs::path real = fs::weakly_canonical(path, error);
    return error ? path : real;
}

// One report image link of a shard, as the merged report links it; an image
// inside the shard's folder is copied (or hard-linked) to the same place under
// merged_dir, so that the merged folder works on its own. The
// copy goes only inside merged_dir (a link such as "a/../../x" cannot climb out
// of it), and an image that is a symbolic link, or sits in a linked folder,
// leading out of the shard's folder is refused: merging must not copy the
// machine's files into a report.
std::string merge_image(const std::string& link, const fs::path& shard_dir, const fs::path& merged_dir,
                        const fs::path& summary) {
    if (link.empty()) return link;
    const fs::path target = (shard_dir / link).lexically_normal();
    std::error_code error;
    if (!is_inside(target, shard_dir))  // e.g. a PNG golden linked because the render matched it
        return target.lexically_relative(merged_dir).generic_string();
    if (!is_inside(resolved(target), resolved(shard_dir)))
        throw MergeError(summary.string() + ": the report image " + target.string() +
                         " is a symbolic link (or in a linked folder) leading out of the shard's folder; refused");
    if (!fs::is_regular_file(target, error))
        throw MergeError(summary.string() + ": the report image " + target.string() + " is missing");
    const fs::path relative = target.lexically_relative(shard_dir);
    const fs::path destination = merged_dir / relative;
    if (!is_inside(resolved(destination), resolved(merged_dir)))
        throw MergeError(summary.string() + ": the report image " + relative.string() +
                         " would be written outside the merged report folder " + merged_dir.string() +
                         " (a linked folder there); refused");
    link_or_copy_file_atomically(target, destination);
    return relative.generic_string();
}

}  // namespace

CheckRun merge_shard_reports(const std::vector<fs::path>& shard_dirs, const fs::path& merged_dir) {
    if (shard_dirs.empty()) throw MergeError("no shard report folders to merge");
    const fs::path merged = normal_absolute(merged_dir);
    struct Part {
        fs::path dir;
        fs::path summary;
        CheckRun run;
    };
    std::map<int, Part> parts;  // by shard index
    for (const fs::path& dir : shard_dirs) {
        Part part{normal_absolute(dir), normal_absolute(dir) / "summary.json", {}};
        if (part.dir == merged)
            throw MergeError(dir.string() + ": the merged report folder cannot be one of the shards' folders");
        std::error_code error;
        if (!fs::is_regular_file(part.summary, error))
            throw MergeError(part.summary.string() +
                             ": no such file; give the report folders of the shards (each holds a summary.json)");
        if (!is_inside(resolved(part.summary), resolved(part.dir)))
            throw MergeError(part.summary.string() + ": a symbolic link leading out of the shard's folder; refused");
        try {
            part.run = read_json_summary(part.summary);
        } catch (const SummaryError& e) {
            throw MergeError(e.what());
        }
        const CheckRun& run = part.run;
        if (!parts.empty()) {
            const Part& first = parts.begin()->second;
            if (run.shard.count != first.run.shard.count || run.suite_scenes != first.run.suite_scenes)
                throw MergeError(part.summary.string() + ": shard " + batch::shard_text(run.shard) + " of " +
                                 std::to_string(run.suite_scenes) + " scenes does not belong with " +
                                 first.summary.string() + ": shard " + batch::shard_text(first.run.shard) + " of " +
                                 std::to_string(first.run.suite_scenes) + " scenes");
        }
        if (const auto it = parts.find(run.shard.index); it != parts.end())
            throw MergeError(part.summary.string() + ": shard " + batch::shard_text(run.shard) + " is also " +
                             it->second.summary.string());
        // Before shard_items lists the part: a summary cannot claim more scenes than its shards hold.
        if (run.shard.count < 1 ||
            run.suite_scenes > (run.scenes.size() + 1) * std::size_t(run.shard.count))
            throw MergeError(part.summary.string() + ": shard " + batch::shard_text(run.shard) + " holds " +
                             std::to_string(run.scenes.size()) + " scenes, too few for a suite of " +
                             std::to_string(run.suite_scenes));
        if (run.scenes.size() != batch::shard_items(run.suite_scenes, run.shard).size())
            throw MergeError(part.summary.string() + ": shard " + batch::shard_text(run.shard) + " holds " +
                             std::to_string(run.scenes.size()) + " scenes, but that part of " +
                             std::to_string(run.suite_scenes) + " has " +
                             std::to_string(batch::shard_items(run.suite_scenes, run.shard).size()));
        parts.emplace(run.shard.index, std::move(part));
    }
    const Part& first = parts.begin()->second;
    const int count = first.run.shard.count;
    for (int i = 0; i < count; ++i)
        if (!parts.contains(i))
            throw MergeError("shard " + batch::shard_text({i, count}) + " is missing (" + first.summary.string() +
                             " is of " + std::to_string(count) + "); give every shard's report folder");

    std::map<std::string, fs::path> seen;  // scene name -> the summary it came from
    for (const auto& [index, part] : parts)
        for (const SceneResult& r : part.run.scenes)
            if (const auto [it, added] = seen.emplace(r.name, part.summary); !added)
                throw MergeError(part.summary.string() + ": scene \"" + r.name + "\" is also in " +
                                 it->second.string());

    std::error_code error;
    fs::create_directories(merged / "images", error);
    if (error) throw MergeError(merged_dir.string() + ": cannot create the report folder: " + error.message());
    remove_report_images(merged);

    CheckRun merged_run;
    merged_run.suite_scenes = first.run.suite_scenes;
    merged_run.scenes.resize(first.run.suite_scenes);
    std::set<std::string> isas;
    for (auto& [index, part] : parts) {
        const std::vector<std::size_t> items = batch::shard_items(part.run.suite_scenes, part.run.shard);
        for (std::size_t k = 0; k < items.size(); ++k) {
            SceneResult r = std::move(part.run.scenes[k]);
            r.images.expected = merge_image(r.images.expected, part.dir, merged, part.summary);
            r.images.actual = merge_image(r.images.actual, part.dir, merged, part.summary);
            r.images.diff = merge_image(r.images.diff, part.dir, merged, part.summary);
            merged_run.scenes[items[k]] = std::move(r);
        }
        merged_run.seconds += part.run.seconds;
        merged_run.threads = std::max(merged_run.threads, part.run.threads);
        isas.insert(part.run.isa);
    }
    for (const std::string& isa : isas) merged_run.isa += (merged_run.isa.empty() ? "" : ", ") + isa;
    return merged_run;
}

}  // namespace tessera::check
