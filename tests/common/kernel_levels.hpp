// Tests that run every instruction-set level of the kernels and compare
// their bits: the level by number, and a guard restoring the best.
#pragma once

#include "core/simd.hpp"

namespace polyvol::test {

// 0: scalar (no FMA: Dekker's two_prod), 1: up to AVX2 + FMA, 2 (or -1):
// the CPU's best. Process-wide (simd::limit_to).
inline void cap_kernel_level(int level) {
    simd::limit_to(level == 0 ? simd::Level::scalar : level == 1 ? simd::Level::avx2 : simd::Level::avx512);
}

// Whether the CPU runs the AVX-512 kernels.
inline bool cpu_has_avx512() {
    simd::limit_to(simd::Level::avx512);
    return simd::level() == simd::Level::avx512;
}

// Restores the best kernels when a test ends (also on a failed assertion).
struct LevelGuard {
    ~LevelGuard() { simd::limit_to(simd::Level::avx512); }
};

}  // namespace polyvol::test
