#include <doctest/doctest.h>

#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/memory_budget.hpp"

using namespace tessera::io;

namespace {

// Sets the budget for one test and puts the process's back after it.
struct BudgetScope {
    explicit BudgetScope(std::uint64_t bytes) : saved(memory_budget()) { set_memory_budget(bytes); }
    ~BudgetScope() { set_memory_budget(saved); }
    std::uint64_t saved;
};

}  // namespace

TEST_CASE("io: --max-memory sizes in bytes, K, M, G, T") {
    CHECK(parse_byte_size("1000") == 1000);
    CHECK(parse_byte_size("4G") == 4ull << 30);
    CHECK(parse_byte_size("512m") == 512ull << 20);
    CHECK(parse_byte_size("1.5GiB") == 3ull << 29);
    CHECK(parse_byte_size("64KB") == 64ull << 10);
    for (const char* bad : {"", "x", "-1G", "0", "4Q", "nan", "1e30T"})
        CHECK_THROWS_AS(parse_byte_size(bad), std::invalid_argument);
}

TEST_CASE("io: the default budget is half of physical memory") {
    const std::uint64_t budget = default_memory_budget();
    CHECK(budget >= 256ull << 20);
    CHECK(budget < 1ull << 50);
}

TEST_CASE("io: what an input would need is checked against the budget, in one line") {
    const BudgetScope scope(64ull << 20);
    CHECK_NOTHROW(check_memory(64ull << 20, "a texture"));
    CHECK_THROWS_WITH_AS(check_memory(65ull << 20, "a 4096x4096 texture"),
                         "a 4096x4096 texture would need 65.0 MB, more than the memory budget of 64.0 MB "
                         "(--max-memory)",
                         MemoryBudgetError);
    MemoryTally tally;
    tally.add(40ull << 20, "mesh 0");
    CHECK(tally.total() == 40ull << 20);
    CHECK_THROWS_AS(tally.add(30ull << 20, "mesh 1"), MemoryBudgetError);
    CHECK(tally.total() == 40ull << 20);  // a refused addition is not counted
    CHECK_THROWS_AS(tally.add(saturating_mul(1ull << 40, 1ull << 40), "overflow"), MemoryBudgetError);
}

TEST_CASE("io: sizes multiply and add without wrapping") {
    CHECK(saturating_mul(1ull << 32, 1ull << 32) == UINT64_MAX);
    CHECK(saturating_mul(3, 4) == 12);
    CHECK(saturating_add(UINT64_MAX, 1) == UINT64_MAX);
}

TEST_CASE("io: library internals become a sentence") {
    CHECK(error_sentence(std::bad_alloc()).find("out of memory") == 0);
    std::string what;
    try {
        std::vector<int> v;
        v.resize(v.max_size() + 1);
    } catch (const std::length_error& e) {
        what = error_sentence(e);
    }
    CHECK(what == "a size in the input is too large to allocate");
    CHECK(error_sentence(std::runtime_error("scene.toml: bad")) == "scene.toml: bad");
}

TEST_CASE("io: a header claiming more than any format can decode from the file is refused") {
    const BudgetScope scope(1ull << 40);
    CHECK_NOTHROW(check_decoded_size(1000, 1000 * kMaxCompressionRatio, "a frame"));
    CHECK_THROWS_WITH_AS(check_decoded_size(100, 16384ull * 16384 * 4, "the 16384x16384 frame"),
                         "the 16384x16384 frame would decode to 1.0 GB from a file of 100 bytes; no image format "
                         "compresses that far (the data is missing)",
                         MemoryBudgetError);
}
