// core/fingerprint.hpp: mum_by_halves (WebAssembly's multiply-xor) gives
// the bits of the 128-bit product's mum, on edge and random operands.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "core/fingerprint.hpp"

namespace polyvol::core::fingerprint {
namespace {

uint64_t mum_128(uint64_t a, uint64_t b) {
    __extension__ typedef unsigned __int128 u128;
    const u128 r = static_cast<u128>(a) * b;
    return static_cast<uint64_t>(r) ^ static_cast<uint64_t>(r >> 64);
}

TEST(Mum, ByHalvesIsTheProductsMum) {
    const uint64_t edges[] = {0, 1, 2, 0xFFFFFFFFu, 0x100000000u, 0xFFFFFFFFFFFFFFFFu, 0x8000000000000000u,
                              0x9E3779B97F4A7C15u, 0xFFFFFFFF00000001u};
    for (uint64_t a : edges)
        for (uint64_t b : edges) EXPECT_EQ(mum_by_halves(a, b), mum_128(a, b)) << a << " " << b;
    EXPECT_EQ(mum_by_halves(0xFFFFFFFFFFFFFFFFu, 0xFFFFFFFFFFFFFFFFu), 0xFFFFFFFFFFFFFFFEu ^ 1u);  // (2^64-1)^2
    std::mt19937_64 rng(20261130);
    for (int i = 0; i < 100000; ++i) {
        const uint64_t a = rng(), b = rng();
        ASSERT_EQ(mum_by_halves(a, b), mum_128(a, b)) << a << " " << b;
        ASSERT_EQ(mum(a, b), mum_128(a, b));
    }
}

}  // namespace
}  // namespace polyvol::core::fingerprint
