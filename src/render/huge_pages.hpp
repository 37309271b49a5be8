// Frame memory in 2 MiB pages. A first frame touches tens of megabytes, and on
// our VMs every 4 KiB page fault is expensive: asking for transparent huge
// pages (before the memory is first touched) cuts the faults about 500-fold.
#pragma once

#include <cstdint>
#include <vector>

#include <sys/mman.h>

namespace tessera::render {

// Reserves room for n elements and, if that allocated new memory, advises
// the kernel to back the 2 MiB-aligned part of it with huge pages. Harmless
// where transparent huge pages are off.
template <class T, class Allocator>
void reserve_huge(std::vector<T, Allocator>& v, std::size_t n) {
    if (v.capacity() >= n) return;
    v.reserve(n);
    constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;
    const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
    const std::uintptr_t end = begin + v.capacity() * sizeof(T);
    const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1), last = end & ~(kHugePage - 1);
    if (first < last) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

}  // namespace tessera::render
