#pragma once
// parallelFor: a small fork-join loop on std::thread.
//
// Guarantees: the range [begin, end) is cut into at most `threads` contiguous chunks whose
// boundaries are multiples of `grain` (except the last), every index is visited exactly once, and
// the caller's thread works on the first chunk, so threads = 1 never starts a thread. Which indices
// a chunk holds depends only on (begin, end, grain, threads), so per-chunk results combined in chunk
// order are deterministic. An exception thrown by the body is rethrown in the caller after all
// chunks have finished. No pool: starting a thread costs some tens of microseconds, negligible
// against the millisecond loops this is meant for.

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace freeform {

/// The number of threads `requested` stands for: itself when positive, else the hardware
/// concurrency (at least 1), asked once per process: std::thread::hardware_concurrency() reads
/// /sys on Linux (about 10 us a call), which was most of the cost of binding small chunks.
inline int resolveThreadCount(int requested)
{
    if (requested > 0) return requested;
    static const int hw = [] {
        const unsigned n = std::thread::hardware_concurrency();
        return n == 0 ? 1 : static_cast<int>(n);
    }();
    return hw;
}

/// Number of chunks parallelFor uses for this range.
inline int parallelChunkCount(std::size_t begin, std::size_t end, std::size_t grain, int threads)
{
    if (end <= begin) return 0;
    grain = std::max<std::size_t>(grain, 1);
    const std::size_t units = (end - begin + grain - 1) / grain;
    return static_cast<int>(std::min<std::size_t>(units, static_cast<std::size_t>(resolveThreadCount(threads))));
}

/// Calls body(chunk, first, last) for the chunks of [begin, end); chunk numbers run from 0 to
/// parallelChunkCount(...) - 1 in index order. threads <= 0: hardware concurrency.
template <typename Body>
void parallelFor(std::size_t begin, std::size_t end, std::size_t grain, int threads, Body&& body)
{
    const int chunks = parallelChunkCount(begin, end, grain, threads);
    if (chunks == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    const std::size_t units = (end - begin + grain - 1) / grain;
    auto bounds = [&](int c) {
        const std::size_t first = begin + grain * (units * static_cast<std::size_t>(c) / static_cast<std::size_t>(chunks));
        const std::size_t last = begin + grain * (units * static_cast<std::size_t>(c + 1) / static_cast<std::size_t>(chunks));
        return std::pair<std::size_t, std::size_t>(first, std::min(last, end));
    };
    if (chunks == 1) {
        body(0, begin, end);
        return;
    }
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(chunks));
    std::vector<std::thread> workers;
    workers.reserve(static_cast<std::size_t>(chunks - 1));
    for (int c = 1; c < chunks; ++c) {
        workers.emplace_back([&, c] {
            try {
                const auto [first, last] = bounds(c);
                body(c, first, last);
            } catch (...) {
                errors[static_cast<std::size_t>(c)] = std::current_exception();
            }
        });
    }
    try {
        const auto [first, last] = bounds(0);
        body(0, first, last);
    } catch (...) {
        errors[0] = std::current_exception();
    }
    for (auto& w : workers) w.join();
    for (const auto& e : errors)
        if (e) std::rethrow_exception(e);
}

} // namespace freeform
