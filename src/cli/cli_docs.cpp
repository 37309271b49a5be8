#include "cli/cli_docs.hpp"

#include <cstdio>
#include <sstream>

#include "cli/tools_exec.hpp"
#include "cli/usage.hpp"

namespace tessera::cli {

namespace {

// Spec fields are tab-separated, one record a line: no tab or newline inside.
std::string flat(std::string text) {
    for (char& c : text)
        if (c == '\t' || c == '\n') c = ' ';
    return text;
}

std::vector<std::string> split(std::string_view text, char separator) {
    std::vector<std::string> parts;
    for (std::size_t start = 0;;) {
        const std::size_t end = text.find(separator, start);
        parts.emplace_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        if (end == std::string_view::npos) return parts;
        start = end + 1;
    }
}

std::string join(const std::vector<std::string>& parts, std::string_view separator) {
    std::string text;
    for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? std::string(separator) : "") + parts[i];
    return text;
}

// The choices of an IsMember check as CLI11 names it ("INT:{1,4}", "TEXT:{time,work}").
std::vector<std::string> choices(const std::string& value_type) {
    const std::size_t open = value_type.find('{'), close = value_type.rfind('}');
    if (open == std::string::npos || close == std::string::npos || close < open) return {};
    return split(std::string_view(value_type).substr(open + 1, close - open - 1), ',');
}

// roff: a backslash is \e, a minus is \-, and a line may not start with . or '.
std::string roff(std::string_view text) {
    std::string out;
    for (const char c : text) {
        if (c == '\\') out += "\\e";
        else if (c == '-') out += "\\-";
        else out += c;
    }
    if (!out.empty() && (out.front() == '.' || out.front() == '\'')) out.insert(0, "\\&");
    return out;
}

std::string usage_line(const CommandDoc& command) {
    std::string line = "tessera " + command.name + " [options]";
    for (const OptionDoc& option : command.options)
        if (option.positional) line += " " + option.names.front() + "...";
    return line;
}

}  // namespace

std::vector<CommandDoc> describe_commands(const CLI::App& app) {
    std::vector<CommandDoc> commands;
    for (const CLI::App* sub : app.get_subcommands(std::function<bool(const CLI::App*)>{})) {
        if (sub->get_prefix_command()) continue;
        CommandDoc command{sub->get_name(), sub->get_description(), {}};
        for (const CLI::Option* option : sub->get_options()) {
            OptionDoc doc;
            doc.positional = option->get_positional() && option->get_lnames().empty() && option->get_snames().empty();
            if (doc.positional) {
                doc.names.push_back(option->get_name(true));
            } else {
                for (const std::string& name : option->get_snames()) doc.names.push_back("-" + name);
                for (const std::string& name : option->get_lnames()) doc.names.push_back("--" + name);
            }
            doc.takes_value = option->get_expected_max() != 0;  // flags expect no value
            doc.value_type = doc.takes_value ? option->get_type_name() : "";
            doc.default_value = doc.takes_value ? option->get_default_str() : "";
            if (doc.default_value == "[]" || doc.default_value == "{}") doc.default_value.clear();  // an empty list
            doc.description = option->get_description();
            command.options.push_back(std::move(doc));
        }
        commands.push_back(std::move(command));
    }
    return commands;
}

std::string to_spec(const std::vector<CommandDoc>& commands) {
    std::string spec;
    for (const CommandDoc& command : commands) {
        spec += "command\t" + flat(command.name) + "\t" + flat(command.description) + "\n";
        for (const OptionDoc& o : command.options)
            spec += std::string(o.positional ? "positional" : "option") + "\t" + join(o.names, ",") + "\t" +
                    (o.takes_value ? "1" : "0") + "\t" + flat(o.value_type) + "\t" + flat(o.default_value) + "\t" +
                    flat(o.description) + "\n";
    }
    return spec;
}

std::vector<CommandDoc> from_spec(std::string_view spec) {
    std::vector<CommandDoc> commands;
    for (const std::string& line : split(spec, '\n')) {
        const std::vector<std::string> fields = split(line, '\t');
        if (fields.size() == 3 && fields[0] == "command") {
            commands.push_back({fields[1], fields[2], {}});
        } else if (fields.size() == 6 && !commands.empty() && (fields[0] == "option" || fields[0] == "positional")) {
            commands.back().options.push_back(
                {split(fields[1], ','), fields[0] == "positional", fields[2] == "1", fields[3], fields[4], fields[5]});
        }
    }
    return commands;
}

std::string bash_completion(const std::vector<CommandDoc>& commands) {
    std::vector<std::string> names;
    for (const CommandDoc& command : commands) names.push_back(command.name);
    std::ostringstream out;
    out << "# bash completion for tessera, made from its command-line definition (tessera --print-completion bash)\n"
           "_tessera() {\n"
           "    local cur=\"${COMP_WORDS[COMP_CWORD]}\" prev=\"${COMP_WORDS[COMP_CWORD-1]}\"\n"
           "    local command=\"\" i\n"
           "    for ((i = 1; i < COMP_CWORD; i++)); do\n"
           "        case \"${COMP_WORDS[i]}\" in -*) ;; *) command=\"${COMP_WORDS[i]}\"; break ;; esac\n"
           "    done\n"
           "    if [[ -z \"$command\" ]]; then\n"
           "        COMPREPLY=($(compgen -W \""
        << join(names, " ")
        << " --help --version\" -- \"$cur\"))\n"
           "        return\n"
           "    fi\n"
           "    local options=\"\"\n"
           "    case \"$command\" in\n";
    for (const CommandDoc& command : commands) {
        std::vector<std::string> all;
        out << "    " << command.name << ")\n";
        out << "        case \"$prev\" in\n";
        for (const OptionDoc& option : command.options) {
            if (option.positional) continue;
            for (const std::string& name : option.names) all.push_back(name);
            if (!option.takes_value) continue;
            const std::vector<std::string> values = choices(option.value_type);
            out << "        " << join(option.names, "|") << ")\n";
            if (values.empty())  // a file, a number or a name: files are the useful guess
                out << "            COMPREPLY=($(compgen -f -- \"$cur\")); return ;;\n";
            else
                out << "            COMPREPLY=($(compgen -W \"" << join(values, " ") << "\" -- \"$cur\")); return ;;\n";
        }
        out << "        esac\n";
        out << "        options=\"" << join(all, " ") << "\" ;;\n";
    }
    out << "    *) return ;;\n"
           "    esac\n"
           "    if [[ \"$cur\" == -* ]]; then\n"
           "        COMPREPLY=($(compgen -W \"$options\" -- \"$cur\"))\n"
           "    else\n"
           "        COMPREPLY=($(compgen -f -- \"$cur\"))\n"
           "    fi\n"
           "}\n"
           "complete -o filenames -F _tessera tessera\n";
    return out.str();
}

std::string man_page(const std::vector<CommandDoc>& commands, std::string_view version) {
    std::ostringstream out;
    out << ".\\\" Made from tessera's command-line definition (tessera --print-man); do not edit.\n"
        << ".TH TESSERA 1 \"\" \"tessera " << roff(version) << "\" \"User Commands\"\n"
        << ".SH NAME\ntessera \\- a multithreaded SIMD CPU rasterizer with a PBR fragment stage\n"
        << ".SH SYNOPSIS\n.B tessera\n.I command\n[\\fIoptions\\fR] [\\fIarguments\\fR]\n.br\n"
        << ".B tessera\n.BR \\-\\-help \" | \" \\-\\-version\n"
        << ".SH DESCRIPTION\nTessera renders scene files (.toml) and glTF models (.gltf, .glb) with the "
           "LearnOpenGL direct-lighting PBR shader, on the CPU. Each command has its own options; "
           "\\fBtessera\\fR \\fIcommand\\fR \\fB\\-\\-help\\fR lists them with their defaults.\n"
        << ".SH COMMANDS\n";
    for (const CommandDoc& command : commands) {
        out << ".SS \"" << roff(usage_line(command)) << "\"\n" << roff(command.description) << ".\n";
        for (const OptionDoc& option : command.options) {
            out << ".TP\n";
            std::string names;
            for (std::size_t i = 0; i < option.names.size(); ++i)
                names += (i ? ", " : "") + std::string(option.positional ? "\\fI" : "\\fB") + roff(option.names[i]) + "\\fR";
            if (option.takes_value && !option.positional) names += " \\fI" + roff(option.value_type) + "\\fR";
            out << names << "\n" << roff(option.description);
            if (!option.default_value.empty()) out << " (default: " << roff(option.default_value) << ")";
            out << "\n";
        }
    }
    out << ".SH EXIT STATUS\n"
           ".TP\n0\nSuccess (for check: every scene passed or warned).\n"
           ".TP\n1\nThe work failed: a scene that does not load or render, an image that cannot be written "
           "(for check: a scene failed, was missing or could not be rendered).\n"
           ".TP\n2\nA usage error, found before any work starts: an unknown command or option, a bad value, "
           "a file that is not a scene file, options that exclude each other, an output that cannot be written. "
           "The message is one line, \\fBtessera: error:\\fR ..., with a suggestion for a mistyped name.\n"
           ".SH SEE ALSO\nThe documentation in the source tree: docs/cli.md, docs/scene-format.md.\n";
    return out.str();
}

bool is_docs_request(std::string_view argument) { return argument == "--print-completion" || argument == "--print-man"; }

int print_docs(const CLI::App& app, int argc, char** argv) {
    const std::string request = argv[1];
    if (request == "--print-completion" && (argc != 3 || std::string_view(argv[2]) != "bash")) {
        print_error("--print-completion: expected 'bash' (the only shell supported)");
        return kUsageExit;
    }
    // tessera-tools' commands, from its own definition.
    const std::string command = "'" + tools_executable(argv[0]).string() + "' " + std::string(kSpecRequest);
    std::string spec;
    if (std::FILE* pipe = ::popen(command.c_str(), "r")) {
        char buffer[4096];
        for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) spec.append(buffer, n);
        if (::pclose(pipe) != 0) spec.clear();
    }
    const std::vector<CommandDoc> tools = from_spec(spec);
    if (tools.empty()) {
        print_error("cannot read the commands of tessera-tools (" + command + ")");
        return 1;
    }
    // In tessera --help's order: its own commands, and tessera-tools' where their stand-ins are.
    const std::vector<CommandDoc> own = describe_commands(app);
    std::vector<CommandDoc> commands;
    for (const CLI::App* sub : app.get_subcommands(std::function<bool(const CLI::App*)>{})) {
        const std::vector<CommandDoc>& from = sub->get_prefix_command() ? tools : own;
        for (const CommandDoc& doc : from)
            if (doc.name == sub->get_name()) commands.push_back(doc);
    }
    const std::string text = request == "--print-man" ? man_page(commands, TESSERA_VERSION) : bash_completion(commands);
    std::fwrite(text.data(), 1, text.size(), stdout);
    return 0;
}

}  // namespace tessera::cli
