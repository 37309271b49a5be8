// The memory budget (--max-memory): how many bytes one input may make the
// loaders allocate (decoded images, a glTF model's expanded meshes). Loaders
// check what an input would need BEFORE allocating it, so a small file that
// claims a huge image or amplifies one accessor into many copies is refused
// with one line instead of exhausting memory.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tessera::io {

class MemoryBudgetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// TESSERA_MAX_MEMORY when set (a size as parse_byte_size reads it), else half
// of the machine's physical memory (MemTotal in /proc/meminfo), or 4 GB where
// that cannot be read.
std::uint64_t default_memory_budget();

// The process's budget: the default until set_memory_budget (the CLI's --max-memory).
std::uint64_t memory_budget();
void set_memory_budget(std::uint64_t bytes);

// "4G", "512M", "1.5GiB", "300000000": bytes; K, M, G, T are powers of 1024.
// Throws std::invalid_argument naming --max-memory.
std::uint64_t parse_byte_size(std::string_view text);

// a·b, saturating at UINT64_MAX (sizes from a file's header can overflow).
std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b);
std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b);

// Throws MemoryBudgetError "<what> would need <bytes>, more than the memory
// budget of <budget> (--max-memory)" when bytes exceed the budget.
void check_memory(std::uint64_t bytes, std::string_view what);

// A running total for one input (a glTF model: every mesh, morph target and
// image it expands to), checked against the budget at each addition.
class MemoryTally {
public:
    void add(std::uint64_t bytes, std::string_view what);
    std::uint64_t total() const { return total_; }

private:
    std::uint64_t total_ = 0;
};

// An image format compresses at most this far (deflate 1032:1, LZW ~2730:1, a
// flat JPEG ~1500:1, with room for EXR's codecs): a header claiming more
// decoded bytes than this times the file's size is a lie, whatever the budget.
inline constexpr std::uint64_t kMaxCompressionRatio = 16384;

// Throws MemoryBudgetError "<what> claims <decoded> from a file of <file_bytes>..." when
// decoded_bytes > file_bytes · kMaxCompressionRatio, else checks decoded_bytes against the budget.
void check_decoded_size(std::uint64_t file_bytes, std::uint64_t decoded_bytes, std::string_view what);

// An exception as one sentence for the user: std::bad_alloc and std::length_error
// (whose what() is a library internal such as "vector::_M_default_append")
// become what they mean; other exceptions give their what().
std::string error_sentence(const std::exception& error);

}  // namespace tessera::io
