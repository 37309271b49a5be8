// The terminal's line for a scene; the JUnit report reuses it.
#include <cstdio>

#include "check/report.hpp"

namespace tessera::check {

std::string describe(const SceneResult& r) {
    std::string line = std::string(status_name(r.status)) + " " + r.name;
    if (!r.reason.empty()) line += ": " + r.reason;
    if (r.compared && r.status != Status::pass) {
        char numbers[160];
        std::snprintf(numbers, sizeof numbers, " [largest difference %.4g at (%d, %d), mean %.3g, %lld pixels over fail, %lld over warn]",
                      r.metrics.max_error, r.metrics.max_x, r.metrics.max_y, r.metrics.mean_error,
                      (long long)r.metrics.pixels_over_fail, (long long)r.metrics.pixels_over_warn);
        line += numbers;
    }
    if (!r.update.empty()) line += "; " + r.update;
    return line;
}

}  // namespace tessera::check
