#include "cli/tools_exec.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

namespace tessera::cli {

const std::vector<ToolCommand>& tool_commands() {
    static const std::vector<ToolCommand> commands = {
        {"bench", "Render a scene many times and report time per stage"},
        {"contact-sheet", "Tile rendered frames (or any images) into one PNG"},
        {"check", "Render scene suites and compare them with golden images (regression testing)"},
    };
    return commands;
}

bool is_tool_command(std::string_view argument) {
    for (const ToolCommand& command : tool_commands())
        if (argument == command.name) return true;
    return false;
}

std::filesystem::path tools_executable(const char* argv0) {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    const std::filesystem::path dir = error ? std::filesystem::path(argv0).parent_path() : self.parent_path();
    // Beside this executable in the build tree; in an installed tree bin/tessera finds it in
    // lib/tessera/ (TESSERA_HELPERS_FROM_BIN, relative, so the tree may be moved).
    std::filesystem::path tools = dir / "tessera-tools";
#ifdef TESSERA_HELPERS_FROM_BIN
    if (std::filesystem::path installed = dir / TESSERA_HELPERS_FROM_BIN / "tessera-tools";
        !std::filesystem::exists(tools, error) && std::filesystem::exists(installed, error))
        tools = installed.lexically_normal();
#endif
    return tools;
}

int exec_tools(int argc, char** argv) {
    const std::filesystem::path tools = tools_executable(argv[0]);
    ::execv(tools.c_str(), argv);  // argv[0] stays: messages and usage still say "tessera"
    std::fprintf(stderr, "tessera: error: '%s' is part of tessera-tools, which cannot run from '%s': %s\n",
                 argc > 1 ? argv[1] : "", tools.c_str(), std::strerror(errno));
    return 1;
}

}  // namespace tessera::cli
