// Output files written to a temporary name beside the target and renamed into place, so that a
// failed or interrupted write never leaves a half-written file: the rename is atomic (same
// folder, same file system), and readers see the old file or the whole new one.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tessera::io {

class WriteError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A name beside `path`, unique to this process and call: "<path>.tmp.<pid>.<n>".
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

// Calls write(temporary), which writes the whole file at `temporary` and returns "" or why it
// failed, then renames the file onto `path`. On any failure the temporary file is removed and
// WriteError is thrown: "<path>: cannot write <what>: reason" or
// "<path>: cannot move the written <what> into place: reason". The folder must exist.
void write_atomically(const std::filesystem::path& path, std::string_view what,
                      const std::function<std::string(const std::filesystem::path& temporary)>& write);

// The same for bytes in memory, and for a copy of another file.
void write_text_atomically(const std::filesystem::path& path, std::string_view text, std::string_view what = "file");
void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to);

// Creates the folders above `path` that are missing; throws WriteError naming the folder.
void create_parent_folders(const std::filesystem::path& path);

}  // namespace tessera::io
