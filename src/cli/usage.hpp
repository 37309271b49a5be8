// Usage errors of both binaries (tessera and tessera-tools): every mistake on
// the command line is one line `tessera: error: ...` and exit status 2, with a
// "did you mean" for a mistyped command or option. Exit status 1 stays for
// work that failed (a scene that does not load, a file that cannot be written).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace tessera::cli {

inline constexpr int kUsageExit = 2;

// A command line that cannot be run as given (options that exclude each other,
// a file of the wrong kind): main() prints it as a usage error, exit status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Optimal-string-alignment distance: insertions, deletions, substitutions and
// swaps of two neighbours each cost 1 ("widht" is 1 from "width").
std::size_t edit_distance(std::string_view a, std::string_view b);

// The name in `names` nearest to `word`, if it is near enough to be a typo of it.
std::optional<std::string> closest_name(std::string_view word, const std::vector<std::string>& names);

// Every option name of `command` as typed (--width, -o), help included.
std::vector<std::string> option_names(const CLI::App& command);

// Turns CLI11's parse error into the one-line message and the exit status:
// --help and --version print as CLI11 does and return 0; every other error
// prints `tessera: error: [COMMAND: ]MESSAGE` and returns kUsageExit.
int report_parse_error(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv);

// Prints `tessera: error: MESSAGE` (one line: newlines become "; ").
void print_error(std::string_view message);

// What CLI11's `always_capture_default` shows for an option whose 0 means
// "the scene's own": nothing (its description says so).
inline CLI::Option* no_default_shown(CLI::Option* option) { return option->default_str(""); }

// Once every option is defined: an empty list shows no "=[]" in --help.
void hide_empty_defaults(CLI::App& app);

}  // namespace tessera::cli
