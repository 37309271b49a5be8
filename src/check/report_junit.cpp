#include <cstdio>
#include <string>

#include "check/atomic_file.hpp"
#include "check/report.hpp"

namespace tessera::check {

namespace {

std::string xml_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default:
                // Control characters other than tab and newlines are not allowed in XML 1.0.
                if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') out += ' ';
                else out += c;
        }
    }
    return out;
}

std::string seconds(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", ms / 1000.0);
    return text;
}

}  // namespace

void write_junit_report(const CheckRun& run, const std::filesystem::path& path) {
    int failures = 0, errors = 0;
    for (const SceneResult& r : run.scenes) {
        if (r.status == Status::error) ++errors;
        if (r.status == Status::fail || r.status == Status::missing) ++failures;
    }
    std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    xml += "<testsuites name=\"tessera check\" tests=\"" + std::to_string(run.scenes.size()) + "\" failures=\"" +
           std::to_string(failures) + "\" errors=\"" + std::to_string(errors) + "\" time=\"" +
           seconds(run.seconds * 1000.0) + "\">\n";
    xml += "  <testsuite name=\"tessera check\" tests=\"" + std::to_string(run.scenes.size()) + "\" failures=\"" +
           std::to_string(failures) + "\" errors=\"" + std::to_string(errors) + "\" skipped=\"0\" time=\"" +
           seconds(run.seconds * 1000.0) + "\">\n";
    for (const SceneResult& r : run.scenes) {
        xml += "    <testcase classname=\"tessera.check\" name=\"" + xml_escape(r.name) + "\" file=\"" +
               xml_escape(r.scene.string()) + "\" time=\"" + seconds(r.render_ms + r.compare_ms) + "\"";
        const std::string detail = describe(r);
        switch (r.status) {
            case Status::pass:
                xml += "/>\n";
                continue;
            case Status::warn:
                xml += ">\n      <system-out>" + xml_escape(detail) + "</system-out>\n";
                break;
            case Status::fail:
            case Status::missing:
                xml += ">\n      <failure type=\"" + std::string(status_name(r.status)) + "\" message=\"" +
                       xml_escape(r.reason) + "\">" + xml_escape(detail) + "</failure>\n";
                break;
            case Status::error:
                xml += ">\n      <error type=\"error\" message=\"" + xml_escape(r.reason) + "\">" + xml_escape(detail) +
                       "</error>\n";
                break;
        }
        xml += "    </testcase>\n";
    }
    xml += "  </testsuite>\n</testsuites>\n";
    write_text_atomically(path, xml);
}

}  // namespace tessera::check
