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
    // Every report image is display-referred: tagged sRGB (an sRGB chunk), whatever the buffer was read
    // from. An EXR's "linear" tag would write gAMA 1.0, and browsers would show the preview washed out.
    OIIO::ImageBuf tagged(image);
    tagged.specmod().attribute("oiio:ColorSpace", "sRGB");
    io::write_atomically(path, "image", [&](const fs::path& temporary) -> std::string {
        return tagged.write(temporary.string(), OIIO::TypeDesc::UINT8, "png") ? "" : tagged.geterror();
    });
}

void copy_file_atomically(const fs::path& from, const fs::path& to) {
    io::create_parent_folders(to);
    io::copy_file_atomically(from, to);
}

void link_or_copy_file_atomically(const fs::path& from, const fs::path& to) {
    io::create_parent_folders(to);
    io::write_atomically(to, "file", [&](const fs::path& temporary) -> std::string {
        std::error_code error;
        fs::create_hard_link(from, temporary, error);
        if (error) fs::copy_file(from, temporary, error);  // another file system, or links not allowed
        return error ? error.message() : "";
    });
}

}  // namespace tessera::check
