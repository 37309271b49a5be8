// Frame lists and output names: what `--frames 0-239:2` means and where each
// frame goes (`-o out/{scene}/frame_{frame:04}.png`).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::batch {

class FrameRangeError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

inline constexpr int kMaxFrameNumber = 999999;

// A comma-separated list of ranges, each "A" (one frame), "A-B" (A to B
// inclusive) or "A-B:S" (every S-th from A, up to B), 0 <= A <= B <=
// kMaxFrameNumber, S >= 1. The frames in the order written; a frame listed
// twice is refused (its output would be written twice). Throws FrameRangeError.
std::vector<int> parse_frame_ranges(std::string_view text);

// Output names hold placeholders: {scene} is the scene file's stem; {frame} is
// the frame number, {frame:0N} the same padded with zeros to N digits (1..9).
// Throws FrameRangeError for a malformed {frame...} placeholder.
void check_output_pattern(std::string_view pattern);
bool has_frame_placeholder(std::string_view pattern);
std::string expand_output_pattern(std::string_view pattern, std::string_view scene_stem, int frame);

}  // namespace tessera::batch
