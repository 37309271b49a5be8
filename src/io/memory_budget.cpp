#include "io/memory_budget.hpp"

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string>

#include "io/input_file.hpp"

namespace tessera::io {

namespace {

std::atomic<std::uint64_t> g_budget{0};  // 0: not yet chosen

}  // namespace

std::uint64_t default_memory_budget() {
    if (const char* env = std::getenv("TESSERA_MAX_MEMORY"); env != nullptr && *env != '\0') {
        try {
            return parse_byte_size(env);
        } catch (const std::invalid_argument&) {
            throw std::invalid_argument("TESSERA_MAX_MEMORY '" + std::string(env) +
                                        "': expected a size such as 4G, 512M or 1000000 (bytes)");
        }
    }
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    unsigned long long kib = 0;
    std::string unit;
    while (meminfo >> key >> kib >> unit)
        if (key == "MemTotal:") return std::uint64_t(kib) * 1024 / 2;
    return 4ull << 30;
}

std::uint64_t memory_budget() {
    std::uint64_t budget = g_budget.load(std::memory_order_relaxed);
    if (budget == 0) {
        budget = default_memory_budget();
        g_budget.store(budget, std::memory_order_relaxed);
    }
    return budget;
}

void set_memory_budget(std::uint64_t bytes) { g_budget.store(bytes == 0 ? 1 : bytes, std::memory_order_relaxed); }

std::uint64_t parse_byte_size(std::string_view text) {
    const auto refuse = [&] {
        throw std::invalid_argument("--max-memory '" + std::string(text) +
                                    "': expected a size such as 4G, 512M or 1000000 (bytes)");
    };
    const std::string s(text);
    char* end = nullptr;
    const double value = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
    if (s.empty() || end == s.c_str() || !std::isfinite(value) || value <= 0) refuse();
    std::string unit(end);
    for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
    double scale = 1;
    if (unit == "" || unit == "B") scale = 1;
    else if (unit == "K" || unit == "KB" || unit == "KIB") scale = 1024.0;
    else if (unit == "M" || unit == "MB" || unit == "MIB") scale = 1024.0 * 1024;
    else if (unit == "G" || unit == "GB" || unit == "GIB") scale = 1024.0 * 1024 * 1024;
    else if (unit == "T" || unit == "TB" || unit == "TIB") scale = 1024.0 * 1024 * 1024 * 1024;
    else refuse();
    const double bytes = value * scale;
    if (bytes < 1 || bytes >= 1.8e19) refuse();
    return std::uint64_t(bytes);
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
    std::uint64_t r = 0;
    return __builtin_mul_overflow(a, b, &r) ? UINT64_MAX : r;
}

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
    std::uint64_t r = 0;
    return __builtin_add_overflow(a, b, &r) ? UINT64_MAX : r;
}

void check_memory(std::uint64_t bytes, std::string_view what) {
    const std::uint64_t budget = memory_budget();
    if (bytes > budget)
        throw MemoryBudgetError(std::string(what) + " would need " + byte_text(bytes) +
                                ", more than the memory budget of " + byte_text(budget) + " (--max-memory)");
}

void check_decoded_size(std::uint64_t file_bytes, std::uint64_t decoded_bytes, std::string_view what) {
    if (decoded_bytes > saturating_mul(file_bytes, kMaxCompressionRatio))
        throw MemoryBudgetError(std::string(what) + " would decode to " + byte_text(decoded_bytes) + " from a file of " +
                                byte_text(file_bytes) + "; no image format compresses that far (the data is missing)");
    check_memory(decoded_bytes, what);
}

void MemoryTally::add(std::uint64_t bytes, std::string_view what) {
    const std::uint64_t total = saturating_add(total_, bytes);
    const std::uint64_t budget = memory_budget();
    if (total > budget)
        throw MemoryBudgetError(std::string(what) + " would bring this file's decoded data to " + byte_text(total) +
                                ", more than the memory budget of " + byte_text(budget) + " (--max-memory)");
    total_ = total;
}

std::string error_sentence(const std::exception& error) {
    if (dynamic_cast<const std::bad_alloc*>(&error) != nullptr)
        return "out of memory: the input needs more memory than the machine gave (--max-memory checks what "
               "loaders can foresee, currently " + byte_text(memory_budget()) + ")";
    if (dynamic_cast<const std::length_error*>(&error) != nullptr)
        return "a size in the input is too large to allocate";
    return error.what();
}

}  // namespace tessera::io
