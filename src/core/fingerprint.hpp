// core/fingerprint.hpp — private: the closedness fingerprint
// (polyvol/soup.hpp explains it and bounds its error): its arithmetic,
// shared by the streamed soup's pass-1 kernel (measure/soup_pass1.cpp) and
// by the pass over a mesh (core/fingerprint.cpp), which serves topology's
// fingerprint_closedness (polyvol/topology.hpp) and measure's vtnb. It sits
// in core, below both: topology measures each shell's volume, and measure
// asks whether a surface is closed.
//
// Arithmetic mod p = 2^31 - 1 in 64-bit words, reduced lazily (2^31 ≡ 1):
// differences are formed as x + p - y (<= 2p < 2^32), products (< 2^64)
// folded as (x mod 2^31) + (x >> 31).
#pragma once

#include <cstdint>
#include <random>

#include "polyvol/mesh.hpp"

namespace polyvol::core::fingerprint {

constexpr uint64_t kP = (uint64_t{1} << 31) - 1;  // the fingerprint field F_p
constexpr int kLanes = 4;                         // independent lanes (four 31-bit hash words)

[[gnu::always_inline]] inline uint64_t fold(uint64_t x) { return (x & kP) + (x >> 31); }  // ≡ x (mod p)

// (hb - ha)(hc - ha)(hc - hb) mod p as a value < 2^34 congruent to it (h* <= p):
// the triangle's sum over its directed edges x→y of H(x) H(y)^2 - H(x)^2 H(y).
[[gnu::always_inline]] inline uint64_t vandermonde(uint64_t ha, uint64_t hb, uint64_t hc) {
    const uint64_t d1 = hb + kP - ha, d2 = hc + kP - ha, d3 = hc + kP - hb;  // <= 2p < 2^32
    const uint64_t x = fold(fold(d1 * d2));                                  // < 2^31 + 8
    return fold(x * d3);                                                     // < 2^31 + 2^33
}

[[gnu::always_inline]] inline uint64_t reduce(uint64_t x) {  // x mod p
    x = fold(fold(x));
    return x >= kP ? x - kP : x;
}

// mum's product from four 32 x 32 -> 64 bit products: the same bits, for
// WebAssembly, which has no 64 x 64 -> 128 bit multiply (there __int128's
// product is a call to __multi3, a 128 x 128 bit product).
[[gnu::always_inline]] inline uint64_t mum_by_halves(uint64_t a, uint64_t b) {
    const uint64_t al = a & 0xFFFFFFFFu, ah = a >> 32, bl = b & 0xFFFFFFFFu, bh = b >> 32;
    const uint64_t ll = al * bl, lh = al * bh, hl = ah * bl, hh = ah * bh;
    const uint64_t mid = (ll >> 32) + (lh & 0xFFFFFFFFu) + (hl & 0xFFFFFFFFu);  // < 3 * 2^32
    const uint64_t lo = mid << 32 | (ll & 0xFFFFFFFFu);
    const uint64_t hi = hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
    return lo ^ hi;
}

// wyhash's multiply-xor: the two halves of the 128-bit product, xored.
[[gnu::always_inline]] inline uint64_t mum(uint64_t a, uint64_t b) {
#if defined(__wasm__)
    return mum_by_halves(a, b);
#else
    __extension__ typedef unsigned __int128 u128;
    const u128 r = static_cast<u128>(a) * b;
    return static_cast<uint64_t>(r) ^ static_cast<uint64_t>(r >> 64);
#endif
}

// A step of SplitMix64: keys derived from a seed (reproducible, for tests).
inline uint64_t splitmix(uint64_t& s) {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// 64 bits from std::random_device (keys no input can be chosen against).
inline uint64_t random_word(std::random_device& rd) { return static_cast<uint64_t>(rd()) << 32 | rd(); }

// Whether the mesh is a closed 2-cycle, by the fingerprint over keyed
// hashes of its points (topology.hpp's fingerprint_closedness says what
// each answer means): keys from std::random_device, or derived from seed.
Closedness mesh_closedness(const MeshView& mesh);
Closedness mesh_closedness(const MeshView& mesh, uint64_t seed);

}  // namespace polyvol::core::fingerprint
