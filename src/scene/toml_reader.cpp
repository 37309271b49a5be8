#include "scene/toml_reader.hpp"

#include <cmath>

#include "tessera/scene.hpp"

namespace tessera {
namespace {

std::string_view type_name(toml::node_type type) {
    switch (type) {
        case toml::node_type::table: return "table";
        case toml::node_type::array: return "array";
        case toml::node_type::string: return "string";
        case toml::node_type::integer: return "integer";
        case toml::node_type::floating_point: return "floating-point";
        case toml::node_type::boolean: return "boolean";
        case toml::node_type::date: return "date";
        case toml::node_type::time: return "time";
        case toml::node_type::date_time: return "date-time";
        case toml::node_type::none: break;
    }
    return "nothing";
}

}  // namespace

void TomlReader::fail(const std::string& message) const { throw SceneError(source_ + ": " + message); }

void TomlReader::fail_at(const toml::source_region& where, const std::string& message) const {
    if (where.begin.line == 0) fail(message);
    throw SceneError(source_ + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column) + ": " +
                     message);
}

void TomlReader::fail_type(const toml::node& node, std::string_view expected, const std::string& name) const {
    fail_at(node.source(),
            "expected " + std::string(expected) + " for '" + name + "', got " + std::string(type_name(node.type())));
}

void TomlReader::check_keys(const toml::table& table, const std::string& name,
                            std::initializer_list<std::string_view> valid) const {
    for (auto&& [key, node] : table) {
        bool known = false;
        for (const std::string_view v : valid) known = known || key.str() == v;
        if (known) continue;
        std::string list;
        for (const std::string_view v : valid) list += (list.empty() ? "" : ", ") + std::string(v);
        const std::string place = name.empty() ? "at top level" : "in '" + name + "'";
        fail_at(key.source().begin.line != 0 ? key.source() : node.source(),
                "unknown key '" + std::string(key.str()) + "' " + place + "; valid keys: " + list);
    }
}

const toml::node& TomlReader::require(const toml::table& table, std::string_view key,
                                      const std::string& table_name) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) fail_at(table.source(), "missing required key '" + child(table_name, key) + "'");
    return *node;
}

const toml::table& TomlReader::table_of(const toml::node& node, const std::string& name) const {
    const toml::table* table = node.as_table();
    if (table == nullptr) fail_type(node, "a table", name);
    return *table;
}

const toml::array& TomlReader::array_of(const toml::node& node, const std::string& name,
                                        std::string_view expected) const {
    const toml::array* array = node.as_array();
    if (array == nullptr) fail_type(node, expected, name);
    return *array;
}

double TomlReader::read_number(const toml::node& node, const std::string& name) const {
    double value = 0.0;
    if (const auto* integer = node.as_integer()) {
        value = static_cast<double>(integer->get());
    } else if (const auto* floating = node.as_floating_point()) {
        value = floating->get();
    } else {
        fail_type(node, "a number", name);
    }
    if (!std::isfinite(value) || !std::isfinite(static_cast<float>(value))) {
        fail_at(node.source(), "expected a finite number for '" + name + "', got " + to_text(value));
    }
    return value;
}

float TomlReader::read_float(const toml::node& node, const std::string& name, std::optional<ValueRange> bounds) const {
    const double value = read_number(node, name);
    if (bounds && !(value >= bounds->min && value <= bounds->max)) {
        fail_at(node.source(), "expected '" + name + "' to be " + std::string(bounds->text) + ", got " + to_text(value));
    }
    return static_cast<float>(value);
}

glm::vec3 TomlReader::read_vec3(const toml::node& node, const std::string& name, std::optional<ValueRange> bounds) const {
    const toml::array* array = node.as_array();
    if (array == nullptr) fail_type(node, "an array of 3 numbers", name);
    if (array->size() != 3) {
        fail_at(node.source(), "expected an array of 3 numbers for '" + name + "', got " +
                                   std::to_string(array->size()) + " elements");
    }
    glm::vec3 result{};
    for (int i = 0; i < 3; ++i) {
        result[i] = read_float(*array->get(static_cast<std::size_t>(i)), name + "[" + std::to_string(i) + "]", bounds);
    }
    return result;
}

glm::vec3 TomlReader::read_scale(const toml::node& node, const std::string& name) const {
    glm::vec3 scale{1.0f};
    if (node.is_number()) {
        scale = glm::vec3(read_float(node, name));
    } else if (node.is_array()) {
        scale = read_vec3(node, name);
    } else {
        fail_type(node, "a number or an array of 3 numbers", name);
    }
    if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f) {
        fail_at(node.source(), "expected every component of '" + name + "' to be non-zero");
    }
    return scale;
}

std::int64_t TomlReader::read_integer(const toml::node& node, const std::string& name) const {
    const auto* integer = node.as_integer();
    if (integer == nullptr) fail_type(node, "an integer", name);
    return integer->get();
}

bool TomlReader::read_bool(const toml::node& node, const std::string& name) const {
    const auto* flag = node.as_boolean();
    if (flag == nullptr) fail_type(node, "a boolean", name);
    return flag->get();
}

std::string TomlReader::read_string(const toml::node& node, const std::string& name) const {
    const auto* string = node.as_string();
    if (string == nullptr) fail_type(node, "a string", name);
    return string->get();
}

}  // namespace tessera
