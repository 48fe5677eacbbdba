// read_binary_stl_triangles (polyvol/io.hpp): a binary STL's coordinates,
// packed nine floats a triangle, copied window by window from the mapped file.
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/prefault.hpp"
#include "polyvol/io.hpp"
#include "core/bit_cast.hpp"

namespace polyvol {

std::vector<float> read_binary_stl_triangles(const std::string& path) {
    const BinaryStlFile file(path);
    const BinaryStlProbe& probe = file.probe();
    std::vector<float> out;
    // The count is trustworthy only when the size rule holds; otherwise
    // for_each_window throws its ReadError (where and why) before any
    // window, and nothing was allocated.
    if (probe.binary_stl) core::resize_for_filling(out, std::size_t{9} * probe.triangles);
    // The first record with a NaN or infinite coordinate, over all windows
    // (windows run in parallel and in any order: the smallest index wins).
    std::atomic<uint64_t> first_bad{std::numeric_limits<uint64_t>::max()};
    file.for_each_window([&](std::span<const std::byte> records, uint64_t first) {
        const std::size_t n = records.size() / 50;
        float* dst = out.data() + 9 * first;
        uint32_t bad = 0;  // 1 once a coordinate of the window is NaN or infinite
        for (std::size_t t = 0; t < n; ++t) {
            uint32_t w[9];
            std::memcpy(w, records.data() + 50 * t + 12, 36);
            std::memcpy(dst + 9 * t, w, 36);
            uint32_t e = 0;
            for (uint32_t x : w) e |= (x & 0x7F800000u) == 0x7F800000u;
            bad |= e;
        }
        if (bad == 0) return;
        for (std::size_t t = 0; t < n; ++t)
            for (int k = 0; k < 9; ++k)
                if ((core::bit_cast<uint32_t>(dst[9 * t + k]) & 0x7F800000u) == 0x7F800000u) {
                    uint64_t cur = first_bad.load(std::memory_order_relaxed);
                    const uint64_t at = 9 * (first + t) + static_cast<uint64_t>(k);
                    while (at < cur && !first_bad.compare_exchange_weak(cur, at, std::memory_order_relaxed)) {
                    }
                    return;
                }
    });
    if (const uint64_t at = first_bad.load(); at != std::numeric_limits<uint64_t>::max())
        throw ReadError::at_byte(path, 84 + 50 * (at / 9) + 12 + 4 * (at % 9),
                                 "non-finite coordinate in triangle " + std::to_string(at / 9));
    return out;
}

}  // namespace polyvol
