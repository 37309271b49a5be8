// What counts as a pass, a warning and a failure when a render is compared
// with its golden image.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace tessera::check {

// Outcome of one scene, in the order a report lists them (worst first).
enum class Status { error, fail, missing, warn, pass };
std::string_view status_name(Status status);  // "error", "fail", "missing", "warn", "pass"

// Thresholds of one scene. Differences are per channel and absolute, in the
// golden image's units: display values in [0, 1] for a PNG golden (one 8-bit
// step is 1/255), scene-linear radiance for an EXR golden. A pixel "is beyond"
// a level when any channel differs by more than its tolerance (and, when the
// relative tolerance is set, also by more than that fraction of the mean of
// the two values), as ImageBufAlgo::compare counts it.
//
// Classification:
//   fail  pixels beyond `fail` > allowed(fail_pixels, fail_ratio), or the
//         largest difference > max_error, or pixels beyond `warn` >
//         allowed(max_warn_pixels, max_warn_ratio), or (perceptual) more
//         pixels than allowed(fail_pixels, fail_ratio) fail Yee's test;
//   warn  otherwise, pixels beyond `warn` > allowed(warn_pixels, warn_ratio);
//   pass  otherwise.
// allowed(pixels, ratio) = max(pixels, ratio · image pixels), as Playwright's
// maxDiffPixels / maxDiffPixelRatio.
struct Thresholds {
    double fail = 1.5 / 255.0;  // by default one 8-bit step passes, two fail
    double fail_relative = 0;
    double fail_pixels = 0;
    double fail_ratio = 0;
    double warn = 0;            // by default any difference at all is a warning
    double warn_relative = 0;
    double warn_pixels = 0;
    double warn_ratio = 0;
    double max_error = std::numeric_limits<double>::infinity();  // hard ceiling on the largest difference
    // Pixels beyond `warn` that fail the scene; unset (both) means no limit.
    std::optional<double> max_warn_pixels;
    std::optional<double> max_warn_ratio;
    bool perceptual = false;    // also run Yee's perceptual test (ImageBufAlgo::compare_Yee)
};

// Pixels a limit allows in an image of `pixels` pixels.
inline double allowed_pixels(double count, double ratio, std::int64_t pixels) {
    const double by_ratio = ratio * double(pixels);
    return count > by_ratio ? count : by_ratio;
}
// The same for the optional max_warn limit: no limit when neither is set.
inline double allowed_pixels(const std::optional<double>& count, const std::optional<double>& ratio,
                             std::int64_t pixels) {
    if (!count && !ratio) return std::numeric_limits<double>::infinity();
    return allowed_pixels(count.value_or(0), ratio.value_or(0), pixels);
}

}  // namespace tessera::check
