// Sharding: splitting a list of work items (frames, scenes, test cases) into
// N parts so that N processes, each taking one part, do every item exactly
// once. A part is chosen on the command line (--shard I/N) or taken from the
// scheduler's environment: a Slurm job array's task or a Kubernetes Indexed
// Job's completion index. Used by `tessera render`; meant for `tessera check` too.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::batch {

// One part of N. Written "I/N" with I counted from 1 (as jest's and
// playwright's --shard), held counted from 0.
struct Shard {
    int index = 0;  // 0 .. count − 1
    int count = 1;  // >= 1
    friend bool operator==(const Shard&, const Shard&) = default;
};

inline constexpr int kMaxShards = 1000000;

// A shard that cannot be used: a malformed --shard, or an environment that
// names none consistently. what() says which value and what was expected.
class ShardError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// "I/N" with 1 <= I <= N <= kMaxShards. Throws ShardError.
Shard parse_shard(std::string_view text);
std::string shard_text(const Shard& shard);  // "I/N", 1-based

// A shard and where it came from, for the line a run prints.
struct ShardChoice {
    Shard shard;
    std::string origin;  // e.g. "--shard 2/4", "SLURM_ARRAY_TASK_ID=5 (min 4, step 1, count 4)"
    bool sharded() const { return shard.count > 1 || !origin.empty(); }
};

// Reads an environment variable; nullopt when unset.
using Environment = std::function<std::optional<std::string>(std::string_view name)>;
Environment process_environment();  // getenv

// The shard a run takes, first match wins:
// 1. `option` (--shard I/N), when given;
// 2. a Slurm job array task: SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_MIN,
//    SLURM_ARRAY_TASK_COUNT and SLURM_ARRAY_TASK_STEP (default 1): index =
//    (ID − MIN) / STEP, count = COUNT. An array with gaps (--array=1,5,7) has
//    no such arithmetic and is refused: give --shard then;
// 3. a Kubernetes Indexed Job: JOB_COMPLETION_INDEX (0-based) of `count`
//    parts, the Job's completions, which the environment does not hold;
// 4. otherwise the whole work: 1/1, origin empty.
// `count` (--shard-count), when given with Slurm, must agree with it.
// Throws ShardError naming the variable at fault.
ShardChoice choose_shard(const std::optional<std::string>& option, std::optional<int> count, const Environment& env);

// The items of `item_count` that `shard` takes: item j belongs to shard
// j mod count (interleaved rather than in blocks, so that each shard gets a
// sample of the whole range: frames whose cost varies along an animation
// spread evenly, and the first finished frames of all shards preview it all).
// Ascending; the shards of one count partition 0 .. item_count − 1.
std::vector<std::size_t> shard_items(std::size_t item_count, const Shard& shard);

template <typename Item>
std::vector<Item> take_shard(const std::vector<Item>& items, const Shard& shard) {
    std::vector<Item> taken;
    for (const std::size_t i : shard_items(items.size(), shard)) taken.push_back(items[i]);
    return taken;
}

}  // namespace tessera::batch
