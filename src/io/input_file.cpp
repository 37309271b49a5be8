#include "io/input_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tessera::io {

namespace fs = std::filesystem;

namespace {

std::string kind_of(const struct stat& st) {
    if (S_ISDIR(st.st_mode)) return "a folder";
    if (S_ISFIFO(st.st_mode)) return "a named pipe (FIFO)";
    if (S_ISCHR(st.st_mode)) return "a character device";
    if (S_ISBLK(st.st_mode)) return "a block device";
    if (S_ISSOCK(st.st_mode)) return "a socket";
    return "not a regular file";
}

[[noreturn]] void refuse_type(const fs::path& path, std::string_view kind, const struct stat& st) {
    throw InputFileError(path, "cannot read " + std::string(kind) + ": it is " + kind_of(st) +
                                   ", not a regular file");
}

void check_stat(const fs::path& path, std::string_view kind, const struct stat& st, std::uint64_t max_bytes) {
    if (!S_ISREG(st.st_mode)) refuse_type(path, kind, st);
    const auto size = std::uint64_t(st.st_size);
    if (size > max_bytes)
        throw InputFileError(path, std::string(kind) + " of " + byte_text(size) + " is larger than the " +
                                       byte_text(max_bytes) + " it can need");
}

struct stat stat_by_name(const fs::path& path, std::string_view kind) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw InputFileError(path, "cannot open " + std::string(kind) + ": " +
                                       (errno == ENOENT ? std::string("no such file") : std::strerror(errno)));
    return st;
}

// An open descriptor of a checked regular file, closed on scope exit.
class CheckedFile {
public:
    CheckedFile(const fs::path& path, std::string_view kind, std::uint64_t max_bytes) : path_(path) {
        check_stat(path, kind, stat_by_name(path, kind), max_bytes);
        // O_NONBLOCK: should the name have become a FIFO since the stat, open does not wait for a writer.
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
        if (fd_ < 0) throw InputFileError(path, "cannot open " + std::string(kind) + ": " + std::strerror(errno));
        struct stat st {};
        if (::fstat(fd_, &st) != 0) {
            const int e = errno;
            ::close(fd_);
            throw InputFileError(path, "cannot read " + std::string(kind) + ": " + std::strerror(e));
        }
        try {
            check_stat(path, kind, st, max_bytes);
        } catch (...) {
            ::close(fd_);
            throw;
        }
        size_ = std::uint64_t(st.st_size);
    }
    ~CheckedFile() { ::close(fd_); }
    CheckedFile(const CheckedFile&) = delete;
    CheckedFile& operator=(const CheckedFile&) = delete;

    std::uint64_t size() const { return size_; }

    // Up to `count` bytes into out; fewer only at the end of the file.
    std::size_t read(std::uint8_t* out, std::size_t count, std::string_view kind) {
        std::size_t done = 0;
        while (done < count) {
            const ssize_t got = ::read(fd_, out + done, count - done);
            if (got < 0 && errno == EINTR) continue;
            if (got < 0) throw InputFileError(path_, "cannot read " + std::string(kind) + ": " + std::strerror(errno));
            if (got == 0) break;
            done += std::size_t(got);
        }
        return done;
    }

private:
    fs::path path_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
};

template <class Bytes>
Bytes read_whole(const fs::path& path, std::uint64_t max_bytes, std::string_view kind) {
    CheckedFile file(path, kind, max_bytes);
    Bytes bytes;
    bytes.resize(std::size_t(file.size()));
    // A file that shrank since the fstat ends early; one that grew is read to its size then.
    const std::size_t got = file.read(reinterpret_cast<std::uint8_t*>(bytes.data()), bytes.size(), kind);
    bytes.resize(got);
    return bytes;
}

}  // namespace

std::string byte_text(std::uint64_t bytes) {
    char text[64];
    if (bytes < 10 * 1024ull) {
        std::snprintf(text, sizeof text, "%llu bytes", (unsigned long long)bytes);
    } else {
        const char* units[] = {"KB", "MB", "GB", "TB", "PB", "EB"};
        double value = double(bytes) / 1024.0;
        int unit = 0;
        while (value >= 1024.0 && unit < 5) value /= 1024.0, ++unit;
        std::snprintf(text, sizeof text, value < 100 ? "%.1f %s" : "%.0f %s", value, units[unit]);
    }
    return text;
}

std::uint64_t check_input_file(const fs::path& path, std::uint64_t max_bytes, std::string_view kind) {
    const struct stat st = stat_by_name(path, kind);
    check_stat(path, kind, st, max_bytes);
    return std::uint64_t(st.st_size);
}

std::vector<std::uint8_t> read_input_file(const fs::path& path, std::uint64_t max_bytes, std::string_view kind) {
    return read_whole<std::vector<std::uint8_t>>(path, max_bytes, kind);
}

std::string read_input_text(const fs::path& path, std::uint64_t max_bytes, std::string_view kind) {
    return read_whole<std::string>(path, max_bytes, kind);
}

std::vector<std::uint8_t> read_input_prefix(const fs::path& path, std::size_t count, std::string_view kind) {
    CheckedFile file(path, kind, std::uint64_t(-1));
    std::vector<std::uint8_t> bytes(std::size_t(std::min<std::uint64_t>(count, file.size())));
    bytes.resize(file.read(bytes.data(), bytes.size(), kind));
    return bytes;
}

void check_output_file(const fs::path& path, std::string_view kind) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return;  // absent (or unreachable: the open that follows says why)
    if (!S_ISREG(st.st_mode))
        throw InputFileError(path, "cannot write " + std::string(kind) + ": it is " + kind_of(st) +
                                       ", not a regular file");
}

}  // namespace tessera::io
