// tessera check: render a suite of scenes, compare each with its golden image,
// write a report (HTML, JUnit, JSON) and optionally update golden images.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "check/suite.hpp"
#include "tessera/renderer.hpp"

namespace tessera::cli {

struct CheckCommand {
    std::vector<std::string> inputs;  // one manifest (check.toml), or scene files / patterns with --golden
    std::string golden_dir;
    std::string scene_root;
    std::string report_dir;           // default: the manifest's `report`, else ./check-report
    std::string junit_path;           // default: <report>/junit.xml
    std::string json_path;            // default: <report>/summary.json
    // --update's values: none given = "failed" (bare --update), "missing", or scene names / globs over them.
    // Values that are scene files or manifests (a .toml, .gltf or .glb path) were inputs that followed
    // a bare --update: run_check moves them back.
    std::vector<std::string> update;
    const CLI::Option* update_option = nullptr;  // whether --update was given at all (bare, it has no values)
    std::vector<std::string> filters;   // --filter GLOB...: only the scenes whose names match
    std::string new_golden_format = "png";
    bool quiet = false;
    std::optional<std::string> shard;  // --shard I/N; default from Slurm / Kubernetes, as `tessera render`
    std::optional<int> shard_count;    // --shard-count N (Kubernetes Indexed Jobs)
    bool merge = false;                // --merge: inputs are shards' report folders, merged into --report
    check::SuiteDefaults defaults;    // thresholds and size overrides from the command line
    RenderSettings settings;
};

// Adds the sub-command and its options to `app`; returns it.
CLI::App* add_check_command(CLI::App& app, CheckCommand& cmd);

// Exit status: 0 every scene passed or warned, 1 any failed, was missing or
// could not be rendered, 2 bad usage or manifest (with --merge: shard reports
// that are unreadable or do not make one run).
int run_check(CheckCommand& cmd);

// Bad usage of `tessera check`: 2, as for every command (usage.hpp).
inline constexpr int kCheckUsageError = 2;

}  // namespace tessera::cli
