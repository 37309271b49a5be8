#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <Imath/half.h>

#include "image/png_writer.hpp"
#include "io/atomic_file.hpp"
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

// One EXR channel: its name, where its values are, and how the file stores it.
struct ExrChannel {
    const char* name;
    const void* values;      // this channel's value of pixel 0: float, or std::uint32_t for UINT
    std::size_t stride;      // values from one pixel to the next
    Imf::PixelType format;   // HALF or FLOAT (from float values) or UINT in the file
};

// The radiance and every AOV plane the image has, named as OpenEXR and
// OpenImageIO expect (image_io.hpp lists them): the names and types OpenImageIO
// wrote before OpenEXR wrote them directly. Colour-like data in [0, 1] is
// stored as half, which holds more than the 8 bits textures give; depth,
// normal and position as float, since half's 11 bits would step by 0.06 at a
// depth of 100.
std::vector<ExrChannel> exr_channels(const RenderedImage& image, const std::filesystem::path& path) {
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    std::vector<ExrChannel> channels;
    const auto add = [&](const auto& plane, const char* plane_name,
                         std::initializer_list<const char*> names, Imf::PixelType format) {
        if (plane.empty()) return;
        if (plane.size() != names.size() * pixels)
            throw ImageError(path.string() + ": the image's " + plane_name + " plane holds " +
                             std::to_string(plane.size()) + " values, not " + std::to_string(names.size() * pixels));
        std::size_t c = 0;
        for (const char* name : names) channels.push_back({name, plane.data() + c++, names.size(), format});
    };
    add(image.radiance, "radiance", {"R", "G", "B"}, Imf::HALF);
    add(image.aov.depth, "depth", {"Z"}, Imf::FLOAT);
    add(image.aov.normal, "normal", {"N.X", "N.Y", "N.Z"}, Imf::FLOAT);
    add(image.aov.albedo, "albedo", {"albedo.R", "albedo.G", "albedo.B"}, Imf::HALF);
    add(image.aov.roughness, "roughness", {"roughness"}, Imf::HALF);
    add(image.aov.metallic, "metallic", {"metallic"}, Imf::HALF);
    add(image.aov.position, "position", {"P.X", "P.Y", "P.Z"}, Imf::FLOAT);
    // Ids are exact integers: uint, which neither float (past 2^24) nor half could hold.
    add(image.aov.object_id, "object_id", {"object_id"}, Imf::UINT);
    add(image.aov.material_id, "material_id", {"material_id"}, Imf::UINT);
    add(image.aov.shadow, "shadow", {"shadow"}, Imf::HALF);
    return channels;
}

// A failure's reason, never "" (which means success below).
std::string failure(std::string reason) { return reason.empty() ? "write failed" : reason; }

// Returns why the write failed, or "" on success. One multi-channel file
// (OpenEXR 3.1, ZIP compression as OpenImageIO wrote it). Float channels are
// written from the image's planes in place (each slice points into its plane);
// half channels from a converted copy, since OpenEXR converts only between
// matching types: Imath's half(float), round to nearest, as OpenImageIO did.
std::string write_exr(const std::vector<ExrChannel>& channels, int width, int height,
                      const std::filesystem::path& tmp) {
    try {
        const std::size_t pixels = std::size_t(width) * std::size_t(height);
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer frame;
        std::vector<std::vector<Imath::half>> half_planes;
        half_planes.reserve(channels.size());
        for (const ExrChannel& c : channels) {
            header.channels().insert(c.name, Imf::Channel(c.format));
            if (c.format == Imf::HALF) {
                std::vector<Imath::half>& plane = half_planes.emplace_back(pixels);
                const float* values = static_cast<const float*>(c.values);
                for (std::size_t i = 0; i < pixels; ++i) plane[i] = Imath::half(values[i * c.stride]);
                frame.insert(c.name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(plane.data()), sizeof(Imath::half),
                                                sizeof(Imath::half) * std::size_t(width)));
            } else {  // FLOAT and UINT: 4 bytes a value, written in place
                static_assert(sizeof(float) == sizeof(std::uint32_t));
                const std::size_t x_stride = c.stride * sizeof(float);
                frame.insert(c.name, Imf::Slice(c.format, static_cast<char*>(const_cast<void*>(c.values)), x_stride,
                                                x_stride * std::size_t(width)));
            }
        }
        Imf::OutputFile file(tmp.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(height);
    } catch (const std::exception& e) {
        return failure(e.what());
    }
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

    try {
        io::write_atomically(path, "image", [&](const std::filesystem::path& tmp) {
            return format == ImageFormat::png ? write_png_rgb8(image.display.data(), image.width, image.height, tmp)
                                              : write_exr(channels, image.width, image.height, tmp);
        });
    } catch (const io::WriteError& e) {
        throw ImageError(e.what());
    }
}

}  // namespace tessera
