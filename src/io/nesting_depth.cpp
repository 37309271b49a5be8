#include "io/nesting_depth.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace tessera::io {

Depth json_nesting_depth(std::string_view text, std::size_t limit) {
    Depth result;
    std::size_t depth = 0, line = 1;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') ++line;
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
            continue;
        }
        if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > result.depth) result.depth = depth;
            if (depth > limit) {
                result.line = line;
                return result;
            }
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return result;
}

Depth toml_nesting_depth(std::string_view text, std::size_t limit) {
    Depth result;
    struct Open {
        char bracket;       // '[' or '{'
        std::size_t depth;  // the level of the array or inline table itself
    };
    std::vector<Open> open;
    std::size_t line = 1;
    std::size_t table_depth = 0;  // the last [table] header's parts: keys under it are below them
    bool key_context = true;      // reading a key (line start, or after '{' or ',' in an inline table)
    bool header = false;          // inside a [table] or [[array]] header
    bool line_start = true;
    std::size_t dots = 0;         // dots of the key (or header) being read
    std::size_t value_depth = 0;  // the level of the key whose value follows '='
    const auto reach = [&](std::size_t depth) {
        if (depth > result.depth) result.depth = depth;
        if (depth > limit && result.line == 0) result.line = line;
    };
    // Keys are below the innermost inline table, or below the table header at the top.
    const auto key_base = [&] { return open.empty() ? table_depth : open.back().depth; };
    const auto skip_string = [&](std::size_t& i) {
        const char quote = text[i];
        const bool multi = text.substr(i, 3) == std::string(3, quote);
        i += multi ? 3 : 1;
        for (; i < text.size(); ++i) {
            const char c = text[i];
            if (c == '\n') {
                ++line;
                if (!multi) return;
            }
            if (quote == '"' && c == '\\') {
                if (i + 1 < text.size() && text[i + 1] == '\n') ++line;
                ++i;
                continue;
            }
            if (c == quote && (!multi || text.substr(i, 3) == std::string(3, quote))) {
                i += multi ? 2 : 0;
                return;
            }
        }
    };
    for (std::size_t i = 0; i < text.size() && result.line == 0; ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            header = false;
            line_start = true;
            if (open.empty()) key_context = true, dots = 0;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') continue;
        const bool at_line_start = line_start;
        line_start = false;
        if (c == '#') {
            while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
        } else if (c == '"' || c == '\'') {
            skip_string(i);
        } else if (header) {
            if (c == '.') {
                reach(++dots + 1);
            } else if (c == ']') {
                header = false;
                table_depth = dots + 1;
                reach(table_depth);
                if (i + 1 < text.size() && text[i + 1] == ']') ++i;
            }
        } else if (key_context) {
            if (c == '[' && at_line_start && open.empty()) {
                header = true, dots = 0;
                if (i + 1 < text.size() && text[i + 1] == '[') ++i;
            } else if (c == '.') {
                reach(key_base() + ++dots + 1);
            } else if (c == '=') {
                key_context = false;
                value_depth = key_base() + dots + 1;
                reach(value_depth);
                dots = 0;
            } else if (c == '}' && !open.empty()) {  // an empty inline table
                open.pop_back();
                key_context = false;
            }
        } else if (c == '[' || c == '{') {
            // An array's elements are one below it; anything else is the value of the key before '='.
            const std::size_t depth = !open.empty() && open.back().bracket == '[' ? open.back().depth + 1 : value_depth;
            open.push_back({c, depth});
            reach(depth + (c == '[' ? 1 : 0));
            if (c == '{') key_context = true, dots = 0;
        } else if ((c == ']' || c == '}') && !open.empty()) {
            open.pop_back();
        } else if (c == ',' && !open.empty() && open.back().bracket == '{') {
            key_context = true, dots = 0;
        }
    }
    return result;
}

namespace {

void check_depth(const Depth& d, std::size_t limit, std::string_view source, const char* format) {
    if (d.line == 0) return;
    throw std::runtime_error(std::string(source) + ":" + std::to_string(d.line) + ": nested deeper than " +
                             std::to_string(limit) + " levels (" + format + "); refused before parsing");
}

}  // namespace

void check_json_depth(std::string_view text, std::size_t limit, std::string_view source) {
    check_depth(json_nesting_depth(text, limit), limit, source, "JSON arrays and objects");
}

void check_toml_depth(std::string_view text, std::size_t limit, std::string_view source) {
    check_depth(toml_nesting_depth(text, limit), limit, source, "TOML tables, dotted keys, arrays and inline tables");
}

}  // namespace tessera::io
