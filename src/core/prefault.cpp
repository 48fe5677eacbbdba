// core/prefault.hpp: faulting in a large buffer's pages on every core.
#include "core/prefault.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>

namespace polyvol::core {

void prefault(void* data, std::size_t bytes) {
#ifdef MADV_POPULATE_WRITE
    constexpr std::size_t kMin = std::size_t{8} << 20;    // smaller: one core's faults cost less than the loop
    // Bytes per madvise call: at 8 MiB and more, at least two slices (one per
    // core here); the call itself costs about a microsecond against 1-2 ms
    // to fault in 4 MiB, so smaller slices would only add calls.
    constexpr std::size_t kSlice = std::size_t{4} << 20;
    if (bytes < kMin) return;
    const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    const auto at = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t begin = (at + page - 1) / page * page;
    const std::uintptr_t end = (at + bytes) / page * page;
    if (end <= begin) return;
    const std::size_t slices = (end - begin + kSlice - 1) / kSlice;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slices, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t s = r.begin(); s < r.end(); ++s) {
            const std::uintptr_t a = begin + s * kSlice;
            const std::uintptr_t b = std::min<std::uintptr_t>(end, a + kSlice);
            (void)::madvise(reinterpret_cast<void*>(a), b - a, MADV_POPULATE_WRITE);  // advice: failure is harmless
        }
    });
#else
    (void)data;
    (void)bytes;
#endif
}

}  // namespace polyvol::core
