// Reading an input file without trusting it: only a regular file is opened
// (a FIFO, device or folder is refused by name before any read, since reading
// one can block forever or never end), and its size is checked against what
// the caller's format can need before the file is read whole.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::io {

// what(): "<path>: <reason>"; reason() alone, for callers that name the file their own way.
class InputFileError : public std::runtime_error {
public:
    InputFileError(const std::filesystem::path& path, const std::string& reason)
        : std::runtime_error(path.string() + ": " + reason), reason_(reason) {}
    const std::string& reason() const { return reason_; }

private:
    std::string reason_;
};

// Byte counts for messages: "8.0 GB", "512 KB", "37 bytes".
std::string byte_text(std::uint64_t bytes);

// The file's size if it is a regular file (symlinks followed) of at most
// max_bytes; `kind` names it in the refusal ("scene file", "texture"). Throws
// InputFileError. For libraries that open files by name themselves.
std::uint64_t check_input_file(const std::filesystem::path& path, std::uint64_t max_bytes, std::string_view kind);

// The whole file, after check_input_file's checks (made again on the open
// file, so a file swapped for a FIFO in between is refused too).
std::vector<std::uint8_t> read_input_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                                          std::string_view kind);
std::string read_input_text(const std::filesystem::path& path, std::uint64_t max_bytes, std::string_view kind);

// The first `count` bytes (fewer if the file is shorter), same checks but no size limit.
std::vector<std::uint8_t> read_input_prefix(const std::filesystem::path& path, std::size_t count,
                                            std::string_view kind);

// For a file the program appends to or overwrites (a --log file): absent, or a
// regular file; a FIFO or device would block or swallow the output. Throws InputFileError.
void check_output_file(const std::filesystem::path& path, std::string_view kind);

}  // namespace tessera::io
