#pragma once
/// \file The one way dynmesh splits a loop across threads: [0, n) cut into a few contiguous
/// parts, each run on its own thread (part 0 on the caller's). Callers make each part write
/// only its own slots or its own arrays and merge them in part order, so that results never
/// depend on the number of parts. And the one way it asks for transparent huge pages on a
/// large array (fewer page faults when a mesh of millions of elements is first written).

#include <algorithm>
#include <cstddef>
#include <exception>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace dynmesh {

/// The number of parts for n items: 1 when n < 2 * min_per_part, else as many as the machine
/// has hardware threads (at most 8), each part at least min_per_part items.
[[nodiscard]] unsigned parallel_parts(std::size_t n, std::size_t min_per_part);

/// Part p of `parts` contiguous parts of [0, n): [n p / parts, n (p + 1) / parts).
[[nodiscard]] inline std::pair<std::size_t, std::size_t> part_range(unsigned p, unsigned parts, std::size_t n) {
    return {n * p / parts, n * (std::size_t(p) + 1) / parts};
}

/// Calls fn(p, begin, end) for each part p of [0, n) (part_range), part 0 on the calling thread
/// and the others on threads of their own (on the calling thread too when the system refuses a
/// thread), and waits for all. When parts throw, the exception of the lowest-numbered one is
/// rethrown after every part has ended.
template <class Fn>
void run_parts(unsigned parts, std::size_t n, Fn&& fn) {
    if (parts <= 1) {
        fn(0u, std::size_t(0), n);
        return;
    }
    std::vector<std::exception_ptr> errors(parts);
    const auto run = [&](unsigned p) {
        try {
            const auto [b, e] = part_range(p, parts, n);
            fn(p, b, e);
        } catch (...) {
            errors[p] = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    unsigned started = 1;  // parts 1 .. started - 1 run on threads of their own
    try {
        threads.reserve(parts - 1);
        for (; started < parts; ++started) threads.emplace_back(run, started);
    } catch (...) {  // no thread to be had: the parts left run here
    }
    run(0);
    for (unsigned p = started; p < parts; ++p) run(p);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

/// Advises the kernel to back [data, data + bytes) with transparent huge pages where it can
/// (the whole 2 MiB pages inside the range; Linux, when THP is in "madvise" mode). Only advice:
/// nothing changes when it is refused or unavailable.
void advise_huge_pages(const void* data, std::size_t bytes) noexcept;

/// An array of n trivially constructible elements, left uninitialized (no pass over memory
/// that is about to be written anyway), with huge pages advised.
template <class T>
[[nodiscard]] std::unique_ptr<T[]> uninitialized_huge_array(std::size_t n) {
    static_assert(std::is_trivially_default_constructible_v<T>);
    std::unique_ptr<T[]> a(new T[n]);
    advise_huge_pages(a.get(), n * sizeof(T));
    return a;
}

/// Reserves room for n elements in an empty vector and advises huge pages for it; call before
/// the first write (resize, assign) so that the pages are faulted in as huge pages.
template <class T, class A>
void reserve_huge(std::vector<T, A>& v, std::size_t n) {
    v.reserve(n);
    advise_huge_pages(v.data(), n * sizeof(T));
}

}  // namespace dynmesh
