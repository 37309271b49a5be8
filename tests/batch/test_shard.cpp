// Tests for src/batch/shard.cpp: --shard, the schedulers' environments, and
// that the shards of any count cover every item exactly once.
#include <map>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "batch/frames.hpp"
#include "batch/shard.hpp"

using namespace tessera::batch;

namespace {

Environment fake_environment(std::map<std::string, std::string> values) {
    return [values](std::string_view name) -> std::optional<std::string> {
        const auto found = values.find(std::string(name));
        if (found == values.end()) return std::nullopt;
        return found->second;
    };
}

std::string error_of(const std::optional<std::string>& option, std::optional<int> count,
                     std::map<std::string, std::string> env) {
    try {
        choose_shard(option, count, fake_environment(std::move(env)));
    } catch (const ShardError& error) {
        return error.what();
    }
    FAIL_CHECK("no ShardError");
    return "";
}

// A Slurm array task's variables ("" leaves one out).
std::map<std::string, std::string> slurm_task(const char* id, const char* min, const char* count, const char* step = "") {
    std::map<std::string, std::string> env;
    const auto set = [&env](const char* name, const char* value) {
        if (*value != '\0') env.emplace(name, value);
    };
    set("SLURM_ARRAY_TASK_ID", id);
    set("SLURM_ARRAY_TASK_MIN", min);
    set("SLURM_ARRAY_TASK_COUNT", count);
    set("SLURM_ARRAY_TASK_STEP", step);
    return env;
}

}  // namespace

TEST_CASE("--shard I/N: 1-based text, 0-based index, malformed values refused") {
    CHECK(parse_shard("1/1") == Shard{0, 1});
    CHECK(parse_shard("3/7") == Shard{2, 7});
    CHECK(shard_text(Shard{2, 7}) == "3/7");
    for (const char* bad : {"", "3", "0/4", "5/4", "1/0", "-1/4", "1/-4", "a/4", "1/4x", " 1/4", "1/1000001"})
        CHECK_THROWS_AS(parse_shard(bad), ShardError);
    CHECK_THROWS_WITH(parse_shard("0/4"), "--shard '0/4': I counts from 1 and must be in 1..N");
}

TEST_CASE("the shard comes from --shard, else Slurm's array variables, else JOB_COMPLETION_INDEX") {
    const std::map<std::string, std::string> slurm = slurm_task("6", "4", "4");
    SUBCASE("nothing: the whole work") {
        const ShardChoice choice = choose_shard(std::nullopt, std::nullopt, fake_environment({}));
        CHECK(choice.shard == Shard{0, 1});
        CHECK_FALSE(choice.sharded());
    }
    SUBCASE("--shard wins over the environment") {
        const ShardChoice choice = choose_shard("2/3", std::nullopt, fake_environment(slurm));
        CHECK(choice.shard == Shard{1, 3});
        CHECK(choice.origin == "--shard 2/3");
        CHECK(choice.sharded());
    }
    SUBCASE("Slurm: ID − MIN of COUNT (an array 4-7)") {
        const ShardChoice choice = choose_shard(std::nullopt, std::nullopt, fake_environment(slurm));
        CHECK(choice.shard == Shard{2, 4});
        CHECK(choice.origin == "SLURM_ARRAY_TASK_ID=6 (min 4, step 1, count 4)");
    }
    SUBCASE("Slurm with a step (--array=0-12:4): (ID − MIN) / STEP") {
        CHECK(choose_shard(std::nullopt, std::nullopt, fake_environment(slurm_task("8", "0", "4", "4"))).shard ==
              Shard{2, 4});
        CHECK(error_of(std::nullopt, std::nullopt, slurm_task("6", "0", "4", "4")).find("an array with gaps") !=
              std::string::npos);
    }
    SUBCASE("Slurm: an array with gaps, missing or malformed variables, a disagreeing --shard-count") {
        // --array=4,5,7,9: count 4, min 4
        CHECK(error_of(std::nullopt, std::nullopt, slurm_task("9", "4", "4")) ==
              "SLURM_ARRAY_TASK_ID=9 (min 4, step 1, count 4) is not min + k·step for k < count: an array with gaps "
              "(--array=1,5,7) has no part arithmetic; give --shard I/N");
        CHECK(error_of(std::nullopt, std::nullopt, slurm_task("6", "4", "")).find("SLURM_ARRAY_TASK_COUNT is not set") ==
              0);
        CHECK(error_of(std::nullopt, std::nullopt, slurm_task("6", "four", "4")) == "SLURM_ARRAY_TASK_MIN='four' is not a whole number >= 0");
        CHECK(error_of(std::nullopt, 3, slurm).find("--shard-count 3 disagrees with SLURM_ARRAY_TASK_ID=6") == 0);
        CHECK(choose_shard(std::nullopt, 4, fake_environment(slurm)).shard == Shard{2, 4});
    }
    SUBCASE("Kubernetes: JOB_COMPLETION_INDEX of --shard-count") {
        const std::map<std::string, std::string> k8s{{"JOB_COMPLETION_INDEX", "2"}};
        const ShardChoice choice = choose_shard(std::nullopt, 3, fake_environment(k8s));
        CHECK(choice.shard == Shard{2, 3});
        CHECK(choice.origin == "JOB_COMPLETION_INDEX=2 of --shard-count 3");
        CHECK(error_of(std::nullopt, std::nullopt, k8s).find("give --shard-count") != std::string::npos);
        CHECK(error_of(std::nullopt, 2, k8s) == "JOB_COMPLETION_INDEX=2 is not below --shard-count 2");
        CHECK(error_of(std::nullopt, 2, {{"JOB_COMPLETION_INDEX", "x"}}).find("not a whole number") != std::string::npos);
    }
    SUBCASE("--shard-count alone is a mistake, unless 1") {
        CHECK(error_of(std::nullopt, 4, {}).find("--shard-count 4 without a part") == 0);
        CHECK(choose_shard(std::nullopt, 1, fake_environment({})).shard == Shard{0, 1});
        CHECK(error_of(std::nullopt, 0, {}).find("--shard-count 0") == 0);
    }
}

TEST_CASE("sharding is exact: N = 1, 2, 3, 7 over uneven lists and stepped frame ranges cover each item once") {
    const std::vector<std::string> ranges{"0-239", "0-239:2", "5-100:7", "0-22:3", "3", "0-1", "10-15,40-41,90-100:5"};
    for (const std::string& range : ranges) {
        const std::vector<int> frames = parse_frame_ranges(range);
        for (const int n : {1, 2, 3, 7}) {
            std::map<int, int> times_rendered;
            std::size_t smallest = frames.size(), largest = 0;
            for (int i = 0; i < n; ++i) {
                const std::vector<int> part = take_shard(frames, Shard{i, n});
                smallest = std::min(smallest, part.size());
                largest = std::max(largest, part.size());
                for (const int frame : part) ++times_rendered[frame];
            }
            INFO("--frames " << range << ", N = " << n);
            CHECK(times_rendered.size() == frames.size());
            for (const int frame : frames) CHECK(times_rendered[frame] == 1);
            CHECK(largest - smallest <= 1);  // balanced: parts differ by at most one item
        }
    }
    // Interleaved: shard 2 of 3 of 0-22:3 (0, 3, ..., 21) takes the 2nd, 5th and 8th frames.
    CHECK(take_shard(parse_frame_ranges("0-22:3"), Shard{1, 3}) == std::vector<int>{3, 12, 21});
    // More shards than items: the extra shards get nothing.
    CHECK(take_shard(std::vector<int>{4, 5}, Shard{6, 7}).empty());
}
