// What a check run leaves behind for people and CI systems. Each file is
// written to a temporary name and renamed into place.
#pragma once

#include <filesystem>
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
// (runs over parts of a suite merge by concatenating "scenes" and summing "counts").
void write_json_summary(const CheckRun& run, const std::filesystem::path& path);
std::string json_summary(const CheckRun& run);

// One line per scene that is not a pass, for the terminal.
std::string describe(const SceneResult& result);

}  // namespace tessera::check
