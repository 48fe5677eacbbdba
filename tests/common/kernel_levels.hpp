// Tests that run every instruction-set level of the kernels and compare
// their bits: the level by number, and a guard restoring the best.
#pragma once

#include "core/simd.hpp"

namespace polyvol::test {

// The levels the tests run, each capped by the CPU: 0 scalar (no FMA:
// Dekker's two_prod; the AES hash by Highway's emulation), 1 up to SSE4, 2 up to AVX2 + FMA
// (AES-NI), 3 the CPU's best (AVX-512 with IFMA and VAES where it has them).
inline constexpr int kLevels[] = {0, 1, 2, 3};

// Caps the kernels at a level (-1: the CPU's best). Process-wide (simd::limit_to).
inline void cap_kernel_level(int level) {
    simd::limit_to(level == 0   ? simd::Level::scalar
                   : level == 1 ? simd::Level::sse4
                   : level == 2 ? simd::Level::avx2
                                : simd::Level::avx512);
}

// Whether the CPU runs the AVX-512 kernels (whatever the limit now).
inline bool cpu_has_avx512() { return simd::available_levels().front() == simd::Level::avx512; }

// Restores the best kernels when a test ends (also on a failed assertion).
struct LevelGuard {
    ~LevelGuard() { simd::limit_to(simd::Level::avx512); }
};

}  // namespace polyvol::test
