// core/aes_round.hpp — private: one round of AES encryption (the x86
// AESENC instruction, Highway's AESRound) in portable C++: the scalar twin
// for the Highway target that has no AESRound (HWY_SCALAR), so that a hash
// built of AES rounds has one value on every target (tests/core compare it
// with the instruction).
//
// Conventions (FIPS-197, as AESENC): the state is 16 bytes, column-major
// (byte 4c + r is row r of column c); one round is SubBytes, ShiftRows,
// MixColumns, then the round key added (xor).
#pragma once

#include <array>
#include <cstdint>

namespace polyvol::core {

// a · b in GF(2^8) modulo x^8 + x^4 + x^3 + x + 1 (0x11B).
constexpr uint8_t gf_mul(uint8_t a, uint8_t b) {
    uint8_t p = 0;
    for (int i = 0; i < 8; ++i) {
        if ((b & 1) != 0) p = static_cast<uint8_t>(p ^ a);
        const bool carry = (a & 0x80) != 0;
        a = static_cast<uint8_t>(a << 1);
        if (carry) a = static_cast<uint8_t>(a ^ 0x1B);
        b = static_cast<uint8_t>(b >> 1);
    }
    return p;
}

// The S-box: s(x) = A x^-1 + 0x63 (x^-1 = x^254, 0 for 0), A the affine map
// b_i ^ b_{i+4} ^ b_{i+5} ^ b_{i+6} ^ b_{i+7} (indices mod 8).
constexpr std::array<uint8_t, 256> aes_sbox() {
    std::array<uint8_t, 256> s{};
    for (int x = 0; x < 256; ++x) {
        uint8_t inv = 1, base = static_cast<uint8_t>(x);
        for (int e = 254; e > 0; e >>= 1) {  // x^254 by squaring
            if ((e & 1) != 0) inv = gf_mul(inv, base);
            base = gf_mul(base, base);
        }
        if (x == 0) inv = 0;
        uint8_t out = 0x63;
        for (int r = 0; r < 5; ++r)
            out = static_cast<uint8_t>(out ^ static_cast<uint8_t>((inv << r) | (inv >> (8 - r))));
        s[static_cast<std::size_t>(x)] = out;
    }
    return s;
}
inline constexpr std::array<uint8_t, 256> kAesSbox = aes_sbox();

// state <- MixColumns(ShiftRows(SubBytes(state))) ^ key. MixColumns takes a
// column (a0, a1, a2, a3) to the product with the circulant (2 3 1 1).
inline void aes_round(uint8_t state[16], const uint8_t key[16]) {
    uint8_t t[16];
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) t[4 * c + r] = kAesSbox[state[(4 * (c + r) + r) % 16]];  // row r shifted left by r
    for (int c = 0; c < 4; ++c) {
        const uint8_t* a = &t[4 * c];
        for (int r = 0; r < 4; ++r)
            state[4 * c + r] = static_cast<uint8_t>(gf_mul(2, a[r]) ^ gf_mul(3, a[(r + 1) % 4]) ^ a[(r + 2) % 4] ^
                                                    a[(r + 3) % 4] ^ key[4 * c + r]);
    }
}

}  // namespace polyvol::core
