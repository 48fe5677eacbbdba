// exact/exact_sum.cpp — carry propagation and correctly rounded conversion
// of the superaccumulator (see exact_sum.hpp for the representation).
#include "exact/exact_sum.hpp"
#include "core/bit_cast.hpp"

#include <bit>
#include <cmath>
#include <limits>

namespace polyvol::exact {

__extension__ typedef unsigned __int128 u128;

void ExactSum::add_special(double x) {
    if (std::isnan(x)) {
        specials_ |= kNan;
    } else {
        specials_ |= x > 0 ? kPosInf : kNegInf;
    }
}

void ExactSum::normalize() {
    for (int k = 0; k + 1 < kChunks; ++k) {
        const int64_t carry = chunk_[k] >> 32;  // floor division (arithmetic shift)
        chunk_[k] &= int64_t{0xFFFFFFFF};
        chunk_[k + 1] += carry;
    }
    adds_left_ = kAddsPerCarry;
}

void ExactSum::merge(const ExactSum& other) {
    ExactSum o = other;
    o.normalize();
    normalize();
    // Both in [0, 2^32) below the top: the sums stay far from overflow.
    for (int k = 0; k < kChunks; ++k) chunk_[k] += o.chunk_[k];
    specials_ |= o.specials_;
    normalize();
}

void ExactSum::subtract(const ExactSum& other) {
    ExactSum o = other;
    o.normalize();
    normalize();
    for (int k = 0; k < kChunks; ++k) chunk_[k] -= o.chunk_[k];
    // -inf of other is +inf here and vice versa.
    uint8_t s = o.specials_ & kNan;
    if (o.specials_ & kPosInf) s |= kNegInf;
    if (o.specials_ & kNegInf) s |= kPosInf;
    specials_ |= s;
    normalize();
}

int ExactSum::sign() const {
    ExactSum t = *this;
    t.normalize();
    if (t.chunk_[kChunks - 1] != 0) return t.chunk_[kChunks - 1] > 0 ? 1 : -1;
    for (int k = kChunks - 2; k >= 0; --k)
        if (t.chunk_[k] != 0) return 1;
    return 0;
}

double round_digits(const uint64_t* digits, int count, int unit_exponent, bool sticky, bool negative) {
    int t = count - 1;
    while (t >= 0 && digits[t] == 0) --t;
    const double zero = negative ? -0.0 : 0.0;
    if (t < 0) return zero;  // |value| < 2^unit_exponent, callers keep that far below 2^-1075
    auto digit = [&](int i) -> u128 { return i >= 0 ? digits[i] : 0; };
    // A window of three digits holding the leading one.
    const u128 w = (digit(t) << 64) | (digit(t - 1) << 32) | digit(t - 2);
    for (int i = t - 3; i >= 0 && !sticky; --i) sticky = digits[i] != 0;
    const int base = 32 * (t - 2) + unit_exponent;  // exponent of w's bit 0
    const auto whi = static_cast<uint64_t>(w >> 64);
    const int nb = 64 + (64 - std::countl_zero(whi));  // bit length of w (>= 65)
    const int lead = nb - 1 + base;                    // value in [2^lead, 2^(lead+1))
    int ulp_exp = lead - 52;
    if (ulp_exp < -1074) ulp_exp = -1074;  // subnormal result
    const int sh = ulp_exp - base;         // bits of w below the result's ulp (>= 12)
    if (sh > 96) return zero;              // w < 2^96 <= half an ulp of 2^-1074
    const u128 one = 1;
    const auto q = static_cast<uint64_t>(w >> sh);  // <= 2^53
    const u128 rem = w & ((one << sh) - 1);
    const u128 half = one << (sh - 1);
    const bool up = rem > half || (rem == half && (sticky || (q & 1u) != 0));
    const double mag = std::ldexp(static_cast<double>(q + (up ? 1u : 0u)), ulp_exp);  // exact or ±inf
    return negative ? -mag : mag;
}

double ExactSum::round_div(uint32_t divisor) const {
    if (specials_ != 0) {
        if ((specials_ & kNan) || ((specials_ & kPosInf) && (specials_ & kNegInf)))
            return std::numeric_limits<double>::quiet_NaN();
        return (specials_ & kPosInf) ? std::numeric_limits<double>::infinity()
                                     : -std::numeric_limits<double>::infinity();
    }
    ExactSum t = *this;
    t.normalize();
    const bool negative = t.chunk_[kChunks - 1] < 0;
    if (negative) {
        for (int k = 0; k < kChunks; ++k) t.chunk_[k] = -t.chunk_[k];
        t.normalize();
    }
    // Magnitude as base-2^32 digits, scaled by 2^64 so that the quotient keeps
    // 64 bits below 2^-1074 and the remainder only acts as a sticky bit.
    constexpr int n = kChunks + 3;
    uint64_t w[n] = {};
    for (int k = 0; k + 1 < kChunks; ++k) w[k + 2] = static_cast<uint64_t>(t.chunk_[k]);
    const auto top = static_cast<uint64_t>(t.chunk_[kChunks - 1]);
    w[kChunks + 1] = top & 0xFFFFFFFFu;
    w[kChunks + 2] = top >> 32;
    uint64_t rem = 0;
    if (divisor != 1) {
        for (int i = n - 1; i >= 0; --i) {
            const uint64_t cur = (rem << 32) | w[i];  // < divisor * 2^32
            w[i] = cur / divisor;
            rem = cur % divisor;
        }
    }
    return round_digits(w, n, kUnitExponent - 64, rem != 0, negative);
}

std::optional<double> decided_round_div(const ExactSum& sum, double bound, uint32_t divisor) {
    if (bound == 0) return sum.round_div(divisor);
    ExactSum lo = sum, hi = sum;
    lo.add(-bound);
    hi.add(bound);
    const double a = lo.round_div(divisor), b = hi.round_div(divisor);
    if (core::bit_cast<uint64_t>(a) != core::bit_cast<uint64_t>(b)) return std::nullopt;
    return a;
}

}  // namespace polyvol::exact
