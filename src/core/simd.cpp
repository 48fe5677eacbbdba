// core/simd.cpp — the instruction sets the kernels may use: the CPU's, from
// CPUID (what each of Highway's targets needs, and that the OS saves the
// registers), capped by limit_to.
#include "core/simd.hpp"

#include "core/hwy_targets.hpp"  // before Highway

#include <hwy/highway.h>

#include <atomic>
#include <cstdlib>
#include <string_view>

#if HWY_ARCH_X86
#include <cpuid.h>
#elif HWY_ARCH_ARM_A64 && defined(__linux__)
#include <asm/hwcap.h>
#include <sys/auxv.h>
#endif

namespace polyvol::simd {

namespace {

struct Cpu {
    Level level = Level::scalar;
    bool ifma_vaes = false;
};

#if HWY_ARCH_X86
bool bit(unsigned reg, int b) { return (reg >> b & 1u) != 0; }

// XCR0: which register states the OS saves (0 when it has no XSAVE).
uint64_t xcr0(bool osxsave) {
    if (!osxsave) return 0;
    unsigned lo = 0, hi = 0;
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    return (static_cast<uint64_t>(hi) << 32) | lo;
}

// Highway's x86 targets need: SSE4 = SSE3, SSSE3, SSE4.1, SSE4.2, POPCNT,
// PCLMUL, AES;
// AVX2 = that and AVX, AVX2, BMI, BMI2, FMA, F16C (and the OS saving the
// AVX state); AVX3 = that and AVX-512 F, VL, DQ, BW (and the OS saving the
// AVX-512 state).
Cpu detect() {
    Cpu cpu;
    unsigned a = 0, b1 = 0, c1 = 0, d1 = 0;
    if (__get_cpuid(1, &a, &b1, &c1, &d1) == 0) return cpu;
    unsigned b7 = 0, c7 = 0, d7 = 0;
    if (__get_cpuid_count(7, 0, &a, &b7, &c7, &d7) == 0) b7 = c7 = 0;
    const uint64_t xcr = xcr0(bit(c1, 27));
    const bool sse4 = bit(c1, 0) && bit(c1, 9) && bit(c1, 19) && bit(c1, 20) && bit(c1, 23) && bit(c1, 1) &&
                      bit(c1, 25);
    const bool avx2 = sse4 && (xcr & 0x6) == 0x6 && bit(c1, 28) && bit(b7, 5) && bit(b7, 3) && bit(b7, 8) &&
                      bit(c1, 12) && bit(c1, 29);
    const bool avx512 = avx2 && (xcr & 0xE6) == 0xE6 && bit(b7, 16) && bit(b7, 31) && bit(b7, 17) && bit(b7, 30);
    cpu.level = avx512 ? Level::avx512 : avx2 ? Level::avx2 : sse4 ? Level::sse4 : Level::scalar;
    cpu.ifma_vaes = avx512 && bit(b7, 21) && bit(c7, 9);
    return cpu;
}
#elif HWY_ARCH_ARM_A64 && defined(__linux__)
// NEON is part of AArch64; Highway's NEON target is compiled with +crypto,
// so it also needs the AES instructions, which some cores lack.
Cpu detect() { return Cpu{(getauxval(AT_HWCAP) & HWCAP_AES) != 0 ? Level::sse4 : Level::scalar, false}; }
#else
Cpu detect() { return Cpu{}; }
#endif

const Cpu& cpu() {
    static const Cpu c = detect();
    return c;
}

// The limit from POLYVOL_MAX_ISA (scalar, sse4, avx2 or avx512), or none.
int environment_limit() {
    const char* v = std::getenv("POLYVOL_MAX_ISA");
    const std::string_view name(v == nullptr ? "" : v);
    const Level l = name == "scalar" ? Level::scalar
                    : name == "sse4" ? Level::sse4
                    : name == "avx2" ? Level::avx2
                                     : Level::avx512;
    return static_cast<int>(l);
}

// The limit (limit_to), as a Level's number; -1 until the first level()
// reads POLYVOL_MAX_ISA (constant-initialised: also right during other
// files' static initialisation).
constinit std::atomic<int> g_limit{-1};

int limit() {
    int l = g_limit.load(std::memory_order_relaxed);
    if (l < 0) {
        int unset = -1;
        l = environment_limit();
        if (!g_limit.compare_exchange_strong(unset, l, std::memory_order_relaxed)) l = unset;
    }
    return l;
}

// The levels compiled in (HWY_TARGETS of core/hwy_targets.hpp).
bool compiled(Level l) {
    switch (l) {
        case Level::scalar: return (HWY_TARGETS & (HWY_SCALAR | HWY_EMU128)) != 0;
#if HWY_ARCH_X86
        case Level::sse4: return (HWY_TARGETS & HWY_SSE4) != 0;
        case Level::avx2: return (HWY_TARGETS & HWY_AVX2) != 0;
        case Level::avx512: return (HWY_TARGETS & HWY_AVX3) != 0;
#elif HWY_ARCH_ARM_A64
        case Level::sse4: return (HWY_TARGETS & HWY_NEON) != 0;
        default: return false;
#else
        default: return false;
#endif
    }
    return false;
}

}  // namespace

Level level() {
    const int cap = limit();
    const int has = static_cast<int>(cpu().level);
    return static_cast<Level>(has < cap ? has : cap);
}

bool has_avx512_ifma_vaes() { return cpu().ifma_vaes && level() == Level::avx512; }

void limit_to(Level l) { g_limit.store(static_cast<int>(l), std::memory_order_relaxed); }

std::vector<Level> available_levels() {
    std::vector<Level> out;
    for (int l = static_cast<int>(cpu().level); l >= 0; --l)
        if (compiled(static_cast<Level>(l))) out.push_back(static_cast<Level>(l));
    return out;
}

std::string level_name(Level l) {
    switch (l) {
        case Level::avx512: return "AVX3";
        case Level::avx2: return "AVX2";
#if HWY_ARCH_ARM_A64
        case Level::sse4: return "NEON";
#else
        case Level::sse4: return "SSE4";
#endif
        case Level::scalar: break;
    }
    return (HWY_TARGETS & HWY_EMU128) != 0 ? "EMU128" : "SCALAR";  // HWY_CHOOSE_FALLBACK's
}

}  // namespace polyvol::simd
