#include "io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

namespace tessera::io {

namespace fs = std::filesystem;

fs::path temporary_path_for(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path temporary = path;
    temporary += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    return temporary;
}

void write_atomically(const fs::path& path, std::string_view what,
                      const std::function<std::string(const fs::path& temporary)>& write) {
    const fs::path temporary = temporary_path_for(path);
    std::string reason;
    try {
        reason = write(temporary);
    } catch (...) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw;
    }
    std::error_code error;
    if (reason.empty()) fs::rename(temporary, path, error);
    // rename() does nothing when both names are links to one file already (a hard-linked copy of
    // a file linked there before): the temporary name is then still there.
    if (reason.empty() && !error) fs::remove(temporary, error);
    if (!reason.empty() || error) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        if (!reason.empty())
            throw WriteError(path.string() + ": cannot write " + std::string(what) + ": " + reason);
        throw WriteError(path.string() + ": cannot move the written " + std::string(what) + " into place: " + error.message());
    }
}

void write_text_atomically(const fs::path& path, std::string_view text, std::string_view what) {
    write_atomically(path, what, [&](const fs::path& temporary) -> std::string {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out.write(text.data(), std::streamsize(text.size()));
        out.close();
        return out ? "" : std::strerror(errno);  // the failed open, write or close's reason
    });
}

void copy_file_atomically(const fs::path& from, const fs::path& to) {
    write_atomically(to, "a copy of " + from.string(), [&](const fs::path& temporary) -> std::string {
        std::error_code error;
        fs::copy_file(from, temporary, fs::copy_options::overwrite_existing, error);
        return error ? error.message() : "";
    });
}

void create_parent_folders(const fs::path& path) {
    std::error_code error;
    if (path.has_parent_path()) fs::create_directories(path.parent_path(), error);
    if (error) throw WriteError(path.parent_path().string() + ": cannot create folder: " + error.message());
}

}  // namespace tessera::io
