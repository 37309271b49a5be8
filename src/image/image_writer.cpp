#include <atomic>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

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

// One EXR channel: its name, where its values are, and how the file stores it.
struct ExrChannel {
    const char* name;
    const float* values;     // this channel's value of pixel 0
    std::size_t stride;      // floats from one pixel to the next
    OIIO::TypeDesc format;   // HALF or FLOAT
};

// The radiance and every AOV plane the image has, named as OpenEXR and
// OpenImageIO expect (image_io.hpp lists them). Colour-like data in [0, 1] is
// stored as half, which holds more than the 8 bits textures give; depth,
// normal and position as float, since half's 11 bits would step by 0.06 at a
// depth of 100.
std::vector<ExrChannel> exr_channels(const RenderedImage& image, const std::filesystem::path& path) {
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    std::vector<ExrChannel> channels;
    const auto add = [&](const std::vector<float>& plane, const char* plane_name,
                         std::initializer_list<const char*> names, OIIO::TypeDesc format) {
        if (plane.empty()) return;
        if (plane.size() != names.size() * pixels)
            throw ImageError(path.string() + ": the image's " + plane_name + " plane holds " +
                             std::to_string(plane.size()) + " values, not " + std::to_string(names.size() * pixels));
        std::size_t c = 0;
        for (const char* name : names) channels.push_back({name, plane.data() + c++, names.size(), format});
    };
    add(image.radiance, "radiance", {"R", "G", "B"}, OIIO::TypeDesc::HALF);
    add(image.aov.depth, "depth", {"Z"}, OIIO::TypeDesc::FLOAT);
    add(image.aov.normal, "normal", {"N.X", "N.Y", "N.Z"}, OIIO::TypeDesc::FLOAT);
    add(image.aov.albedo, "albedo", {"albedo.R", "albedo.G", "albedo.B"}, OIIO::TypeDesc::HALF);
    add(image.aov.roughness, "roughness", {"roughness"}, OIIO::TypeDesc::HALF);
    add(image.aov.metallic, "metallic", {"metallic"}, OIIO::TypeDesc::HALF);
    add(image.aov.position, "position", {"P.X", "P.Y", "P.Z"}, OIIO::TypeDesc::FLOAT);
    return channels;
}

// A failure's reason, never "" (which means success below).
std::string failure(std::string reason) { return reason.empty() ? "write failed" : reason; }

// Returns why the write failed, or "" on success.
std::string write_png(const RenderedImage& image, const std::filesystem::path& tmp) {
    const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf buffer(spec, const_cast<std::uint8_t*>(image.display.data()));
    return buffer.write(tmp.string(), OIIO::TypeDesc::UINT8, "png") ? "" : failure(buffer.geterror());
}

// Returns why the write failed, or "" on success. One multi-channel file, written a scanline at a time so that interleaving
// the planes needs one row of memory, not a second copy of the image.
std::string write_exr(const std::vector<ExrChannel>& channels, int width, int height,
                      const std::filesystem::path& tmp) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("openexr");
    if (!out) return failure(OIIO::geterror());
    bool all_half = true;
    for (const ExrChannel& c : channels) all_half = all_half && c.format == OIIO::TypeDesc::HALF;
    OIIO::ImageSpec spec(width, height, int(channels.size()), all_half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    spec.channelnames.clear();
    for (const ExrChannel& c : channels) {
        if (c.name == std::string_view("Z")) spec.z_channel = int(spec.channelnames.size());
        spec.channelnames.emplace_back(c.name);
        if (!all_half) spec.channelformats.push_back(c.format);
    }
    if (!out->open(tmp.string(), spec)) return failure(out->geterror());
    std::vector<float> row(channels.size() * std::size_t(width));
    for (int y = 0; y < height; ++y) {
        const std::size_t first_pixel = std::size_t(y) * width;
        for (std::size_t c = 0; c < channels.size(); ++c) {
            const float* values = channels[c].values + first_pixel * channels[c].stride;
            for (int x = 0; x < width; ++x) row[x * channels.size() + c] = values[x * channels[c].stride];
        }
        if (!out->write_scanline(y, 0, OIIO::TypeDesc::FLOAT, row.data())) return failure(out->geterror());
    }
    if (!out->close()) return failure(out->geterror());
    return "";
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
    std::vector<ExrChannel> channels;
    if (format == ImageFormat::exr) channels = exr_channels(image, path);

    const std::filesystem::path tmp = temporary_path_for(path);
    std::string reason = format == ImageFormat::png ? write_png(image, tmp)
                                                    : write_exr(channels, image.width, image.height, tmp);
    if (!reason.empty()) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
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
