#include "check/atomic_file.hpp"

#include "io/atomic_file.hpp"

namespace tessera::check {

namespace fs = std::filesystem;

void write_text_atomically(const fs::path& path, std::string_view text) {
    io::create_parent_folders(path);
    io::write_text_atomically(path, text);
}

void write_png_atomically(const OIIO::ImageBuf& image, const fs::path& path) {
    io::create_parent_folders(path);
    io::write_atomically(path, "image", [&](const fs::path& temporary) -> std::string {
        return image.write(temporary.string(), OIIO::TypeDesc::UINT8, "png") ? "" : image.geterror();
    });
}

void copy_file_atomically(const fs::path& from, const fs::path& to) {
    io::create_parent_folders(to);
    io::copy_file_atomically(from, to);
}

}  // namespace tessera::check
