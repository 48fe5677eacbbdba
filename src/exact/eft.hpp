// exact/eft.hpp — error-free transformations of doubles and a minimal
// double-double ("dd") type.
//
// Sources:
//   T. J. Dekker, "A floating-point technique for extending the available
//     precision", Numer. Math. 18 (1971) — fast_two_sum, split, two_prod.
//   D. E. Knuth, TAOCP vol. 2, 4.2.2 — two_sum.
//   J.-M. Muller et al., Handbook of Floating-Point Arithmetic (2nd ed.), 4.3–4.4.
//
// Every function here is exact — its results (s, e) satisfy s + e == the
// exact result — under these conditions, which callers must guarantee:
//   * IEEE-754 binary64, round to nearest even, and no FMA contraction of the
//     expressions below (the build passes -ffp-contract=off; std::fma is
//     called explicitly where a fused multiply-add is meant);
//   * no overflow;
//   * for two_prod: the exact error a*b - fl(a*b) is representable, which holds
//     when the lowest set bits of a and b have exponents summing to >= -1074
//     (then every value involved is a multiple of 2^-1074). polyvol's exact
//     kernels guarantee this by checking the coordinate range up front.
#pragma once

#include <cmath>

namespace polyvol::exact {

#if defined(__GNUC__)
#define POLYVOL_INLINE [[gnu::always_inline]] inline
#else
#define POLYVOL_INLINE inline
#endif

// The safe range of the exact kernels' coordinates: 0 or 2^-160 <= |x| <=
// 2^190. With every coordinate in it, every product of up to five
// coordinates and every intermediate value is a multiple of 2^-1060 below
// 2^1000, so the transformations below are exact on them (the condition
// "checking the coordinate range up front" above).
inline constexpr double kSafeMin = 0x1p-160, kSafeMax = 0x1p190;
inline bool in_safe_range(double x) {
    const double a = std::fabs(x);
    return a == 0 || (a >= kSafeMin && a <= kSafeMax);  // false for NaN
}

// s + e == a + b exactly, |e| <= ulp(s)/2 (Knuth; no condition on a, b).
POLYVOL_INLINE void two_sum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bb = s - a;
    e = (a - (s - bb)) + (b - bb);
}

// two_sum in every element of a GCC vector of doubles (vector_size): the
// same operations element by element, so each lane gets two_sum's bits.
template <class V>
POLYVOL_INLINE void two_sum_lanes(const V& a, const V& b, V& s, V& e) {
    s = a + b;
    const V bb = s - a;
    e = (a - (s - bb)) + (b - bb);
}

// s + e == a + b exactly, provided a == 0 or exponent(a) >= exponent(b)
// (e.g. |a| >= |b|) (Dekker).
POLYVOL_INLINE void fast_two_sum(double a, double b, double& s, double& e) {
    s = a + b;
    e = b - (s - a);
}

// p + e == a * b exactly (needs a hardware FMA to be fast: std::fma is a
// library call on targets compiled without one — see two_prod_dekker).
POLYVOL_INLINE void two_prod(double a, double b, double& p, double& e) {
    p = a * b;
    e = std::fma(a, b, -p);
}

// Veltkamp's split: hi + lo == a, each fitting in 26 bits (|a| < 2^996).
POLYVOL_INLINE void split(double a, double& hi, double& lo) {
    const double c = 134217729.0 * a;  // 2^27 + 1
    hi = c - (c - a);
    lo = a - hi;
}

// p + e == a * b exactly without an FMA (Dekker), for |a|, |b| < 2^996.
POLYVOL_INLINE void two_prod_dekker(double a, double b, double& p, double& e) {
    p = a * b;
    double ah, al, bh, bl;
    split(a, ah, al);
    split(b, bh, bl);
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

// two_prod with the FMA chosen at compile time: kernels are instantiated
// twice (with a hardware FMA and without) and dispatched at run time.
template <bool kFma>
POLYVOL_INLINE void two_prod_t(double a, double b, double& p, double& e) {
    if constexpr (kFma) {
        two_prod(a, b, p, e);
    } else {
        two_prod_dekker(a, b, p, e);
    }
}

// A double-double: the unevaluated sum hi + lo. Operations below are not
// error-free; their error bounds are stated where they are used (see
// measure/cone.hpp), in terms of magnitudes of the operands.
struct DD {
    double hi = 0;
    double lo = 0;
};

// Renormalise (exact): returns (s, e) with s + e == x.hi + x.lo, |e| <= ulp(s)/2.
POLYVOL_INLINE DD renormalize(DD x) {
    DD r;
    two_sum(x.hi, x.lo, r.hi, r.lo);
    return r;
}

// "Sloppy" double-double addition: error <= 3.01 u^2 (|x.hi| + |y.hi|) for
// normalised x, y (u = 2^-53); result renormalised exactly.
POLYVOL_INLINE DD dd_add(DD x, DD y) {
    double s, e;
    two_sum(x.hi, y.hi, s, e);
    const double l = e + (x.lo + y.lo);
    DD r;
    two_sum(s, l, r.hi, r.lo);
    return r;
}

// Product of double-doubles, dropping x.lo*y.lo:
// error <= (|x.hi| |y.lo| + |x.lo| |y.hi|) u + |x.lo y.lo| + 2u |fl(lo terms)| ...
// (bounded where used). Result is not renormalised.
template <bool kFma>
POLYVOL_INLINE DD dd_mul(DD x, DD y) {
    double p, e;
    two_prod_t<kFma>(x.hi, y.hi, p, e);
    DD r;
    r.hi = p;
    r.lo = e + (x.hi * y.lo + x.lo * y.hi);
    return r;
}

}  // namespace polyvol::exact
