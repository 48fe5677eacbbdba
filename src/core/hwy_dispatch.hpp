// core/hwy_dispatch.hpp — private: the run-time choice among the per-target
// functions that Highway's foreach_target compiles (N_AVX3::f, N_AVX2::f,
// ...), by the library's CPU detection (simd::level()).
//
// Not Highway's own dispatch (HWY_EXPORT, HWY_DYNAMIC_DISPATCH): that lives
// in libhwy, whose start-up code measures a timer's resolution in every
// process that loads it, 2.5 ms at every start of the command for nothing
// the kernels use (docs/benchmarks.md). Highway stays header-only here.
//
// Used in a kernels file's HWY_ONCE section, in the namespace that holds
// its per-target namespaces: POLYVOL_DISPATCH(f)(args...).
#pragma once

#include "core/hwy_targets.hpp"  // before Highway, where this comes first

#include <hwy/highway.h>

#include "core/simd.hpp"

#if HWY_ARCH_X86 && (HWY_TARGETS & HWY_AVX3)
#define POLYVOL_IF_AVX3(FN) \
    if (l >= ::polyvol::simd::Level::avx512) return &N_AVX3::FN;
#else
#define POLYVOL_IF_AVX3(FN)
#endif
#if HWY_ARCH_X86 && (HWY_TARGETS & HWY_AVX2)
#define POLYVOL_IF_AVX2(FN) \
    if (l >= ::polyvol::simd::Level::avx2) return &N_AVX2::FN;
#else
#define POLYVOL_IF_AVX2(FN)
#endif
#if HWY_ARCH_X86 && (HWY_TARGETS & HWY_SSE4)
#define POLYVOL_IF_SSE4(FN) \
    if (l >= ::polyvol::simd::Level::sse4) return &N_SSE4::FN;
#elif HWY_ARCH_ARM_A64 && (HWY_TARGETS & HWY_NEON)
#define POLYVOL_IF_SSE4(FN) \
    if (l >= ::polyvol::simd::Level::sse4) return &N_NEON::FN;
#else
#define POLYVOL_IF_SSE4(FN)
#endif

// The function FN of the best target compiled at or below simd::level();
// Level::scalar is Highway's scalar fallback (SCALAR or EMU128), compiled
// whatever the baseline (hwy_targets.hpp).
#define POLYVOL_DISPATCH(FN)                                        \
    ([] {                                                           \
        [[maybe_unused]] const ::polyvol::simd::Level l = ::polyvol::simd::level(); \
        POLYVOL_IF_AVX3(FN) POLYVOL_IF_AVX2(FN) POLYVOL_IF_SSE4(FN) \
        return HWY_CHOOSE_FALLBACK(FN);                             \
    }())
