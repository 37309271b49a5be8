// The sub-commands whose job is image analysis (check, contact-sheet, bench
// with its heat map) are in a second program, tessera-tools, built beside
// tessera: they need OpenImageIO, whose ~260 libraries cost every process
// that links them ~1 s and ~120 MB before main() on our VMs. `tessera render`
// stays free of it; `tessera check ...` execs `tessera-tools check ...`.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace tessera::cli {

struct ToolCommand {
    const char* name;
    const char* description;  // for `tessera --help`
};
const std::vector<ToolCommand>& tool_commands();
bool is_tool_command(std::string_view argument);

// tessera-tools beside this executable.
std::filesystem::path tools_executable(const char* argv0);

// Replaces this process with tessera-tools (beside this executable), same
// arguments. Returns only on failure: prints why and returns exit status 1.
int exec_tools(int argc, char** argv);

}  // namespace tessera::cli
