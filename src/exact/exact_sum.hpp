// exact/exact_sum.hpp — an exact accumulator of doubles over the whole
// exponent range (a "superaccumulator").
//
// Source: R. M. Neal, "Fast exact summation using small and large
// superaccumulators", arXiv:1505.05571 (2015) — the small superaccumulator:
// an array of signed 64-bit chunks indexed by exponent, with carries
// propagated lazily.
//
// Representation. A finite double is m * 2^(p - 1074) with an integer
// 0 <= m < 2^53 and 0 <= p <= 2045 (subnormals: p = 0). The accumulator holds
// the exact sum as  Σ_k chunk[k] * 2^(32k - 1074),  k = 0 .. kChunks-1.
// add(x) splits m << (p mod 32) between chunk[p/32] (low 32 bits) and
// chunk[p/32 + 1] (the rest, < 2^53), with x's sign: two integer additions,
// no branches on the data. A chunk changes by < 2^53 per add, so after at
// most kAddsPerCarry adds the carries are propagated (normalize()), which
// brings chunk[0 .. kChunks-2] into [0, 2^32) and leaves the signed rest in
// the top chunk. Sums of up to 2^64 doubles cannot overflow the top chunk.
// Infinities and NaNs are counted apart: the result is then what IEEE
// summation would give (NaN, or the infinity).
//
// Guarantees: add, merge and the conversions are exact; round() returns the
// exact sum rounded once to the nearest double (ties to even, subnormals
// rounded at 2^-1074, overflow to ±inf as IEEE round-to-nearest does);
// round_div(d) the same for sum / d. merge is exact, hence associative and
// commutative: a parallel reduction gives bit-identical results for every
// split of the work.
#pragma once

#include <bit>
#include <cstdint>
#include <optional>
#include <span>
#include "core/bit_cast.hpp"

namespace polyvol::exact {

class ExactSum {
public:
    static constexpr int kChunkBits = 32;
    static constexpr int kChunks = 68;        // 2045 + 53 bits + 64 bits of carry headroom
    static constexpr int kUnitExponent = -1074;  // chunk[0]'s bit 0 is worth 2^-1074
    static constexpr int kAddsPerCarry = 1000;   // 2^32 + 1000 * 2^53 < 2^63

    ExactSum() = default;

    // Adds x exactly.
    void add(double x) {
        const uint64_t bits = core::bit_cast<uint64_t>(x);
        const uint32_t ex = static_cast<uint32_t>(bits >> 52) & 0x7FFu;
        if (ex == 0x7FFu) [[unlikely]] {
            add_special(x);
            return;
        }
        const uint64_t normal = ex != 0 ? 1u : 0u;
        const uint64_t mant = (bits & ((uint64_t{1} << 52) - 1)) | (normal << 52);
        const uint32_t p = ex - static_cast<uint32_t>(normal);  // bit position of m's bit 0
        const uint32_t k = p >> 5;
        const uint32_t sh = p & 31u;
        const int64_t neg = -static_cast<int64_t>(bits >> 63);  // 0 or -1
        const auto lo = static_cast<int64_t>((mant << sh) & 0xFFFFFFFFu);
        const auto hi = static_cast<int64_t>(mant >> (32u - sh));
        chunk_[k] += (lo ^ neg) - neg;
        chunk_[k + 1] += (hi ^ neg) - neg;
        if (--adds_left_ == 0) [[unlikely]] normalize();
    }
    void add(std::span<const double> xs) {
        for (double x : xs) add(x);
    }
    // Adds ±m * 2^exponent exactly, m = Σ limbs[i] 2^(64 i) (n limbs, a
    // magnitude), provided 2^exponent >= 2^-1074 and |m 2^exponent| < 2^1090.
    void add_wide(const uint64_t* limbs, int n, bool negative, int exponent) {
        while (n > 0 && limbs[n - 1] == 0) --n;
        if (n == 0) return;
        const int p = exponent - kUnitExponent;
        const int k0 = p >> 5;
        const int sh = p & 31;
        const int64_t neg = negative ? -1 : 0;
        uint64_t carry = 0;
        for (int i = 0; i < 2 * n + 1 && k0 + i < kChunks; ++i) {
            const uint64_t digit = i < 2 * n ? (limbs[i / 2] >> (32 * (i % 2))) & 0xFFFFFFFFu : 0;
            const uint64_t v = (digit << sh) | carry;
            const auto d = static_cast<int64_t>(v & 0xFFFFFFFFu);
            chunk_[k0 + i] += (d ^ neg) - neg;
            carry = v >> 32;
        }
        if (--adds_left_ == 0) [[unlikely]] normalize();
    }
    // Adds the exact sum held by other.
    void merge(const ExactSum& other);
    // Subtracts: *this -= other (exact).
    void subtract(const ExactSum& other);

    // The exact sum rounded to nearest, ties to even.
    double round() const { return round_div(1); }
    // The exact value of sum / divisor rounded to nearest, ties to even
    // (divisor >= 1). Not round(round(sum) / divisor).
    double round_div(uint32_t divisor) const;

    // -1, 0, +1: the sign of the exact (finite) sum; meaningless unless finite().
    int sign() const;
    bool finite() const { return specials_ == 0; }
    bool has_nan() const { return (specials_ & kNan) != 0; }
    bool has_pos_inf() const { return (specials_ & kPosInf) != 0; }
    bool has_neg_inf() const { return (specials_ & kNegInf) != 0; }

    // Propagates carries: chunk(0 .. kChunks-2) in [0, 2^32), the top chunk
    // signed. Does not change the value.
    void normalize();
    // The chunks (call normalize() first for the canonical form above).
    const int64_t* chunks() const { return chunk_; }

private:
    static constexpr uint8_t kNan = 1, kPosInf = 2, kNegInf = 4;
    void add_special(double x);

    int64_t chunk_[kChunks] = {};
    int adds_left_ = kAddsPerCarry;
    uint8_t specials_ = 0;
};

// The filters' decision: sum approximates an exact value within bound (>= 0);
// when (sum - bound) / divisor and (sum + bound) / divisor round to the same
// double (rounding is monotone), that double is the exact value / divisor
// rounded once; otherwise nothing.
std::optional<double> decided_round_div(const ExactSum& sum, double bound, uint32_t divisor);

// Rounds the non-negative integer Σ digit[i] * 2^(32 i + unit_exponent)
// (digits < 2^32), plus "a little more" when sticky, to the nearest double,
// ties to even. Shared by ExactSum and the GMP conversions.
double round_digits(const uint64_t* digits, int count, int unit_exponent, bool sticky, bool negative);

}  // namespace polyvol::exact
