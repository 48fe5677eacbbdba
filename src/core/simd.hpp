// core/simd.hpp — private: which instruction sets the kernels may use.
//
// The library's one CPU detection (CPUID: what each of Highway's targets
// needs). The kernels written with Highway are compiled for every target
// and chosen by level() (core/hwy_dispatch.hpp); the AVX-512 IFMA/VAES hash
// of the streamed soup asks has_avx512_ifma_vaes().
#pragma once

#include <string>
#include <vector>

namespace polyvol::simd {

// x86 levels, best last (on other CPUs: scalar, or sse4 for any SIMD target).
enum class Level { scalar, sse4, avx2, avx512 };

// The best level the CPU has and the kernels may use now (limit_to).
//   sse4:   SSE4.2, AES and PCLMUL (Highway's SSE4 target); NEON on ARM;
//   avx2:   that and AVX2, FMA, BMI2, F16C (Highway's AVX2 target);
//   avx512: that and AVX-512 F, VL, DQ, BW (Highway's AVX3 target).
Level level();

// Whether the kernels may use AVX-512 IFMA and VAES (the streamed soup's
// hash, measure/soup_pass1.cpp): level() is avx512 and the CPU has both.
bool has_avx512_ifma_vaes();

// Limits every kernel to `level` and below, process-wide (Level::avx512:
// no limit). For tests and benchmarks: not while kernels run on other
// threads, nor while a SoupAccumulator is fed (its fingerprint's hash is the
// portable one below AVX2, AES from AVX2 up). Every level gives the same
// sums and bounds, bit for bit. The environment variable POLYVOL_MAX_ISA
// (scalar, sse4, avx2) sets it at the first level(), for benchmarks of one
// level and for users whose CPU misreports.
void limit_to(Level level);

// The levels compiled into the library that this CPU runs, best first (for
// tests that run each: limit_to(l) then runs l), and their Highway names
// ("AVX3", "AVX2", "SSE4" or "NEON", "SCALAR" or "EMU128").
std::vector<Level> available_levels();
std::string level_name(Level level);

}  // namespace polyvol::simd
