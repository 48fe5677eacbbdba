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

// ---- per-term pieces with stated error bounds --------------------------

// |(x, y, z)| with relative error <= γ5 (squares of the components, two
// additions, a square root): directly when the largest component is in
// [2^-500, 2^500] (the squares then cannot overflow and lose nothing that
// matters to underflow), else after an exact scaling by a power of two.
// NaN for non-finite input.
inline double norm3(double x, double y, double z) {
    const double m = std::max(std::max(std::fabs(x), std::fabs(y)), std::fabs(z));
    if (m > 0x1p-500 && m < 0x1p500) return std::sqrt((x * x + y * y) + z * z);
    if (m == 0) return 0;
    if (!std::isfinite(m) || x != x || y != y || z != z) return std::numeric_limits<double>::quiet_NaN();
    int e = 0;
    std::frexp(m, &e);
    const double xs = std::ldexp(x, -e), ys = std::ldexp(y, -e), zs = std::ldexp(z, -e);
    return std::ldexp(std::sqrt((xs * xs + ys * ys) + zs * zs), e);
}

// The cross product a × b as computed, n_x = fl(fl(a_y b_z) - fl(a_z b_y))
// and so on, with X = Σ |products| (six of them). With a, b rounded
// differences of exact points (each component within (1+δ) of the exact
// one), every component of n is off by <= γ4 (|p*| + |q*|), its two exact
// products, so |n - n*|_2 <= |n - n*|_1 <= γ4 X*; underflowing products add
// <= 6 · 2^-1075.
struct BoundedCross {
    double n[3];
    double X;
};
inline BoundedCross bounded_cross(const double a[3], const double b[3]) {
    const double px = a[1] * b[2], qx = a[2] * b[1];
    const double py = a[2] * b[0], qy = a[0] * b[2];
    const double pz = a[0] * b[1], qz = a[1] * b[0];
    return {{px - qx, py - qy, pz - qz},
            ((std::fabs(px) + std::fabs(qx)) + (std::fabs(py) + std::fabs(qy))) + (std::fabs(pz) + std::fabs(qz))};
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

// reduce() over the fan triangles (p0, p_i, p_i+1) of every face with at
// least 3 vertices (the fan of mesh.hpp), face by face: body(a, b, c, acc)
// gets pointers to the three vertices' x, y, z.
template <class A, class Body>
A reduce_fan(const MeshView& mesh, const Body& body) {
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    return reduce<A>(mesh.face_count(), [&](std::size_t f, A& acc) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) return;
        const uint32_t* v = idx + mesh.face_begin(f);
        const double* p0 = pos + 3 * std::size_t{v[0]};
        for (std::size_t i = 1; i + 1 < k; ++i)
            body(p0, pos + 3 * std::size_t{v[i]}, pos + 3 * std::size_t{v[i + 1]}, acc);
    });
}

}  // namespace polyvol::measure::certified
