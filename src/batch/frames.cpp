#include "batch/frames.hpp"

#include <algorithm>
#include <charconv>
#include <utility>
#include <set>

namespace tessera::batch {
namespace {

constexpr std::string_view kScene = "{scene}";
constexpr std::string_view kFrame = "{frame";

int parse_frame_number(std::string_view text, std::string_view range) {
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc() || ptr != end || value < 0 || value > kMaxFrameNumber)
        throw FrameRangeError("--frames: '" + std::string(range) + "': expected whole numbers in 0.." +
                              std::to_string(kMaxFrameNumber) + ", as in 0-239 or 0-239:2");
    return value;
}

// The zero-padded width a "{frame...}" placeholder at `at` asks for, and its
// length; throws for anything but {frame} and {frame:0N}.
std::pair<int, std::size_t> frame_placeholder(std::string_view pattern, std::size_t at) {
    const std::size_t close = pattern.find('}', at);
    if (close == std::string_view::npos)
        throw FrameRangeError("output '" + std::string(pattern) + "': '{frame' is not closed by '}'");
    const std::string_view inside = pattern.substr(at + 1, close - at - 1);  // "frame" or "frame:04"
    const std::size_t length = close - at + 1;
    if (inside == "frame") return {0, length};
    if (inside.size() == 8 && inside.substr(0, 7) == "frame:0" && inside[7] >= '1' && inside[7] <= '9')
        return {inside[7] - '0', length};
    throw FrameRangeError("output '" + std::string(pattern) + "': unsupported placeholder '{" + std::string(inside) +
                          "}'; expected {frame} or {frame:0N} (N = 1..9 digits, zero-padded)");
}

}  // namespace

std::vector<int> parse_frame_ranges(std::string_view text) {
    std::vector<int> frames;
    std::set<int> seen;
    if (text.empty()) throw FrameRangeError("--frames: expected a range such as 0-239 or 0-239:2, got nothing");
    for (std::size_t begin = 0; begin <= text.size();) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const std::string_view range = text.substr(begin, comma - begin);
        begin = comma + 1;
        std::string_view bounds = range;
        int step = 1;
        if (const std::size_t colon = range.find(':'); colon != std::string_view::npos) {
            bounds = range.substr(0, colon);
            step = parse_frame_number(range.substr(colon + 1), range);
            if (step < 1) throw FrameRangeError("--frames: '" + std::string(range) + "': the step must be >= 1");
        }
        const std::size_t dash = bounds.find('-');
        const int first = parse_frame_number(bounds.substr(0, dash), range);
        const int last = dash == std::string_view::npos ? first : parse_frame_number(bounds.substr(dash + 1), range);
        if (last < first)
            throw FrameRangeError("--frames: '" + std::string(range) + "': the last frame is before the first");
        if (dash == std::string_view::npos && step != 1)
            throw FrameRangeError("--frames: '" + std::string(range) + "': a step needs a range, as in 0-239:2");
        for (int f = first; f <= last; f += step) {
            if (!seen.insert(f).second)
                throw FrameRangeError("--frames: frame " + std::to_string(f) + " is listed twice");
            frames.push_back(f);
            if (last - f < step) break;  // no overflow past kMaxFrameNumber
        }
    }
    return frames;
}

void check_output_pattern(std::string_view pattern) {
    for (std::size_t at = pattern.find(kFrame); at != std::string_view::npos; at = pattern.find(kFrame, at + 1))
        frame_placeholder(pattern, at);
}

bool has_frame_placeholder(std::string_view pattern) { return pattern.find(kFrame) != std::string_view::npos; }

std::string expand_output_pattern(std::string_view pattern, std::string_view scene_stem, int frame) {
    std::string path;
    for (std::size_t at = 0; at < pattern.size();) {
        if (pattern.substr(at, kScene.size()) == kScene) {
            path += scene_stem;
            at += kScene.size();
        } else if (pattern.substr(at, kFrame.size()) == kFrame) {
            const auto [width, length] = frame_placeholder(pattern, at);
            std::string number = std::to_string(frame);
            if (int(number.size()) < width) number.insert(0, std::size_t(width) - number.size(), '0');
            path += number;
            at += length;
        } else {
            path += pattern[at++];
        }
    }
    return path;
}

}  // namespace tessera::batch
