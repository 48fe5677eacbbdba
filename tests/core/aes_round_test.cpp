// core/aes_round.hpp, the scalar twin of AESENC: FIPS-197's S-box values,
// and the instruction's bits on random states and keys.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>

#include "core/aes_round.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace polyvol::core {
namespace {

TEST(AesRound, TheSboxIsFips197s) {
    // FIPS-197, figure 7: s(0x00) = 0x63, s(0x01) = 0x7c, s(0x53) = 0xed, s(0xff) = 0x16.
    EXPECT_EQ(kAesSbox[0x00], 0x63);
    EXPECT_EQ(kAesSbox[0x01], 0x7c);
    EXPECT_EQ(kAesSbox[0x53], 0xed);
    EXPECT_EQ(kAesSbox[0xff], 0x16);
    bool seen[256] = {};
    for (const uint8_t s : kAesSbox) seen[s] = true;  // a permutation
    for (const bool b : seen) EXPECT_TRUE(b);
}

#if defined(__x86_64__) || defined(__i386__)
__attribute__((target("sse2,aes"))) void aesenc(uint8_t state[16], const uint8_t key[16]) {
    const __m128i s = _mm_loadu_si128(reinterpret_cast<const __m128i*>(state));
    const __m128i k = _mm_loadu_si128(reinterpret_cast<const __m128i*>(key));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(state), _mm_aesenc_si128(s, k));
}

TEST(AesRound, GivesTheInstructionsBits) {
    if (!__builtin_cpu_supports("aes")) GTEST_SKIP() << "no AES-NI on this CPU";
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 10000; ++trial) {
        uint8_t state[16], key[16];
        for (int i = 0; i < 16; ++i) {
            state[i] = static_cast<uint8_t>(rng());
            key[i] = static_cast<uint8_t>(rng());
        }
        uint8_t twin[16], native[16];
        std::memcpy(twin, state, 16);
        std::memcpy(native, state, 16);
        aes_round(twin, key);
        aesenc(native, key);
        ASSERT_EQ(std::memcmp(twin, native, 16), 0) << "trial " << trial;
    }
}
#endif

}  // namespace
}  // namespace polyvol::core
