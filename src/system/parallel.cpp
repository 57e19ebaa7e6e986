#include "dynmesh/system/parallel.hpp"

#include <cstdint>
#include <thread>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dynmesh {

unsigned parallel_parts(std::size_t n, std::size_t min_per_part) {
    if (min_per_part == 0) min_per_part = 1;
    const unsigned parts = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
    return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(parts, n / min_per_part)));
}

void advise_huge_pages(const void* data, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;
    const auto p = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t first = (p + kHuge - 1) & ~(kHuge - 1), last = (p + bytes) & ~(kHuge - 1);
    if (data != nullptr && last > first) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

}  // namespace dynmesh
