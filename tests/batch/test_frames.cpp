// Tests for src/batch/frames.cpp: --frames lists and output name patterns.
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "batch/frames.hpp"

using namespace tessera::batch;

TEST_CASE("--frames: single frames, inclusive ranges, steps, lists") {
    CHECK(parse_frame_ranges("7") == std::vector<int>{7});
    CHECK(parse_frame_ranges("0-3") == std::vector<int>{0, 1, 2, 3});
    CHECK(parse_frame_ranges("0-10:4") == std::vector<int>{0, 4, 8});  // the step need not land on the last
    CHECK(parse_frame_ranges("10-12,0-1") == std::vector<int>{10, 11, 12, 0, 1});
    CHECK(parse_frame_ranges("0-239").size() == 240);
    CHECK(parse_frame_ranges("999990-999999:7") == std::vector<int>{999990, 999997});
    for (const char* bad : {"", "-3", "3-", "a-b", "5-2", "0-10:0", "0-10:", "3:2", "0-3,2", "1,,2", "0-1000000", " 1"})
        CHECK_THROWS_AS(parse_frame_ranges(bad), FrameRangeError);
    CHECK_THROWS_WITH(parse_frame_ranges("0-3,2"), "--frames: frame 2 is listed twice");
}

TEST_CASE("output patterns: {scene}, {frame}, {frame:0N}") {
    CHECK(expand_output_pattern("out/{scene}/frame_{frame:04}.png", "turntable", 7) == "out/turntable/frame_0007.png");
    CHECK(expand_output_pattern("f{frame}_{frame:02}.exr", "s", 123) == "f123_123.exr");
    CHECK(expand_output_pattern("plain.png", "s", 5) == "plain.png");
    CHECK(expand_output_pattern("{scene}{scene}.png", "a", 0) == "aa.png");
    CHECK(has_frame_placeholder("x_{frame:03}.png"));
    CHECK_FALSE(has_frame_placeholder("x_{scene}.png"));
    CHECK_NOTHROW(check_output_pattern("a_{frame:09}.png"));
    for (const char* bad : {"a_{frame:4}.png", "a_{frame:00}.png", "a_{frame:010}.png", "a_{frame.png", "a_{frames}.png"})
        CHECK_THROWS_AS(check_output_pattern(bad), FrameRangeError);
    CHECK_THROWS_WITH(check_output_pattern("a_{frame:4}.png"),
                      "output 'a_{frame:4}.png': unsupported placeholder '{frame:4}'; expected {frame} or {frame:0N} "
                      "(N = 1..9 digits, zero-padded)");
}
