// core/simd.cpp — the instruction sets the kernels may use, from Highway's
// CPU detection.
#include "core/simd.hpp"

#include "core/hwy_targets.hpp"  // before Highway

#include <hwy/highway.h>
#include <hwy/targets.h>

#include <atomic>
#include <cstdlib>
#include <string_view>

#if HWY_ARCH_X86
#include <cpuid.h>
#endif

namespace polyvol::simd {

namespace {

// The targets at `level` and above, which limit_to(level - 1) removes.
int64_t targets_above(Level level) {
    int64_t above = 0;
    if (level < Level::avx512) above |= HWY_AVX3 | HWY_AVX3_DL;
    if (level < Level::avx2) above |= HWY_AVX2;
    if (level < Level::sse4) above |= HWY_SSE4 | HWY_SSSE3 | HWY_NEON | HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128;
    return above;
}

// hwy::SupportedTargets() runs CPUID on every call (slow, and in a virtual
// machine a trap to the hypervisor): read once, again after each limit.
std::atomic<int64_t> g_targets{0};

int64_t supported() {
    int64_t t = g_targets.load(std::memory_order_relaxed);
    if (t == 0) {
        t = hwy::SupportedTargets();
        g_targets.store(t, std::memory_order_relaxed);
    }
    return t;
}

void set_supported_for_test(int64_t targets) {
    hwy::SetSupportedTargetsForTest(targets);
    g_targets.store(hwy::SupportedTargets(), std::memory_order_relaxed);
}

}  // namespace

Level level() {
    const int64_t t = supported();
    if (t & (HWY_AVX3 | HWY_AVX3_DL)) return Level::avx512;
    if (t & HWY_AVX2) return Level::avx2;
    if (t & (HWY_SSE4 | HWY_NEON | HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128)) return Level::sse4;
    return Level::scalar;
}

bool has_avx512_ifma_vaes() {
#if HWY_ARCH_X86
    // CPUID leaf 7: IFMA is EBX bit 21, VAES ECX bit 9.
    static const bool has = [] {
        unsigned a = 0, b = 0, c = 0, d = 0;
        return __get_cpuid_count(7, 0, &a, &b, &c, &d) != 0 && (b >> 21 & 1) != 0 && (c >> 9 & 1) != 0;
    }();
    return has && level() == Level::avx512;
#else
    return false;
#endif
}

void limit_to(Level level) {
    set_supported_for_test(0);  // the CPU's own targets again
    if (level != Level::avx512) set_supported_for_test(hwy::SupportedTargets() & ~targets_above(level));
}

void limit_from_environment() {
    const char* v = std::getenv("POLYVOL_MAX_ISA");
    if (v == nullptr) return;
    const std::string_view name(v);
    if (name == "scalar") limit_to(Level::scalar);
    if (name == "sse4") limit_to(Level::sse4);
    if (name == "avx2") limit_to(Level::avx2);
    if (name == "avx512") limit_to(Level::avx512);
}

void force_target(int64_t target) {
    set_supported_for_test(0);
    if (target != 0) set_supported_for_test(target);
}

std::vector<int64_t> available_targets() {
    set_supported_for_test(0);
    return hwy::SupportedAndGeneratedTargets();
}

std::string target_name(int64_t target) { return hwy::TargetName(target); }

std::string current_target_name() {
    const int64_t t = supported() & HWY_TARGETS;
    return t == 0 ? std::string("none") : hwy::TargetName(t & -t);
}

}  // namespace polyvol::simd
