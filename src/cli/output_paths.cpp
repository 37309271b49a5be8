#include "cli/output_paths.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "cli/usage.hpp"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

fs::path folder_of(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? fs::path(".") : parent;
}

[[noreturn]] void refuse(const std::string& path, std::string_view what, const std::string& reason) {
    throw UsageError(path + ": cannot write " + std::string(what) + ": " + reason);
}

// Creating (and removing) a file is the only sure test: access() ignores
// read-only mounts and ACLs the way the later write would not.
void probe_folder(const fs::path& folder, const std::string& path, std::string_view what) {
    std::error_code error;
    if (!fs::is_directory(folder, error))
        refuse(path, what, "the folder '" + folder.string() + "' does not exist");
    const fs::path probe = folder / (".tessera-write-test." + std::to_string(::getpid()));
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) refuse(path, what, "the folder '" + folder.string() + "' takes no new file (" + std::strerror(errno) + ")");
    ::close(fd);
    ::unlink(probe.c_str());
}

}  // namespace

void create_parent_folders(const std::string& path, std::string_view what) {
    const fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) return;
    std::error_code error;
    fs::create_directories(folder, error);
    if (error) refuse(path, what, "cannot create the folder '" + folder.string() + "' (" + error.message() + ")");
}

void check_not_folder(const std::string& path, std::string_view what) {
    std::error_code error;
    if (fs::is_directory(path, error)) refuse(path, what, "it is a folder");
}

void check_writable_file(const std::string& path, std::string_view what, bool append) {
    std::error_code error;
    check_not_folder(path, what);
    probe_folder(folder_of(path), path, what);
    if (append && fs::exists(path, error) && ::access(path.c_str(), W_OK) != 0)
        refuse(path, what, std::string("the file is not writable (") + std::strerror(errno) + ")");
}

void check_writable_folder(const std::string& folder, std::string_view what) {
    std::error_code error;
    if (fs::exists(folder, error) && !fs::is_directory(folder, error)) refuse(folder, what, "it is a file, not a folder");
    fs::create_directories(folder, error);
    if (error) refuse(folder, what, "cannot create the folder (" + error.message() + ")");
    probe_folder(folder, folder, what);
}

}  // namespace tessera::cli
