// core/hwy_targets.hpp — private: the Highway targets the library compiles,
// included before any Highway header: every target the compiler can build
// (so the scalar fallback too, whatever -march says), except SSSE3 (CPUs without SSE4.1
// take the scalar target), AVX3_DL (AVX3 covers what the kernels use) and
// SVE (the kernels keep vectors in arrays, which SVE's sizeless vectors
// cannot be; ARM takes NEON).
#pragma once

#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_AVX3_DL | HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128)
#endif
