#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "io/nesting_depth.hpp"

using namespace tessera::io;

namespace {

std::string repeat(const std::string& s, std::size_t n) {
    std::string r;
    r.reserve(s.size() * n);
    for (std::size_t i = 0; i < n; ++i) r += s;
    return r;
}

}  // namespace

TEST_CASE("io: JSON depth counts arrays and objects, not brackets in strings") {
    CHECK(json_nesting_depth(R"({"a": [1, {"b": []}]})", 100).depth == 4);
    CHECK(json_nesting_depth(R"({"a": "[[[[{{{{\"[[["})", 100).depth == 1);
    CHECK(json_nesting_depth("", 100).depth == 0);
    const std::string deep = "{\"extras\":\n" + repeat("[", 20000) + repeat("]", 20000) + "}";
    const Depth d = json_nesting_depth(deep, kMaxJsonDepth);
    CHECK(d.line == 2);
    CHECK(d.depth == kMaxJsonDepth + 1);  // the scan stops at the first level too deep
    CHECK_THROWS_WITH_AS(check_json_depth(deep, kMaxJsonDepth, "summary.json"),
                         "summary.json:2: nested deeper than 256 levels (JSON arrays and objects); refused before "
                         "parsing",
                         std::runtime_error);
    CHECK_NOTHROW(check_json_depth(repeat("[", 256) + repeat("]", 256), kMaxJsonDepth, "x"));
    CHECK_THROWS(check_json_depth(repeat("[", 257) + repeat("]", 257), kMaxJsonDepth, "x"));
}

TEST_CASE("io: TOML depth counts dotted keys, table headers, inline tables and arrays") {
    CHECK(toml_nesting_depth("a = 1\n", 100).depth == 1);
    CHECK(toml_nesting_depth("a.b.c = 1\n", 100).depth == 3);
    CHECK(toml_nesting_depth("[a.b]\nc.d = 1\n", 100).depth == 4);  // keys are below their table
    CHECK(toml_nesting_depth("x = [[1, 2], [3]]\n", 100).depth == 3);
    CHECK(toml_nesting_depth("x = { a.b = { c = 1 } }\n", 100).depth == 4);
    // Dots in numbers, strings and comments are not levels.
    CHECK(toml_nesting_depth("x = 1.5\ny = \"a.b.c[[{\"\nz = 'a.b' # a.b.c.d [[[\n", 100).depth == 1);
    CHECK(toml_nesting_depth("\"a.b\".c = 1\n", 100).depth == 2);
    CHECK(toml_nesting_depth("s = \"\"\"\n[[[a.b.c]]]\n\"\"\"\nt = 2\n", 100).depth == 1);
    // Multi-line arrays keep their depth across lines; the next key starts afresh.
    CHECK(toml_nesting_depth("x = [\n  [1],\n  [2],\n]\ny.z = 1\n", 100).depth == 3);
    CHECK(toml_nesting_depth("[[objects]]\nmesh = \"cube\"\n[objects.material]\nalbedo = [1, 0, 0]\n", 100).depth ==
          4);
}

TEST_CASE("io: TOML 100k levels deep is refused with the line, whichever way it nests") {
    const std::string dotted = "title = 1\n" + repeat("a.", 100000) + "a = 1\n";
    const std::string header = "[" + repeat("a.", 100000) + "a]\n";
    const std::string arrays = "x = " + repeat("[", 100000) + repeat("]", 100000) + "\n";
    const std::string tables = "x = " + repeat("{a = ", 100000) + "1" + repeat("}", 100000) + "\n";
    CHECK(toml_nesting_depth(dotted, kMaxTomlDepth).line == 2);
    CHECK(toml_nesting_depth(header, kMaxTomlDepth).line == 1);
    CHECK(toml_nesting_depth(arrays, kMaxTomlDepth).line == 1);
    CHECK(toml_nesting_depth(tables, kMaxTomlDepth).line == 1);
    CHECK_THROWS_WITH_AS(check_toml_depth(dotted, kMaxTomlDepth, "deep.toml"),
                         "deep.toml:2: nested deeper than 64 levels (TOML tables, dotted keys, arrays and inline "
                         "tables); refused before parsing",
                         std::runtime_error);
    CHECK_NOTHROW(check_toml_depth(repeat("a.", 63) + "a = 1\n", kMaxTomlDepth, "ok.toml"));
    // A key under a deep header counts the header's levels too.
    CHECK_THROWS(check_toml_depth("[" + repeat("a.", 40) + "a]\n" + repeat("b.", 30) + "b = 1\n", kMaxTomlDepth, "x"));
    CHECK_THROWS(check_toml_depth(repeat("a.", 64) + "a = 1\n", kMaxTomlDepth, "deep.toml"));
}
