// Output files written to a temporary name beside the target and renamed into
// place, so that nothing is ever half-written (io/atomic_file.hpp does the work;
// here the folders above the file are created first).
#pragma once

#include <filesystem>
#include <string_view>

#include <OpenImageIO/imagebuf.h>

namespace tessera::check {

// Throws std::runtime_error (io::WriteError) naming the file.
void write_text_atomically(const std::filesystem::path& path, std::string_view text);
void write_png_atomically(const OIIO::ImageBuf& image, const std::filesystem::path& path);  // 8-bit, tagged sRGB
void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to);
// A hard link where the file system allows one (cheap for a report's copies of
// golden images, which are replaced by renaming, never rewritten), else a copy.
void link_or_copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace tessera::check
