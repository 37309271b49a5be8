#include "cli/usage.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace tessera::cli {

namespace {

std::string_view without_dashes(std::string_view name) {
    while (!name.empty() && name.front() == '-') name.remove_prefix(1);
    return name;
}

// "-3", "-0.5", "-1e9": a value, not an option.
bool is_number(const std::string& token) {
    char* end = nullptr;
    std::strtod(token.c_str(), &end);
    return !token.empty() && end == token.c_str() + token.size();
}

// The deepest sub-command CLI11 had entered when it failed, and its path ("render").
const CLI::App* entered_command(const CLI::App& app, std::string& path) {
    const CLI::App* command = &app;
    for (std::vector<CLI::App*> subs = command->get_subcommands(); !subs.empty(); subs = command->get_subcommands()) {
        command = subs.front();
        path += (path.empty() ? "" : " ") + command->get_name();
    }
    return command;
}

std::vector<std::string> command_names(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands(std::function<bool(const CLI::App*)>{})) names.push_back(sub->get_name());
    return names;
}

std::string join(const std::vector<std::string>& names) {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return text;
}

std::string see_help(const std::string& path) {
    return " (see 'tessera " + (path.empty() ? std::string() : path + " ") + "--help')";
}

// The first word on the command line that is not a command, when no command was entered.
std::string unknown_command_message(const CLI::App& app, int argc, char** argv) {
    const std::vector<std::string> names = command_names(app);
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word.empty() || word.front() == '-') continue;
        if (std::find(names.begin(), names.end(), word) != names.end()) return "";
        const std::optional<std::string> near = closest_name(word, names);
        return "'" + word + "' is not a tessera command; " +
               (near ? "did you mean '" + *near + "'?" : "the commands are " + join(names));
    }
    return "a command is required: " + join(names) + see_help("");
}

// The first option on the command line after `command`'s name that it does not know, with a suggestion.
std::string unknown_option_message(const CLI::App& command, const std::string& path, int argc, char** argv) {
    int first = 0;  // the command's name in argv; 0: the program's (no command entered)
    if (!path.empty())
        while (first + 1 < argc && argv[++first] != command.get_name()) {
        }
    const std::vector<std::string> known = option_names(command);
    for (int i = first + 1; i < argc; ++i) {
        const std::string token = argv[i];
        if (token.size() < 2 || token.front() != '-' || token == "--" || is_number(token)) continue;
        std::string name = token.substr(0, token.find('='));
        if (name[1] != '-') name = name.substr(0, 2);  // -o5, -qv: the first short option
        if (std::find(known.begin(), known.end(), name) != known.end()) continue;
        const std::optional<std::string> near = closest_name(name, known);
        return (path.empty() ? "" : path + ": ") + "unknown option '" + name + "'" +
               (near ? "; did you mean '" + *near + "'?" : see_help(path));
    }
    return "";
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
    // d[i][j]: distance between the first i characters of a and the first j of b.
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    }
    return d[a.size()][b.size()];
}

std::optional<std::string> closest_name(std::string_view word, const std::vector<std::string>& names) {
    const std::string_view bare = without_dashes(word);
    // Short words allow one slip, longer ones two or three, never as many as the word has letters.
    const std::size_t allowed = bare.size() <= 3 ? 1 : bare.size() <= 7 ? 2 : 3;
    std::optional<std::string> best;
    std::size_t best_distance = allowed + 1;
    for (const std::string& name : names) {
        const std::size_t distance = edit_distance(bare, without_dashes(name));
        if (distance < best_distance && distance < bare.size()) best = name, best_distance = distance;
    }
    return best;
}

std::vector<std::string> option_names(const CLI::App& command) {
    std::vector<std::string> names;
    for (const CLI::Option* option : command.get_options()) {
        for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
        for (const std::string& name : option->get_snames()) names.push_back("-" + name);
    }
    return names;
}

void hide_empty_defaults(CLI::App& app) {
    for (CLI::Option* option : app.get_options())
        if (option->get_default_str() == "[]") option->default_str("");
    for (CLI::App* sub : app.get_subcommands(std::function<bool(CLI::App*)>{})) hide_empty_defaults(*sub);
}

void print_error(std::string_view message) {
    std::string line(message);
    for (std::size_t at = line.find('\n'); at != std::string::npos; at = line.find('\n', at))
        line.replace(at, 1, at + 1 == line.size() ? "" : "; ");
    std::fprintf(stderr, "tessera: error: %s\n", line.c_str());
}

int report_parse_error(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
    if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(error);  // --help, --version
    std::string path;
    const CLI::App* command = entered_command(app, path);
    std::string message;
    if (command == &app) message = unknown_command_message(app, argc, argv);
    if (message.empty() && dynamic_cast<const CLI::ExtrasError*>(&error))
        message = unknown_option_message(*command, path, argc, argv);
    if (message.empty()) message = (path.empty() ? "" : path + ": ") + std::string(error.what()) + see_help(path);
    print_error(message);
    return kUsageExit;
}

}  // namespace tessera::cli
