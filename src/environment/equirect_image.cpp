#include "environment/equirect_image.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "texture/oiio_module_loader.hpp"
#include "texture/texture.hpp"

namespace tessera::environment {

glm::vec3 EquirectImage::sample(float u, float v) const {
    const float x = u * float(width) - 0.5f, y = v * float(height) - 0.5f;
    const float x0f = std::floor(x), y0f = std::floor(y);
    const float fx = x - x0f, fy = y - y0f;
    const int x0 = std::clamp(int(x0f), 0, width - 1), x1 = std::clamp(int(x0f) + 1, 0, width - 1);
    const int y0 = std::clamp(int(y0f), 0, height - 1), y1 = std::clamp(int(y0f) + 1, 0, height - 1);
    const auto at = [&](int xi, int yi) { return rgb[std::size_t(yi) * std::size_t(width) + std::size_t(xi)]; };
    const glm::vec3 top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * fx;
    const glm::vec3 bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * fx;
    return top + (bottom - top) * fy;
}

namespace {

struct Reading {
    std::string source;
    std::string refusal;  // why begin() stopped
    EquirectImage image;
    int channels = 0;
};

int begin_image(void* context, int width, int height, int depth, int channels) {
    Reading& r = *static_cast<Reading*>(context);
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (depth > 1) r.refusal = "a volume image is not an environment map";
    else if (width < 2 || height < 1 || width > kMaxEquirectWidth || height > kMaxEquirectWidth / 2 + 1)
        r.refusal = "expected an equirectangular image 2..16384 pixels wide, twice as wide as tall; got " + size;
    else if (double(width) / double(height) < 1.5 || double(width) / double(height) > 2.5)
        r.refusal = "expected an equirectangular image, twice as wide as tall (width/height in [1.5, 2.5]); got " + size;
    if (!r.refusal.empty()) return 0;
    r.image.width = width, r.image.height = height, r.channels = std::min(channels, 4);
    r.image.rgb.assign(std::size_t(width) * std::size_t(height), glm::vec3(0.0f));
    return 1;
}

int image_rows(void* context, int y_begin, int y_end, const float* samples) {
    Reading& r = *static_cast<Reading*>(context);
    const int w = r.image.width, h = r.image.height, c = r.channels;
    const auto clean = [](float x) { return std::isfinite(x) && x > 0.0f ? x : 0.0f; };
    for (int y = y_begin; y < y_end; ++y) {
        const float* row = samples + std::size_t(y - y_begin) * std::size_t(w) * std::size_t(c);
        glm::vec3* out = &r.image.rgb[std::size_t(h - 1 - y) * std::size_t(w)];  // flipped: bottom-up
        for (int x = 0; x < w; ++x) {
            const float* p = row + std::size_t(x) * std::size_t(c);
            out[x] = c >= 3 ? glm::vec3(clean(p[0]), clean(p[1]), clean(p[2])) : glm::vec3(clean(p[0]));
        }
    }
    return 1;
}

}  // namespace

void check_equirect_path(const std::filesystem::path& path) {
    const std::string source = path.string();
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    if (extension != ".hdr" && extension != ".exr")
        throw EnvironmentError(source + ": expected a Radiance .hdr or OpenEXR .exr environment image");
    std::error_code error_code;
    if (!std::filesystem::is_regular_file(path, error_code))
        throw EnvironmentError(source + ": cannot open the environment image (no such file)");
}

EquirectImage load_equirect_image(const std::filesystem::path& path) {
    check_equirect_path(path);
    const std::string source = path.string();
    TesseraReadFloatImage read = nullptr;
    try {
        read = texture::oiio_module_float_reader(source);
    } catch (const texture::TextureError& e) {
        throw EnvironmentError(e.what());
    }
    Reading reading{source, {}, {}, 0};
    const TesseraFloatImageSink sink{&reading, begin_image, image_rows};
    char error[512];
    int header_failed = 0;
    if (!read(source.c_str(), &sink, error, sizeof error, &header_failed)) {
        if (!reading.refusal.empty()) throw EnvironmentError(source + ": " + reading.refusal);
        throw EnvironmentError(source + ": cannot read the environment image" +
                               (header_failed ? " (not an HDR or EXR image): " : ": ") + error);
    }
    return std::move(reading.image);
}

}  // namespace tessera::environment
