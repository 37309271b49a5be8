// Nesting depth of a text before it goes to a parser that recurses (toml++,
// nlohmann::json under tinygltf): a file 100k levels deep overflows the stack
// inside the parser, so the depth is measured first by a flat scan and a file
// deeper than the format can need is refused with its line.
#pragma once

#include <cstddef>
#include <string_view>

namespace tessera::io {

struct Depth {
    std::size_t depth = 0;  // the deepest level reached (0: none)
    std::size_t line = 0;   // 1-based line where the limit was first passed (0: within limit)
};

// Arrays and objects, outside strings. Stops at the first line passing `limit`.
Depth json_nesting_depth(std::string_view text, std::size_t limit);

// Tables a key or header reaches (each dotted part is a level), plus inline
// tables and arrays, outside strings and comments.
Depth toml_nesting_depth(std::string_view text, std::size_t limit);

// Throws std::runtime_error "<source>:<line>: nested deeper than <limit> levels (...)"
// when the text nests deeper than limit.
void check_json_depth(std::string_view text, std::size_t limit, std::string_view source);
void check_toml_depth(std::string_view text, std::size_t limit, std::string_view source);

// What the project's formats need, with room to spare (scenes nest 3 deep, glTF ~6 plus extras).
inline constexpr std::size_t kMaxTomlDepth = 64;
inline constexpr std::size_t kMaxJsonDepth = 256;

}  // namespace tessera::io
