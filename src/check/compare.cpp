#include "check/compare.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <OpenImageIO/imagebufalgo.h>

#include "image/display_encoding.hpp"
#include "io/input_file.hpp"
#include "io/memory_budget.hpp"

namespace tessera::check {

std::string_view status_name(Status status) {
    switch (status) {
        case Status::error: return "error";
        case Status::fail: return "fail";
        case Status::missing: return "missing";
        case Status::warn: return "warn";
        case Status::pass: return "pass";
    }
    return "?";
}

namespace {

// A difference as the golden's units read best: 8-bit steps for PNG, radiance for EXR.
std::string amount(double value, GoldenKind kind) {
    char text[64];
    if (kind == GoldenKind::png)
        std::snprintf(text, sizeof text, "%.3g/255", value * 255.0);
    else
        std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

std::string count_text(double pixels) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", std::floor(pixels));
    return text;
}

std::string channel_list(const OIIO::ImageSpec& spec) {
    std::string names;
    for (int c = 0; c < spec.nchannels; ++c) {
        if (c) names += ",";
        names += c < int(spec.channelnames.size()) ? spec.channelnames[c] : "?";
    }
    return names;
}

// `image` with the ignored pixels set to 0 (as float).
OIIO::ImageBuf without_ignored(const OIIO::ImageBuf& image, const std::vector<std::uint8_t>& ignored) {
    const OIIO::ImageSpec& spec = image.spec();
    OIIO::ImageBuf out(OIIO::ImageSpec(spec.width, spec.height, spec.nchannels, OIIO::TypeDesc::FLOAT));
    out.copy_pixels(image);
    const std::vector<float> zero(std::size_t(spec.nchannels), 0.0f);
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x)
            if (ignored[std::size_t(y) * spec.width + x]) out.setpixel(x, y, zero.data(), spec.nchannels);
    return out;
}

}  // namespace

GoldenKind golden_kind_for(const std::filesystem::path& golden) {
    std::string ext = golden.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr" ? GoldenKind::exr : GoldenKind::png;
}

OIIO::ImageBuf actual_image(const RenderedImage& image, GoldenKind kind) {
    if (kind == GoldenKind::png) {
        const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
        return OIIO::ImageBuf(spec, const_cast<std::uint8_t*>(image.display.data()));
    }
    if (image.radiance.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
        throw std::logic_error("an EXR golden needs the render's radiance (RenderSettings::keep_radiance)");
    const OIIO::ImageSpec float_spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
    const OIIO::ImageBuf radiance(float_spec, const_cast<float*>(image.radiance.data()));
    // Rounded to half as the EXR file stores it, so that a render matches the golden it would write, bit for bit.
    OIIO::ImageSpec half_spec(image.width, image.height, 3, OIIO::TypeDesc::HALF);
    half_spec.channelnames = {"R", "G", "B"};
    OIIO::ImageBuf half(half_spec);
    half.copy_pixels(radiance);
    return half;
}

OIIO::ImageBuf read_golden(const std::filesystem::path& golden, int render_width, int render_height) {
    std::uint64_t file_bytes = 0;
    try {
        file_bytes = io::check_input_file(golden, io::memory_budget(), "golden image");
    } catch (const io::InputFileError& e) {
        throw std::runtime_error(golden.string() + ": " + e.reason());
    }
    OIIO::ImageBuf buffer(golden.string());
    const OIIO::ImageSpec& spec = buffer.spec();  // the header only
    if (spec.width > 0 && render_width > 0 && (spec.width != render_width || spec.height != render_height))
        return buffer;
    try {  // the file's own samples (1 byte for PNG), then as float
        const std::uint64_t pixels = io::saturating_mul(std::uint64_t(std::max(spec.width, 0)),
                                                        std::uint64_t(std::max(spec.height, 0)));
        const std::uint64_t samples = io::saturating_mul(pixels, std::uint64_t(std::max(spec.nchannels, 0)));
        const std::string what = "the " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " golden image";
        io::check_decoded_size(file_bytes, samples, what);
        io::check_memory(io::saturating_mul(samples, sizeof(float)), what);
    } catch (const io::MemoryBudgetError& e) {
        throw std::runtime_error(golden.string() + ": " + e.what());
    }
    if (!buffer.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error(golden.string() + ": cannot read golden image: " + buffer.geterror());
    return buffer;
}

Comparison compare_images(const OIIO::ImageBuf& actual_in, const OIIO::ImageBuf& golden_in, const Thresholds& thresholds,
                          GoldenKind kind, const std::vector<std::uint8_t>& ignored) {
    Comparison result;
    const OIIO::ImageSpec& a = actual_in.spec();
    const OIIO::ImageSpec& g = golden_in.spec();
    if (a.width != g.width || a.height != g.height) {
        result.reason = "size differs: golden " + std::to_string(g.width) + "x" + std::to_string(g.height) +
                        ", render " + std::to_string(a.width) + "x" + std::to_string(a.height);
        return result;
    }
    const bool channels_match = kind == GoldenKind::png
                                    ? g.nchannels == 3
                                    : (g.nchannels == 3 && g.channelnames[0] == "R" && g.channelnames[1] == "G" &&
                                       g.channelnames[2] == "B");
    if (!channels_match) {
        result.reason = "channels differ: golden has " + std::to_string(g.nchannels) + " (" + channel_list(g) +
                        "), the render " + (kind == GoldenKind::png ? "3 (R,G,B display values)" : "3 (R,G,B radiance)");
        return result;
    }

    if (!ignored.empty() && ignored.size() != std::size_t(a.width) * std::size_t(a.height))
        throw std::logic_error("compare_images: the ignore mask is not the image's size");
    const std::int64_t ignored_count = std::count(ignored.begin(), ignored.end(), std::uint8_t(1));
    // Ignored pixels made equal (0 in both), so that nothing is counted there.
    OIIO::ImageBuf actual_masked, golden_masked;
    if (ignored_count > 0) {
        actual_masked = without_ignored(actual_in, ignored);
        golden_masked = without_ignored(golden_in, ignored);
    }
    const OIIO::ImageBuf& actual = ignored_count > 0 ? actual_masked : actual_in;
    const OIIO::ImageBuf& golden = ignored_count > 0 ? golden_masked : golden_in;

    const OIIO::ImageBufAlgo::CompareResults cmp =
        OIIO::ImageBufAlgo::compare(actual, golden, float(thresholds.fail), float(thresholds.warn),
                                    float(thresholds.fail_relative), float(thresholds.warn_relative));
    // OpenImageIO 2.4 also sets `error` when any pixel fails: only an error without failures is a real one.
    if (cmp.error && cmp.nfail == 0) {
        result.reason = "comparison error: " + OIIO::geterror();
        return result;
    }
    Metrics& m = result.metrics;
    const std::int64_t all_pixels = std::int64_t(a.width) * a.height;
    m.pixels = all_pixels - ignored_count;
    m.ignored_pixels = ignored_count;
    m.max_error = cmp.maxerror;
    m.max_x = cmp.maxx;
    m.max_y = cmp.maxy;
    m.max_channel = cmp.maxc;
    m.mean_error = cmp.meanerror;
    m.rms_error = cmp.rms_error;
    m.psnr = cmp.PSNR;
    if (ignored_count > 0) {  // OpenImageIO averaged over every pixel: over the compared ones instead
        const double share = m.pixels > 0 ? double(all_pixels) / double(m.pixels) : 0.0;
        m.mean_error *= share;
        m.rms_error *= std::sqrt(share);
        m.psnr = m.rms_error > 0 ? 20.0 * std::log10(1.0 / m.rms_error) : std::numeric_limits<double>::infinity();
    }
    m.pixels_over_fail = std::int64_t(cmp.nfail);
    m.pixels_over_warn = std::int64_t(cmp.nwarn);  // OpenImageIO counts failing pixels here too
    if (thresholds.perceptual) {
        OIIO::ImageBuf actual_linear = actual, golden_linear = golden;
        if (kind == GoldenKind::png) {  // Yee's test wants linear light; PNGs hold gamma-2.2 display values
            actual_linear = OIIO::ImageBufAlgo::pow(actual, 2.2f);
            golden_linear = OIIO::ImageBufAlgo::pow(golden, 2.2f);
        }
        OIIO::ImageBufAlgo::CompareResults yee;
        m.perceptual_fail = OIIO::ImageBufAlgo::compare_Yee(actual_linear, golden_linear, yee);
    }
    result.compared = true;

    const double fail_allowed = allowed_pixels(thresholds.fail_pixels, thresholds.fail_ratio, m.pixels);
    const double warn_allowed = allowed_pixels(thresholds.warn_pixels, thresholds.warn_ratio, m.pixels);
    const double max_warn_allowed = allowed_pixels(thresholds.max_warn_pixels, thresholds.max_warn_ratio, m.pixels);
    std::string fails;
    const auto add = [](std::string& list, const std::string& what) { list += (list.empty() ? "" : "; ") + what; };
    if (double(m.pixels_over_fail) > fail_allowed)
        add(fails, std::to_string(m.pixels_over_fail) + " pixels differ by more than " + amount(thresholds.fail, kind) +
                       " (" + count_text(fail_allowed) + " allowed)");
    if (m.max_error > thresholds.max_error)
        add(fails, "largest difference " + amount(m.max_error, kind) + " at (" + std::to_string(m.max_x) + ", " +
                       std::to_string(m.max_y) + ") is over the ceiling " + amount(thresholds.max_error, kind));
    if (double(m.pixels_over_warn) > max_warn_allowed)
        add(fails, std::to_string(m.pixels_over_warn) + " pixels differ by more than " + amount(thresholds.warn, kind) +
                       " (at most " + count_text(max_warn_allowed) + " may)");
    if (m.perceptual_fail >= 0 && double(m.perceptual_fail) > fail_allowed)
        add(fails, std::to_string(m.perceptual_fail) + " pixels differ perceptually (" + count_text(fail_allowed) +
                       " allowed)");
    if (!fails.empty()) {
        result.status = Status::fail;
        result.reason = fails;
    } else if (double(m.pixels_over_warn) > warn_allowed) {
        result.status = Status::warn;
        result.reason = std::to_string(m.pixels_over_warn) + " pixels differ by more than " +
                        amount(thresholds.warn, kind) + " (" + count_text(warn_allowed) + " allowed before a warning)";
    } else {
        result.status = Status::pass;
    }
    return result;
}

double heat_map_scale(const Thresholds& thresholds, const Metrics& metrics) {
    if (thresholds.fail > 0) return 2.0 * thresholds.fail;
    return metrics.max_error > 0 ? metrics.max_error : 1.0;
}

OIIO::ImageBuf diff_heat_map(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& golden, double scale,
                             const std::vector<std::uint8_t>& ignored) {
    namespace algo = OIIO::ImageBufAlgo;
    const OIIO::ImageBuf largest = algo::maxchan(algo::absdiff(actual, golden));
    OIIO::ImageBuf normalized = algo::clamp(algo::mul(largest, float(1.0 / scale)), 0.0f, 1.0f);
    normalized = algo::pow(normalized, 0.5f);
    OIIO::ImageBuf map = algo::color_map(normalized, 0, "inferno");
    const OIIO::ImageSpec& spec = map.spec();
    if (ignored.size() == std::size_t(spec.width) * std::size_t(spec.height))
        for (int y = 0; y < spec.height; ++y)
            for (int x = 0; x < spec.width; ++x)
                if (ignored[std::size_t(y) * spec.width + x]) map.setpixel(spec.x + x, spec.y + y, kIgnoredColor, 3);
    return map;
}

OIIO::ImageBuf display_preview(const OIIO::ImageBuf& image, GoldenKind kind) {
    if (kind == GoldenKind::png) return image;
    const OIIO::ImageSpec& spec = image.spec();
    OIIO::ImageBuf display(OIIO::ImageSpec(spec.width, spec.height, 3, OIIO::TypeDesc::UINT8));
    std::vector<float> pixel(std::size_t(std::max(spec.nchannels, 3)), 0.0f);
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x) {
            image.getpixel(spec.x + x, spec.y + y, pixel.data(), int(pixel.size()));
            float encoded[3];
            for (int c = 0; c < 3; ++c)  // NaN and negatives as black, as the renderer's display image
                encoded[c] = float(tessera::image::unorm8_from_radiance_reference(pixel[c] > 0.0f ? pixel[c] : 0.0f)) / 255.0f;
            display.setpixel(x, y, encoded, 3);
        }
    return display;
}

}  // namespace tessera::check
