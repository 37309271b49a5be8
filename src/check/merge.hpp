// Merging the reports of the shards of one check run (`tessera check --shard
// I/N` in N processes) into the report one unsharded run would have written.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "check/runner.hpp"

namespace tessera::check {

// Inputs that cannot make one run: an unreadable summary.json, shards of
// different splits or suites, a shard given twice or missing, a scene in two
// shards, an image a summary names that is not there. what() names the file.
class MergeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads <dir>/summary.json of every shard report folder and checks that they
// are the N parts of one split (each part once). The scenes come back in the
// suite's order, as one run lists them (a shard took every N-th scene); the
// report images each shard wrote under its folder are copied (or hard-linked)
// to the same place under merged_dir (its earlier images removed first), so
// that every link of the merged report stays inside its folder. seconds is the sum of the shards' (the work, not the wall time).
// The caller writes the reports. Throws MergeError.
CheckRun merge_shard_reports(const std::vector<std::filesystem::path>& shard_dirs,
                             const std::filesystem::path& merged_dir);

}  // namespace tessera::check
