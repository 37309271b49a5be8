// Reading TOML values with errors that name the file, the line and column of
// the offending value, and its path in the document ('objects[3].scale'): the
// one reader behind the scene file (scene_file.cpp) and its [animation] table
// (animation_file.cpp), so both word their errors alike.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>
#include <toml++/toml.h>

namespace tessera {

// An inclusive range a number must lie in, with its wording for messages.
struct ValueRange {
    double min;
    double max;
    std::string_view text;
};
inline constexpr ValueRange kUnitInterval{0.0, 1.0, "in [0, 1]"};
inline constexpr ValueRange kNonNegative{0.0, std::numeric_limits<double>::infinity(), ">= 0"};

// A value as a message shows it (1.5, 2, 1e+30).
template <typename T>
std::string to_text(const T& value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

// Checks and reads the values of one parsed document; every check that fails
// throws SceneError "source:line:column: message" ("source: message" where
// toml++ knows no position, as for tables it creates implicitly).
class TomlReader {
public:
    explicit TomlReader(std::string source) : source_(std::move(source)) {}
    const std::string& source() const { return source_; }

    [[noreturn]] void fail(const std::string& message) const;
    [[noreturn]] void fail_at(const toml::source_region& where, const std::string& message) const;
    // "expected <expected> for '<name>', got <the node's type>".
    [[noreturn]] void fail_type(const toml::node& node, std::string_view expected, const std::string& name) const;

    // The path of `key` in table `parent` ("" for the document's root).
    static std::string child(const std::string& parent, std::string_view key) {
        return parent.empty() ? std::string(key) : parent + "." + std::string(key);
    }

    // Refuses any key not in `valid`, so that typos do not pass silently.
    void check_keys(const toml::table& table, const std::string& name, std::initializer_list<std::string_view> valid) const;
    const toml::node& require(const toml::table& table, std::string_view key, const std::string& table_name) const;
    const toml::table& table_of(const toml::node& node, const std::string& name) const;
    const toml::array& array_of(const toml::node& node, const std::string& name,
                                std::string_view expected = "an array of tables") const;

    // An integer or a float, finite as a float too (1e300 is a finite double only).
    double read_number(const toml::node& node, const std::string& name) const;
    float read_float(const toml::node& node, const std::string& name, std::optional<ValueRange> bounds = std::nullopt) const;
    glm::vec3 read_vec3(const toml::node& node, const std::string& name,
                        std::optional<ValueRange> bounds = std::nullopt) const;
    // A number (uniform) or 3 numbers, every component non-zero.
    glm::vec3 read_scale(const toml::node& node, const std::string& name) const;
    std::int64_t read_integer(const toml::node& node, const std::string& name) const;
    bool read_bool(const toml::node& node, const std::string& name) const;
    std::string read_string(const toml::node& node, const std::string& name) const;

private:
    std::string source_;
};

}  // namespace tessera
