#include "batch/shard.hpp"

#include <charconv>
#include <cstdlib>

namespace tessera::batch {
namespace {

// A whole decimal number, the whole text (no sign, no spaces); nullopt otherwise.
std::optional<long long> parse_whole(std::string_view text) {
    long long value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc() || ptr != end || value < 0) return std::nullopt;
    return value;
}

long long require_number(const Environment& env, std::string_view name, std::optional<long long> fallback = {}) {
    const std::optional<std::string> text = env(name);
    if (!text) {
        if (fallback) return *fallback;
        throw ShardError(std::string(name) + " is not set, and the Slurm array task needs it to know its part");
    }
    const std::optional<long long> value = parse_whole(*text);
    if (!value) throw ShardError(std::string(name) + "='" + *text + "' is not a whole number >= 0");
    return *value;
}

}  // namespace

Shard parse_shard(std::string_view text) {
    const std::size_t slash = text.find('/');
    const auto refuse = [&](const std::string& why) {
        return ShardError("--shard '" + std::string(text) + "': " + why);
    };
    if (slash == std::string_view::npos) throw refuse("expected I/N, e.g. 2/4 for the second of four parts");
    const std::optional<long long> part = parse_whole(text.substr(0, slash));
    const std::optional<long long> count = parse_whole(text.substr(slash + 1));
    if (!part || !count) throw refuse("expected I/N with whole numbers, e.g. 2/4");
    if (*count < 1 || *count > kMaxShards) throw refuse("N must be in 1.." + std::to_string(kMaxShards));
    if (*part < 1 || *part > *count) throw refuse("I counts from 1 and must be in 1..N");
    return Shard{int(*part - 1), int(*count)};
}

std::string shard_text(const Shard& shard) {
    return std::to_string(shard.index + 1) + "/" + std::to_string(shard.count);
}

Environment process_environment() {
    return [](std::string_view name) -> std::optional<std::string> {
        const char* value = std::getenv(std::string(name).c_str());
        if (value == nullptr) return std::nullopt;
        return std::string(value);
    };
}

ShardChoice choose_shard(const std::optional<std::string>& option, std::optional<int> count, const Environment& env) {
    if (count && (*count < 1 || *count > kMaxShards))
        throw ShardError("--shard-count " + std::to_string(*count) + ": expected 1.." + std::to_string(kMaxShards));
    if (option) {
        const Shard shard = parse_shard(*option);
        if (count && *count != shard.count)
            throw ShardError("--shard " + *option + " and --shard-count " + std::to_string(*count) + " disagree");
        return {shard, "--shard " + *option};
    }
    if (env("SLURM_ARRAY_TASK_ID")) {
        const long long id = require_number(env, "SLURM_ARRAY_TASK_ID");
        const long long min = require_number(env, "SLURM_ARRAY_TASK_MIN");
        const long long tasks = require_number(env, "SLURM_ARRAY_TASK_COUNT");
        const long long step = require_number(env, "SLURM_ARRAY_TASK_STEP", 1);
        if (tasks < 1 || tasks > kMaxShards)
            throw ShardError("SLURM_ARRAY_TASK_COUNT=" + std::to_string(tasks) + ": expected 1.." +
                             std::to_string(kMaxShards));
        if (step < 1) throw ShardError("SLURM_ARRAY_TASK_STEP=" + std::to_string(step) + ": expected >= 1");
        const std::string origin = "SLURM_ARRAY_TASK_ID=" + std::to_string(id) + " (min " + std::to_string(min) +
                                   ", step " + std::to_string(step) + ", count " + std::to_string(tasks) + ")";
        if (id < min || (id - min) % step != 0 || (id - min) / step >= tasks)
            throw ShardError(origin + " is not min + k·step for k < count: an array with gaps "
                                      "(--array=1,5,7) has no part arithmetic; give --shard I/N");
        if (count && *count != tasks)
            throw ShardError("--shard-count " + std::to_string(*count) + " disagrees with " + origin);
        return {Shard{int((id - min) / step), int(tasks)}, origin};
    }
    if (const std::optional<std::string> text = env("JOB_COMPLETION_INDEX")) {
        const std::optional<long long> index = parse_whole(*text);
        if (!index) throw ShardError("JOB_COMPLETION_INDEX='" + *text + "' is not a whole number >= 0");
        if (!count)
            throw ShardError("JOB_COMPLETION_INDEX=" + *text +
                             " is set but the number of parts is not: give --shard-count (the Job's completions)");
        if (*index >= *count)
            throw ShardError("JOB_COMPLETION_INDEX=" + *text + " is not below --shard-count " + std::to_string(*count));
        return {Shard{int(*index), *count},
                "JOB_COMPLETION_INDEX=" + *text + " of --shard-count " + std::to_string(*count)};
    }
    if (count && *count != 1)
        throw ShardError("--shard-count " + std::to_string(*count) +
                         " without a part: give --shard I/N, or run as a Slurm array task or an Indexed Job");
    return {};
}

std::vector<std::size_t> shard_items(std::size_t item_count, const Shard& shard) {
    std::vector<std::size_t> items;
    if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) return items;
    items.reserve(item_count / std::size_t(shard.count) + 1);
    for (std::size_t j = std::size_t(shard.index); j < item_count; j += std::size_t(shard.count)) items.push_back(j);
    return items;
}

}  // namespace tessera::batch
