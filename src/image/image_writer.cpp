#include <atomic>
#include <string>

#include <unistd.h>

#include <OpenImageIO/imagebuf.h>

#include "tessera/image_io.hpp"

namespace tessera {

namespace {

enum class ImageFormat { none, png, exr };

ImageFormat format_for(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".png") return ImageFormat::png;
    if (ext == ".exr") return ImageFormat::exr;
    return ImageFormat::none;
}

// A name beside the target, unique to this process and call, so that the
// final rename is atomic (same directory, same file system).
std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
    static std::atomic<unsigned> counter{0};
    std::filesystem::path tmp = path;
    tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    return tmp;
}

}  // namespace

bool is_supported_image_path(const std::filesystem::path& path) { return format_for(path) != ImageFormat::none; }

void write_image(const RenderedImage& image, const std::filesystem::path& path) {
    const ImageFormat format = format_for(path);
    if (format == ImageFormat::none)
        throw ImageError(path.string() + ": unsupported output format '" + path.extension().string() +
                         "' (expected .png or .exr)");
    if (image.width <= 0 || image.height <= 0) throw ImageError(path.string() + ": nothing was rendered");
    const std::size_t values = 3 * std::size_t(image.width) * std::size_t(image.height);
    if (format == ImageFormat::exr && image.radiance.size() != values)
        throw ImageError(path.string() + ": no HDR radiance was kept for this image (RenderSettings::keep_radiance)");
    if (format == ImageFormat::png && image.display.size() != values)
        throw ImageError(path.string() + ": the display image is incomplete");

    OIIO::ImageBuf buffer;
    if (format == ImageFormat::png) {
        const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
        buffer = OIIO::ImageBuf(spec, const_cast<std::uint8_t*>(image.display.data()));
    } else {
        const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
        buffer = OIIO::ImageBuf(spec, const_cast<float*>(image.radiance.data()));
    }
    const std::filesystem::path tmp = temporary_path_for(path);
    const bool written = format == ImageFormat::png ? buffer.write(tmp.string(), OIIO::TypeDesc::UINT8, "png")
                                                    : buffer.write(tmp.string(), OIIO::TypeDesc::HALF, "openexr");
    if (!written) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        std::string reason = buffer.geterror();
        if (reason.empty()) reason = "write failed";
        throw ImageError(path.string() + ": cannot write image: " + reason);
    }
    std::error_code error;
    std::filesystem::rename(tmp, path, error);
    if (error) {
        std::filesystem::remove(tmp, error);
        throw ImageError(path.string() + ": cannot move the written image into place: " + error.message());
    }
}

}  // namespace tessera
