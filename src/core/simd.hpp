// core/simd.hpp — private: which instruction sets the kernels may use.
//
// The library has one CPU detection: Highway's (hwy::SupportedTargets). The
// kernels written with Highway (measure/cone_kernels.cpp) dispatch on it;
// the x86 kernels still written with intrinsics (measure/soup.cpp,
// implicit/cone_sum.cpp) ask level() here, which reads the same detection.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace polyvol::simd {

// x86 levels, best last (on other CPUs: scalar, or sse4 for any SIMD target).
enum class Level { scalar, sse4, avx2, avx512 };

// The best level the CPU has and the kernels may use now (limit_to).
//   avx2:   AVX2, FMA, BMI2, F16C, AES and PCLMUL (Highway's AVX2 target);
//   avx512: that and AVX-512 F, VL, DQ, BW (Highway's AVX3 target).
Level level();

// Whether the CPU has AVX-512 IFMA and VAES (measure/soup.cpp's hash; not
// among the extensions Highway 1.0 reports).
bool has_avx512_ifma_vaes();

// Limits every kernel to `level` and below, process-wide (Level::avx512:
// no limit). For tests and benchmarks: not while kernels run on other
// threads. Every level gives the same bits.
void limit_to(Level level);

// Applies the environment variable POLYVOL_MAX_ISA (scalar, sse4, avx2 or
// avx512) as limit_to, when it names a level; for benchmarks of one level
// and for users whose CPU misreports. Run once before main by the kernels'
// translation unit (measure/cone_kernels.cpp).
void limit_from_environment();

// Limits the kernels to one Highway target (a HWY_* bit; 0: no limit), for
// the tests that run every target.
void force_target(int64_t target);

// The Highway targets compiled into the library that this CPU runs, best
// first (lifts any limit first), and their names.
std::vector<int64_t> available_targets();
std::string target_name(int64_t target);

// The target the kernels run on now (its name: "AVX3", "AVX2", ...).
std::string current_target_name();

}  // namespace polyvol::simd
