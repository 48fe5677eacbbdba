// Private to measure: certified summation shared by the double-precision
// formulas (prism, pyramid, vtnb, fan area, edge length). Each kernel adds
// its computed terms with a per-term error bound; finish() returns the sum and
// a rigorous bound on its distance from the exact sum of the exact terms.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "exact/eft.hpp"
#include "measure/methods.hpp"

namespace polyvol::measure::certified {

// Model: fl(a op b) = (a op b)(1+δ), |δ| <= u = 2^-53 (round to nearest, no
// FMA contraction: the build passes -ffp-contract=off), plus an absolute error
// <= 2^-1075 when a product or quotient underflows (sums never do).
//
// A kernel calls add(t_i, e_i) for every computed term t_i, where e_i is its
// bound on |t_i - τ_i| (τ_i the exact term on the given doubles), evaluated
// in floating point from computed, non-negative magnitudes with upper-bounded
// constants (gam()). Such an expression of sums, products and quotients of
// positive numbers, each operand within a factor (1+θ_j) of its exact value,
// is itself within (1+θ_J) of its exact value with J <= 256 for every kernel
// here (Higham, Accuracy and Stability, Lemma 3.3; the longest, vtnb's, needs
// about 100), so
//   Σ exact e_i <= (1 + γ_{2J}) · (1 + γ_N) · err <= (1 + γ_{N+512}) err.
// Underflow while evaluating e_i loses at most a few 2^-1075 absolutely,
// covered by the allowance below.
// Terms are added with Knuth's two_sum (Sum2 of Ogita, Rump & Oishi 2005, also
// across the parallel merges): s + Σ(errors) == Σ t_i exactly, and with
// N = 3n + 2 >= the number of additions on any path from a term to the result
// (n leaf two_sums, at most n - 1 merges with two additions each),
//   |fl(s + c) - Σ t_i| <= (u |fl(s+c)| + (1+u) γ_N² Σ|t_i|) / (1 - u),
//   Σ|t_i| <= (1 + γ_N) · abs     (abs: plain sum of |t_i|, any order).
// Then value = fl(±σ / d):  |value - (±σ/d)| <= u |value| / (1-u) + 2^-1075.
// Everything in the bound itself is computed with up() after every
// operation, which gives an upper bound of the exact expression.

inline constexpr double kU = 0x1p-53;
inline constexpr double kOnePlus2U = 1 + 0x1p-52;  // >= 1 + u, representable

inline double up(double x) { return std::nextafter(x, std::numeric_limits<double>::infinity()); }
// An upper bound of γ_k (rigorous; k u < 1/2).
inline double gamma_up(double k) { return up(up(k * kU) / std::nextafter(1.0 - k * kU, 0.0)); }
// γ_k <= k u (1 + 2 k u) for k u <= 1/2: for per-term expressions (within J).
constexpr double gam(double k) { return k * kU * (1 + 2 * k * kU); }

struct Acc {
    double s = 0;      // running two_sum sum
    double c = 0;      // sum of two_sum errors
    double abs = 0;    // Σ |t_i|
    double err = 0;    // Σ e_i
    double aux = 0;    // max per-term magnitude (underflow allowance)
    uint64_t n = 0;    // terms added
    uint64_t units = 0;  // underflow units (kernel-specific count)

    void add(double t, double e) {
        double lo;
        exact::two_sum(s, t, s, lo);
        c += lo;
        abs += std::fabs(t);
        err += e;
        ++n;
    }
    void merge(const Acc& o) {
        double lo;
        exact::two_sum(s, o.s, s, lo);
        c = (c + o.c) + lo;
        abs += o.abs;
        err += o.err;
        aux = std::max(aux, o.aux);
        n += o.n;
        units += o.units;
    }
};

// value = sign · fl(s + c) / divisor and its bound (see above); the
// underflow allowance is units · 2^-1060 · (1 + aux)^power.
inline SumWithBound finish(const Acc& a, double divisor, int power, double sign = 1.0) {
    const double sigma = a.s + a.c;
    SumWithBound r;
    r.value = sign * (divisor == 1.0 ? sigma : sigma / divisor) + 0.0;  // + 0.0: no -0.0
    const double nn = 3.0 * static_cast<double>(a.n) + 2.0;
    const double gN = gamma_up(nn);
    const double sum_abs = up(a.abs * up(1 + gN));
    const double sum_err =
        up(up(up(kU * std::fabs(sigma)) + up(up(up(kOnePlus2U * gN) * gN) * sum_abs)) / (1 - kU));
    const double term_err = up(a.err * up(1 + gamma_up(nn + 512)));
    double amp = 1;
    for (int i = 0; i < power; ++i) amp = up(amp * up(1 + a.aux));
    const double allowance = up(up(static_cast<double>(a.units) * 0x1p-1060) * amp);
    double bound = up(up(sum_err + term_err) + allowance);
    if (divisor != 1.0) {
        bound = up(up(bound / divisor) + up(up(kU * std::fabs(r.value)) / (1 - kU)));
        bound = up(bound + 0x1p-1074);
    }
    if (!std::isfinite(r.value) || !std::isfinite(bound))
        bound = std::numeric_limits<double>::infinity();
    r.error_bound = bound;
    return r;
}

// Deterministic parallel reduction over 0..count-1 in fixed blocks: the
// same input gives the same bits for any number of threads.
inline constexpr std::size_t kGrain = 2048;
template <class A, class Body>
A reduce(std::size_t count, const Body& body) {
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, count, kGrain), A{},
        [&](const tbb::blocked_range<std::size_t>& range, A acc) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) body(i, acc);
            return acc;
        },
        [](A x, const A& y) {
            x.merge(y);
            return x;
        });
}

}  // namespace polyvol::measure::certified
