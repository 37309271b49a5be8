// The bash completion file and the man page, made from the CLI11 definition
// itself so that they cannot drift from it. Hidden options, run at build time
// (src/cli/CMakeLists.txt writes both into the build folder):
//   tessera --print-completion bash    a bash completion script
//   tessera --print-man                a man page (roff), tessera(1)
// Half of the commands are defined in tessera-tools (tools_exec.hpp): tessera
// asks it for theirs with `tessera-tools --print-cli-spec`, a line per command
// and option, and writes one file for both.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace tessera::cli {

// One option or positional argument as --help shows it.
struct OptionDoc {
    std::vector<std::string> names;  // "-o", "--output"; a positional: its name alone
    bool positional = false;
    bool takes_value = false;
    std::string value_type;          // CLI11's, e.g. "TEXT", "INT:{1,4}", "INT:INT in [1 - 16384]"
    std::string default_value;       // "" when none is shown
    std::string description;
};

struct CommandDoc {
    std::string name;
    std::string description;
    std::vector<OptionDoc> options;
};

// Every sub-command of `app` with its options; the stand-ins for tessera-tools'
// commands (prefix commands) are left out.
std::vector<CommandDoc> describe_commands(const CLI::App& app);

// A line-based text of `commands` (tab-separated fields), and back.
std::string to_spec(const std::vector<CommandDoc>& commands);
std::vector<CommandDoc> from_spec(std::string_view spec);

std::string bash_completion(const std::vector<CommandDoc>& commands);
std::string man_page(const std::vector<CommandDoc>& commands, std::string_view version);

// argv[1] is --print-completion or --print-man.
bool is_docs_request(std::string_view argument);
// tessera's side: its own commands and tessera-tools', printed to stdout. Exit status.
int print_docs(const CLI::App& app, int argc, char** argv);
// tessera-tools' side: `--print-cli-spec`.
inline constexpr std::string_view kSpecRequest = "--print-cli-spec";

}  // namespace tessera::cli
