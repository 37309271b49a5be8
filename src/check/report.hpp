// What a check run leaves behind for people and CI systems. Each file is
// written to a temporary name and renamed into place.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "check/runner.hpp"

namespace tessera::check {

// report/index.html: every scene a row, worst first, with expected / actual /
// diff images (lazy-loaded files beside it), a slider and flicker view, pixel
// zoom and the numbers. Opens from disk: no server, no network.
void write_html_report(const CheckRun& run, const std::filesystem::path& report_dir);

// JUnit XML: one <testcase> per scene; fail and missing are <failure>s, errors
// <error>s, warnings pass with the warning in <system-out>.
void write_junit_report(const CheckRun& run, const std::filesystem::path& path);

// JSON summary: the run, the counts, and one self-contained record per scene
// (the shards of a run merge with `tessera check --merge`, see check/merge.hpp).
void write_json_summary(const CheckRun& run, const std::filesystem::path& path);
std::string json_summary(const CheckRun& run);

// A summary.json that cannot be read back: missing, not JSON, another format,
// a field missing or of the wrong type. what() starts with the file's path.
class SummaryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The inverse of write_json_summary (for merging the reports of shards).
// Throws SummaryError.
CheckRun read_json_summary(const std::filesystem::path& path);

// One line per scene that is not a pass, for the terminal.
std::string describe(const SceneResult& result);

}  // namespace tessera::check
