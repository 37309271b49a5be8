#include "check/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <stdexcept>
#include <string>

namespace tessera::check {

namespace fs = std::filesystem;

namespace {

fs::path temporary_path_for(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path tmp = path;
    tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    return tmp;
}

void move_into_place(const fs::path& tmp, const fs::path& path) {
    std::error_code error;
    fs::rename(tmp, path, error);
    if (error) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw std::runtime_error(path.string() + ": cannot move the written file into place: " + error.message());
    }
}

void make_parent(const fs::path& path) {
    std::error_code error;
    if (path.has_parent_path()) fs::create_directories(path.parent_path(), error);
    if (error) throw std::runtime_error(path.parent_path().string() + ": cannot create folder: " + error.message());
}

}  // namespace

void write_text_atomically(const fs::path& path, std::string_view text) {
    make_parent(path);
    const fs::path tmp = temporary_path_for(path);
    {
        std::ofstream out(tmp, std::ios::binary);
        out.write(text.data(), std::streamsize(text.size()));
        out.close();
        if (!out) {
            std::error_code ignored;
            fs::remove(tmp, ignored);
            throw std::runtime_error(path.string() + ": cannot write file");
        }
    }
    move_into_place(tmp, path);
}

void write_png_atomically(const OIIO::ImageBuf& image, const fs::path& path) {
    make_parent(path);
    const fs::path tmp = temporary_path_for(path);
    // Every report image is display-referred: tagged sRGB (an sRGB chunk), whatever the buffer was read
    // from. An EXR's "linear" tag would write gAMA 1.0, and browsers would show the preview washed out.
    OIIO::ImageBuf tagged(image);
    tagged.specmod().attribute("oiio:ColorSpace", "sRGB");
    if (!tagged.write(tmp.string(), OIIO::TypeDesc::UINT8, "png")) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw std::runtime_error(path.string() + ": cannot write image: " + tagged.geterror());
    }
    move_into_place(tmp, path);
}

void link_or_copy_file_atomically(const fs::path& from, const fs::path& to) {
    make_parent(to);
    const fs::path tmp = temporary_path_for(to);
    std::error_code error;
    fs::create_hard_link(from, tmp, error);
    if (error) {  // another file system, or links not allowed: a copy
        copy_file_atomically(from, to);
        return;
    }
    move_into_place(tmp, to);
    // rename() does nothing when both names are links to one file already (the same golden linked twice):
    // then the temporary name is still there.
    fs::remove(tmp, error);
}

void copy_file_atomically(const fs::path& from, const fs::path& to) {
    make_parent(to);
    const fs::path tmp = temporary_path_for(to);
    std::error_code error;
    fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, error);
    if (error) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw std::runtime_error(to.string() + ": cannot copy " + from.string() + ": " + error.message());
    }
    move_into_place(tmp, to);
}

}  // namespace tessera::check
