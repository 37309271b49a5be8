// Comparing a render with its golden image, through OpenImageIO.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "check/thresholds.hpp"
#include "tessera/renderer.hpp"

namespace tessera::check {

// What a golden file holds and how it is compared.
enum class GoldenKind {
    png,  // display-referred 8-bit RGB: compared with the render's display image
    exr,  // scene-linear RGB radiance (half): compared with the render's radiance, rounded to half as EXR stores it
};
GoldenKind golden_kind_for(const std::filesystem::path& golden);  // by extension; anything but .exr is png

// The numbers of one comparison (ImageBufAlgo::compare's, plus Yee's count).
struct Metrics {
    std::int64_t pixels = 0;           // pixels compared (the image's, less the ignored ones)
    std::int64_t ignored_pixels = 0;   // left out by the scene's ignore regions
    double max_error = 0;      // largest per-channel difference
    int max_x = 0, max_y = 0, max_channel = 0;  // where it is (row 0 at the top)
    double mean_error = 0;
    double rms_error = 0;
    double psnr = 0;           // peak 1.0
    std::int64_t pixels_over_fail = 0;
    std::int64_t pixels_over_warn = 0;      // including those over `fail`
    std::int64_t perceptual_fail = -1;      // Yee's failing pixels; -1 when not run
};

struct Comparison {
    Status status = Status::fail;
    std::string reason;   // why it is not a pass ("" for a pass), or the size/channel mismatch
    bool compared = false;  // metrics hold numbers (sizes and channels matched)
    Metrics metrics;
};

// The render as the golden's kind sees it: its 8-bit display image, or its
// radiance rounded to half. The buffer may point into `image`.
OIIO::ImageBuf actual_image(const RenderedImage& image, GoldenKind kind);

// Reads a golden image as float. Throws std::runtime_error naming the file: a
// FIFO or device, or pixels over the memory budget (io/memory_budget.hpp), are
// refused before reading. A golden of another size than render_width x
// render_height (when given) keeps only its header: the comparison fails on
// the size without the pixels being read.
OIIO::ImageBuf read_golden(const std::filesystem::path& golden, int render_width = 0, int render_height = 0);

// Compares and classifies. Sizes or channels that differ are a failure with
// the reason. `kind` says which units the thresholds are in (for messages).
// `ignored` (check/ignore_regions.hpp: one byte per pixel, 1 = ignored; empty:
// none) leaves pixels out: they count as equal, and ratios, mean, RMS and PSNR
// are over the other pixels.
Comparison compare_images(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& golden, const Thresholds& thresholds,
                          GoldenKind kind, const std::vector<std::uint8_t>& ignored = {});

// Heat map of |actual - golden| (largest channel) as 8-bit RGB, through the
// "inferno" colour map: black where equal; full brightness at `scale` and
// beyond, with a square root so that differences far below it still show.
// Ignored pixels (as for compare_images) show in kIgnoredColor.
OIIO::ImageBuf diff_heat_map(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& golden, double scale,
                             const std::vector<std::uint8_t>& ignored = {});
inline constexpr float kIgnoredColor[3] = {0.15f, 0.30f, 0.55f};  // a blue no inferno value has
// The scale check reports use: twice the fail tolerance, or the largest difference when the tolerance is 0.
double heat_map_scale(const Thresholds& thresholds, const Metrics& metrics);

// An 8-bit display preview for the report: PNG goldens as they are; EXR radiance
// encoded exactly as the renderer encodes its PNG (Reinhard, gamma 1/2.2,
// UNORM8: image::unorm8_from_radiance_reference), so that a preview of an EXR
// golden and the render's PNG agree where the radiance does. 8-bit RGB.
OIIO::ImageBuf display_preview(const OIIO::ImageBuf& image, GoldenKind kind);

}  // namespace tessera::check
