// Sharded check runs (src/check/merge.hpp, batch::take_shard): N = 1, 2, 3
// shards of a small suite take every scene once, their merged report says
// what one unsharded run says, and inputs that do not make one run are refused.
#include <doctest/doctest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "batch/shard.hpp"
#include "check/merge.hpp"
#include "check/report.hpp"
#include "check/runner.hpp"
#include "check/suite.hpp"
#include "test_paths.hpp"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = test::output_dir("check_shard") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// ball (fail: its golden is another scene's), broken (error), cube (pass, identical: its
// golden is linked from the report, outside it), more/glint (missing: no golden).
check::Suite suite_with_every_status(const fs::path& dir) {
    const fs::path scenes = test::source_dir() / "tests" / "check" / "scenes";
    const fs::path golden = dir / "golden";
    const check::Suite suite = check::suite_from_arguments(
        {(scenes / "*.toml").string(), (scenes / "more" / "*.toml").string()}, golden, {}, {});
    REQUIRE(suite.scenes.size() == 4);
    check::RunOptions options;
    options.report_dir = dir / "golden_report";
    options.update = check::UpdateMode::missing;
    check::run_check(suite.scenes, options);
    fs::copy_file(golden / "cube.png", golden / "ball.png", fs::copy_options::overwrite_existing);
    fs::remove(golden / "more" / "glint.png");
    return suite;
}

// What the CLI does for `--shard I/N -r dir`: take the part, run it, say which part it is, write the reports.
check::CheckRun run_shard(const check::Suite& suite, const batch::Shard& shard, const fs::path& report_dir) {
    check::RunOptions options;
    options.report_dir = report_dir;
    check::CheckRun run = check::run_check(batch::take_shard(suite.scenes, shard), options);
    run.shard = shard;
    run.suite_scenes = suite.scenes.size();
    check::write_html_report(run, report_dir);
    check::write_json_summary(run, report_dir / "summary.json");
    return run;
}

std::string merge_error(const std::vector<fs::path>& shards, const fs::path& merged) {
    try {
        check::merge_shard_reports(shards, merged);
    } catch (const check::MergeError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string url_decoded(const std::string& url) {
    std::string out;
    for (std::size_t i = 0; i < url.size(); ++i) {
        if (url[i] == '%' && i + 2 < url.size()) {
            out += char(std::stoi(url.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += url[i];
        }
    }
    return out;
}

}  // namespace

TEST_CASE("check shards: 1, 2 and 3 shards take every scene once and merge into the report of one run") {
    const fs::path dir = fresh_dir("split");
    const check::Suite suite = suite_with_every_status(dir);
    check::RunOptions options;
    options.report_dir = dir / "whole";
    check::CheckRun whole = check::run_check(suite.scenes, options);
    whole.shard = {0, 1};
    whole.suite_scenes = suite.scenes.size();
    REQUIRE(whole.count(check::Status::pass) == 1);
    REQUIRE(whole.count(check::Status::fail) == 1);
    REQUIRE(whole.count(check::Status::missing) == 1);
    REQUIRE(whole.count(check::Status::error) == 1);

    for (int count = 1; count <= 3; ++count) {
        CAPTURE(count);
        const fs::path runs = dir / ("of_" + std::to_string(count));
        std::vector<fs::path> shard_dirs;
        std::map<std::string, int> taken;  // scene name -> how many shards took it
        for (int index = 0; index < count; ++index) {
            shard_dirs.push_back(runs / ("shard_" + std::to_string(index + 1)));
            const check::CheckRun part = run_shard(suite, {index, count}, shard_dirs.back());
            for (const check::SceneResult& r : part.scenes) ++taken[r.name];
        }
        CHECK(taken.size() == suite.scenes.size());
        for (const auto& [name, times] : taken) CHECK_MESSAGE(times == 1, name);

        // Merged in the order given or backwards: the same report.
        std::vector<fs::path> backwards(shard_dirs.rbegin(), shard_dirs.rend());
        const check::CheckRun merged = check::merge_shard_reports(backwards, runs / "merged");
        REQUIRE(merged.scenes.size() == whole.scenes.size());
        for (std::size_t i = 0; i < whole.scenes.size(); ++i) {  // the suite's order, the same outcome
            const check::SceneResult& a = whole.scenes[i];
            const check::SceneResult& b = merged.scenes[i];
            CHECK(b.name == a.name);
            CHECK(b.status == a.status);
            CHECK(b.reason == a.reason);
            CHECK(b.compared == a.compared);
            CHECK(b.metrics.pixels_over_fail == a.metrics.pixels_over_fail);
            CHECK(b.metrics.max_error == a.metrics.max_error);
            CHECK(b.metrics.psnr == a.metrics.psnr);  // infinite for the identical cube: null in JSON and back
            CHECK(b.thresholds.max_error == a.thresholds.max_error);
        }
        for (check::Status s : {check::Status::pass, check::Status::warn, check::Status::fail, check::Status::missing,
                                check::Status::error})
            CHECK(merged.count(s) == whole.count(s));
        CHECK(merged.exit_status() == whole.exit_status());

        // The merged summary and JUnit report say what the whole run's say, but for times.
        check::write_html_report(merged, runs / "merged");
        check::write_junit_report(merged, runs / "merged" / "junit.xml");
        check::write_json_summary(merged, runs / "merged" / "summary.json");
        nlohmann::json merged_summary = nlohmann::json::parse(read_text(runs / "merged" / "summary.json"));
        nlohmann::json whole_summary = nlohmann::json::parse(check::json_summary(whole));
        CHECK(merged_summary["counts"] == whole_summary["counts"]);
        CHECK(merged_summary["exit_status"] == whole_summary["exit_status"]);
        CHECK(merged_summary["shard"] == "1/1");
        for (std::size_t i = 0; i < whole.scenes.size(); ++i) {
            CHECK(merged_summary["scenes"][i]["status"] == whole_summary["scenes"][i]["status"]);
            CHECK(merged_summary["scenes"][i]["metrics"] == whole_summary["scenes"][i]["metrics"]);
        }
        const std::string junit = read_text(runs / "merged" / "junit.xml");
        CHECK(junit.find("tests=\"4\" failures=\"2\" errors=\"1\"") != std::string::npos);

        // Every image the merged page shows exists inside the merged folder, the shards' copied in.
        const std::string html = read_text(runs / "merged" / "index.html");
        const std::regex img("<img src=\"([^\"]+)\"");
        int images = 0;
        for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator(); ++it) {
            const std::string link = url_decoded((*it)[1].str());
            CHECK_MESSAGE(fs::is_regular_file(runs / "merged" / link), link);
            ++images;
        }
        CHECK(images >= 6);  // ball: expected, actual, diff and the stacked pair; glint: actual; cube: one
        for (const check::SceneResult& r : merged.scenes)
            if (r.name == "cube") {  // the identical scene's golden, inside the merged folder (linked or copied)
                CHECK(r.images.expected == "images/cube.golden.png");
                CHECK(read_text(runs / "merged" / r.images.expected) == read_text(dir / "golden" / "cube.png"));
            }
    }
}

TEST_CASE("check shards: an empty shard is a run of no scenes, and merges") {
    const fs::path dir = fresh_dir("empty");
    const check::Suite suite = suite_with_every_status(dir);
    std::vector<fs::path> shard_dirs;
    for (int index = 0; index < 5; ++index) {  // 5 shards of 4 scenes: the 5th takes none
        shard_dirs.push_back(dir / ("shard_" + std::to_string(index + 1)));
        const check::CheckRun part = run_shard(suite, {index, 5}, shard_dirs.back());
        CHECK(part.scenes.size() == (index < 4 ? 1u : 0u));
        if (index == 4) CHECK(part.exit_status() == 0);
    }
    const check::CheckRun merged = check::merge_shard_reports(shard_dirs, dir / "merged");
    CHECK(merged.scenes.size() == 4);
    CHECK(merged.exit_status() == 1);
}

TEST_CASE("check merge: a scene in two shards, a shard twice or missing, and unreadable summaries are refused") {
    const fs::path dir = fresh_dir("refused");
    const check::Suite suite = suite_with_every_status(dir);
    const fs::path one = dir / "shard_1", two = dir / "shard_2", merged = dir / "merged";
    run_shard(suite, {0, 2}, one);
    run_shard(suite, {1, 2}, two);
    REQUIRE(merge_error({one, two}, merged) == "(no error)");

    CHECK(merge_error({one, one, two}, merged).find("shard 1/2 is also") != std::string::npos);
    const std::string missing = merge_error({one}, merged);
    CHECK(missing.find("shard 2/2 is missing") != std::string::npos);

    // A copy of shard 2 that also holds a scene of shard 1, as if it were shard 2 of another run.
    const fs::path doubled = dir / "doubled";
    fs::copy(two, doubled, fs::copy_options::recursive);
    nlohmann::json summary = nlohmann::json::parse(read_text(doubled / "summary.json"));
    const nlohmann::json first_of_one = nlohmann::json::parse(read_text(one / "summary.json"))["scenes"][0];
    summary["scenes"][0]["name"] = first_of_one["name"];
    std::ofstream(doubled / "summary.json") << summary.dump(2);
    const std::string twice = merge_error({one, doubled}, merged);
    CHECK(twice.find((doubled / "summary.json").string() + ": scene \"" + first_of_one["name"].get<std::string>() +
                     "\" is also in " + (one / "summary.json").string()) != std::string::npos);

    // Shards of another split of the suite.
    const fs::path other = dir / "other";
    run_shard(suite, {1, 3}, other);
    CHECK(merge_error({one, other}, merged).find("does not belong with") != std::string::npos);

    // Another format, a field of the wrong type, not JSON, no summary at all.
    summary["format"] = "tessera-check-summary/2";
    std::ofstream(doubled / "summary.json") << summary.dump(2);
    CHECK(merge_error({one, doubled}, merged).find((doubled / "summary.json").string() +
                                                   ": not a tessera check summary: format") != std::string::npos);
    summary["format"] = "tessera-check-summary/1";
    summary["scenes"][0]["width"] = "wide";
    std::ofstream(doubled / "summary.json") << summary.dump(2);
    CHECK(merge_error({one, doubled}, merged).find("\"width\" has the wrong type") != std::string::npos);
    std::ofstream(doubled / "summary.json") << "{ not json";
    CHECK(merge_error({one, doubled}, merged).find((doubled / "summary.json").string()) == 0);
    fs::remove(doubled / "summary.json");
    CHECK(merge_error({one, doubled}, merged) == (doubled / "summary.json").string() +
                                                    ": no such file; give the report folders of the shards (each "
                                                    "holds a summary.json)");

    // A report image a summary names that is gone.
    fs::remove_all(two / "images");
    CHECK(merge_error({one, two}, merged).find("the report image") != std::string::npos);
    // The merged folder cannot be a shard's own.
    CHECK(merge_error({one, two}, one).find("cannot be one of the shards' folders") != std::string::npos);
}
