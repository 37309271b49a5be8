// The one comparison every golden test uses, and its thresholds.
#pragma once

#include <filesystem>
#include <string>

#include "tessera/renderer.hpp"

namespace tessera::test {

// Thresholds on display values in [0, 1], stated once. A render on the machine
// that made the golden images matches it exactly; these allow for another
// SIMD width (FMA or not) moving a channel by one 8-bit step here and there.
inline constexpr float kGoldenFailThreshold = 2.5f / 255.0f;  // any channel further off fails
inline constexpr float kGoldenWarnThreshold = 1.5f / 255.0f;  // off by 2 steps: counted
inline constexpr double kGoldenMaxWarnFraction = 0.001;       // at most 0.1% of pixels may be counted
// A mirror-like GGX glint (roughness 0.05, highlight peak ~5e4) amplifies one
// rounding difference into a few 8-bit steps: in a scene with hundreds of
// lights (many_lights) the sanitizer build's code generation moves single
// pixels by 3 steps. So a few pixels may pass the fail threshold, by a bounded amount.
inline constexpr double kGoldenMaxFailFraction = 1e-5;        // 9 pixels of a 1280×720 image
inline constexpr float kGoldenMaxError = 8.5f / 255.0f;       // and never more than 8 steps

struct GoldenResult {
    bool passed = false;
    std::string message;  // what differed, and where the actual and diff images were written
};

// Compares a render's display image with a golden PNG using OpenImageIO's
// ImageBufAlgo::compare. On failure writes <failure_dir>/<name>.actual.png and
// <name>.diff.png (absolute difference, scaled up to be visible).
GoldenResult compare_with_golden(const RenderedImage& image, const std::filesystem::path& golden_png,
                                 const std::filesystem::path& failure_dir, const std::string& name);

}  // namespace tessera::test
