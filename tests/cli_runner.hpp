// Running the tessera binary from a test, as a person would from a shell: its
// arguments quoted, stdout and stderr captured in files, and a sanitizer report
// counted as a failure. Needs TESSERA_CLI_PATH (the built binary).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

namespace tessera::test {

struct CliRun {
    int status = -1;  // the exit status, or -1 if killed by a signal
    std::string out;
    std::string err;
};

inline std::string read_file(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// Single quotes for the shell (the test paths hold none).
inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

// `ENV tessera SUBCOMMAND ARGS`, output captured in files beside `dir`. Slurm's and
// Kubernetes' shard variables are unset, so that a test run inside a job array
// renders what the test asks for (`env` may set them again).
inline CliRun run_tessera(const std::filesystem::path& dir, const std::string& subcommand,
                          const std::vector<std::string>& args, const std::string& env = "") {
    std::ostringstream command;
    command << "env -u SLURM_ARRAY_TASK_ID -u JOB_COMPLETION_INDEX " << env << ' ' << quoted(TESSERA_CLI_PATH) << ' '
            << subcommand;
    for (const std::string& arg : args) command << ' ' << quoted(arg);
    const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    command << " >" << quoted(out.string()) << " 2>" << quoted(err.string());
    const int raw = std::system(command.str().c_str());
    CliRun run;
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    run.out = read_file(out);
    run.err = read_file(err);
    // In a sanitizer build the binary is instrumented too: a report is a failure
    // even when the exit status looks like an ordinary error.
    CHECK_MESSAGE(run.err.find("Sanitizer") == std::string::npos, run.err);
    CHECK_MESSAGE(run.err.find("runtime error:") == std::string::npos, run.err);
    return run;
}

}  // namespace tessera::test
